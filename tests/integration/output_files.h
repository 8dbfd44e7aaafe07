// Reading back what a run wrote, with the readers a user would use (libpng, VTK's XML readers,
// OpenVDB), never with the library's own writers' code (tests only).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace voxspan::test {

struct DecodedPng {
  bool ok = false;
  std::string error;
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  // The fraction of pixels that differ by more than `tolerance` (in some channel) from the
  // most common colour of their row: the background of a row (sky or ground) is one colour
  // there, the fluid is not.
  double fraction_unlike_row_background(int tolerance = 12) const;
};
// Decodes the whole file (CRCs, zlib stream, IEND): a truncated file fails.
DecodedPng read_png_file(const std::filesystem::path& path);

// The lines of a text file; `complete` is false when it does not end with a newline.
std::vector<std::string> read_lines(const std::filesystem::path& path, bool* complete = nullptr);

// Names (not paths) of the plain files in a folder, sorted; hidden temporaries included.
std::vector<std::string> files_in(const std::filesystem::path& folder);
// Files anywhere under `root` whose names mark an unfinished write (".tmp.").
std::vector<std::string> temporaries_under(const std::filesystem::path& root);

struct VdbContents {
  bool ok = false;
  std::string error;
  std::vector<std::string> grids;  // names
  std::string fluid_class;         // "level set" for a level set
  double fluid_volume = 0;         // world units^3, inside the zero level set
  std::int64_t step = -1;          // file metadata
};
VdbContents read_vdb(const std::filesystem::path& path);

// True when the file has an <AppendedData> section, which ParaView 5.11's XML reader fails to
// parse with Debian 12's current expat although VTK 9.1's reads it (docs/runtime.md, "ParaView").
bool has_appended_data(const std::filesystem::path& path);

struct VtpContents {
  bool ok = false;
  bool appended_data = false;
  std::int64_t points = 0;
  std::vector<std::string> arrays;  // point-data array names
};
VtpContents read_vtp(const std::filesystem::path& path);

struct VtiContents {
  bool ok = false;
  bool appended_data = false;
  int dims[3] = {0, 0, 0};  // points per axis (cells + 1)
  bool has_state = false;
  std::vector<int> states;  // the "state" cell array
};
VtiContents read_vti(const std::filesystem::path& path);

// The file names a .pvd lists, in order.
std::vector<std::string> pvd_files(const std::filesystem::path& path);

}  // namespace voxspan::test
