// insitu/runtime/output_folder.h - checks, before step 1, that every folder the run will write to
// exists or can be created and is writable, so that a typo or a read-only mount is one clear
// error at start-up instead of a failed write hours later.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "insitu/config/config.h"

namespace voxspan {

// Creates folder (and its parents) when missing, then proves it writable by creating and
// removing a probe file. Throws voxspan::Error "cannot use <what> folder <path>: <why>".
void prepare_output_folder(const std::filesystem::path& folder, std::string_view what);

// prepare_output_folder for the folder of every enabled output; returns them.
std::vector<std::filesystem::path> prepare_output_folders(const Config& config);

}  // namespace voxspan
