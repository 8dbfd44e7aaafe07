/* c_api_client.h - what the C client of the C API test saw. */
#ifndef VOXSPAN_TEST_C_API_CLIENT_H
#define VOXSPAN_TEST_C_API_CLIENT_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct c_api_client_result {
  int status;
  long boundary, cells_full, returned;
  float first_radius;
  int bad_index_status;
  const char* bad_index_message;
} c_api_client_result;

int c_api_client_run(c_api_client_result* out);

#ifdef __cplusplus
}
#endif

#endif
