// insitu/runtime/config_file.h - the config (insitu/config/config.h) with the registered view
// and output kinds: what the adapter, the tools and the tests load.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/config.h"

namespace voxspan {

// Every key at its default: one surface view "main", PNG frames and stats on.
Config default_config();
// A config for rendering particles the caller already has (files, arrays): every call is a
// render step, so the render, PNG and stats triggers become "every step"; the snapshots keep
// their own triggers. `output_folder` replaces the config's when not empty.
Config offline_config(Config config, const std::string& output_folder = {});
// Throws voxspan::Error listing every problem ("<source>:<line>:<col>: <key path>: ...").
Config load_config_file(const std::filesystem::path& path);
Config load_config_string(std::string_view yaml, std::string_view source_name = "<config>");
// The effective configuration as YAML (every key, defaults included); loading it again
// gives the same Config.
std::string to_yaml(const Config& config);
// Every value as "<key path>: <value>" lines (config_lines with the registered kinds).
std::vector<std::string> config_lines(const Config& config);
// The reference tables of every key (docs/runtime.md, "Every key").
std::string config_reference();

}  // namespace voxspan
