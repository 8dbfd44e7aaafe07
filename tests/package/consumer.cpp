// Compiles only against the installed headers: proves they pull in no GL, VTK or OpenVDB.
#include <voxspan/log.h>
#include <voxspan/version.h>
#include <voxspan/voxspan.h>

#include <cstdio>
#include <cstring>

int main() {
  voxspan::log_info("consumer linked");
  std::printf("%s\n", voxspan::version());
  return std::strcmp(voxspan::version(), VOXSPAN_VERSION_STRING) == 0 &&
                 std::strcmp(voxspan_version(), VOXSPAN_VERSION_STRING) == 0
             ? 0
             : 1;
}
