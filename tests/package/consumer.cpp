// Compiles only against the installed headers: proves they pull in no GL, VTK or OpenVDB, and
// that the runtime's entry point (voxspan/insitu.h) links and reports a bad config.
#include <voxspan/error.h>
#include <voxspan/insitu.h>
#include <voxspan/log.h>
#include <voxspan/version.h>
#include <voxspan/voxspan.h>

#include <cstdio>
#include <cstring>
#include <string>

int main() {
  voxspan::log_info("consumer linked");
  std::printf("%s\n", voxspan::version());
  if (std::strcmp(voxspan::version(), VOXSPAN_VERSION_STRING) != 0 ||
      std::strcmp(voxspan_version(), VOXSPAN_VERSION_STRING) != 0)
    return 1;
  voxspan::AdapterOptions options;
  options.classify.particle_spacing = 0.01;
  try {
    voxspan::adapter_from_config_text("no_such_key: 1\n", options, "consumer.yaml");
  } catch (const voxspan::Error& e) {
    const bool named =
        std::string(e.what()).find("consumer.yaml:1:1: no_such_key") != std::string::npos;
    std::printf("%s\n", named ? "bad config refused" : e.what());
    return named ? 0 : 1;
  }
  return 1;
}
