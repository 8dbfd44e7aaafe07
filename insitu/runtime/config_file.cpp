#include "insitu/runtime/config_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "insitu/runtime/registry.h"
#include "voxspan/error.h"

namespace voxspan {

Config default_config() { return default_config(registered_kinds().config); }

Config offline_config(Config config, const std::string& output_folder) {
  if (!output_folder.empty()) config.output_folder = output_folder;
  const TriggerSpec every{1, 0, true, true};
  config.trigger = config.output("png").trigger = config.output("stats").trigger = every;
  return config;
}

Config load_config_string(std::string_view yaml, std::string_view source_name) {
  return read_config(yaml, source_name, registered_kinds().config);
}

Config load_config_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw make_error("cannot read config file ", path.string(), ": ", std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw make_error("cannot read config file ", path.string());
  return load_config_string(text.str(), path.string());
}

std::string to_yaml(const Config& config) {
  return write_config(config, registered_kinds().config);
}

std::vector<std::string> config_lines(const Config& config) {
  return voxspan::config_lines(config, registered_kinds().config);
}

std::string config_reference() { return voxspan::config_reference(registered_kinds().config); }

}  // namespace voxspan
