// The C API of voxspan/voxspan.h: thin wrappers that never let an exception reach the caller.
#include "voxspan/voxspan.h"

#include "voxspan/log.h"
#include "voxspan/version.h"

extern "C" {

const char* voxspan_version(void) { return voxspan::version(); }

void voxspan_set_log_level(int level) {
  if (level < 0) level = 0;
  if (level > 3) level = 3;
  voxspan::set_log_level(static_cast<voxspan::LogLevel>(level));
}

}  // extern "C"
