// insitu/runtime/output_folder.h - checks, before step 1, that every folder the run will write to
// exists or can be created and is writable, so that a typo or a read-only mount is one clear
// error at start-up instead of a failed write hours later.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/config.h"

namespace voxspan {

// Creates folder (and its parents) when missing, then proves it writable by creating and
// removing a probe file. Throws voxspan::Error "cannot use <what> <path>: <why>" (what:
// "outputs.png folder", "output_folder").
// Returns the folders it made, deepest first.
std::vector<std::filesystem::path> prepare_output_folder(const std::filesystem::path& folder,
                                                         std::string_view what);

// prepare_output_folder for the folder of every enabled output; returns the folders made,
// each before its parents.
std::vector<std::filesystem::path> prepare_output_folders(const Config& config);

// A run's hold on its output folder, so that two runs never write into one (their stats lines
// spliced, their series lists each missing the other's files): a file `.voxspan.lock` in it
// holding the run's process id and host, locked (flock) until the run's finish() or end and
// removed then.
class FolderLock {
 public:
  // Throws voxspan::Error naming the folder and the holder when another run holds it, and the
  // key (`output_folder`, `outputs.png.folder`) to give each run its own.
  FolderLock(const std::filesystem::path& folder, std::string_view key);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

// Removes those of `made` that are empty (a run that failed before writing a file leaves
// nothing behind; one that wrote keeps its folders).
void remove_empty_folders(const std::vector<std::filesystem::path>& made);

}  // namespace voxspan
