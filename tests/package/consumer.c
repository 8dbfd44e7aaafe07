/* A C solver needs only the C header. */
#include <stdio.h>
#include <voxspan/voxspan.h>

int main(void) {
  voxspan_set_log_level(1);
  printf("%s\n", voxspan_version());
  return voxspan_version()[0] == '\0';
}
