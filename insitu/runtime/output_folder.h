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
// Returns the folders it made, deepest first.
std::vector<std::filesystem::path> prepare_output_folder(const std::filesystem::path& folder,
                                                         std::string_view what);

// prepare_output_folder for the folder of every enabled output; returns the folders made,
// each before its parents.
std::vector<std::filesystem::path> prepare_output_folders(const Config& config);

// Removes those of `made` that are empty (a run that failed before writing a file leaves
// nothing behind; one that wrote keeps its folders).
void remove_empty_folders(const std::vector<std::filesystem::path>& made);

}  // namespace voxspan
