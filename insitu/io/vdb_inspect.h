// insitu/io/vdb_inspect.h - what is in a .vdb file, and a picture of its level set, for the
// snapshot inspector (tools/inspect_snapshot) and the tests. OpenVDB stays in the .cpp.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/outputs/formats/png_image.h"

namespace voxspan {

struct VdbGridSummary {
  std::string name;
  std::string value_type;  // "float", "vec3s", "int32"...
  std::string grid_class;  // "level set", "fog volume", "unknown"...
  std::array<double, 3> voxel_size{0, 0, 0};
  std::uint64_t active_voxels = 0;
  std::array<int, 3> index_min{0, 0, 0}, index_max{0, 0, 0};  // active voxels' bounding box
  std::array<double, 3> world_min{0, 0, 0}, world_max{0, 0, 0};
  // Scalar grids: min/max of the active values; vector grids: of their lengths.
  double min_value = 0, max_value = 0;
  double level_set_volume = 0;  // level sets only: enclosed volume, world units cubed
};

struct VdbFileSummary {
  std::vector<VdbGridSummary> grids;
  std::vector<std::pair<std::string, std::string>> metadata;  // file-level, as text
};

// Throws voxspan::Error naming the file when it cannot be opened.
VdbFileSummary inspect_vdb(const std::filesystem::path& path);

struct LevelSetView {
  std::string grid;  // empty: the first level set in the file
  int width = 640, height = 480;
  std::array<double, 3> direction{-1, 2, -0.8};  // the camera looks along this
  std::array<double, 3> up{0, 0, 1};
  double fov_degrees = 40;
};

// Ray-traces the level set (OpenVDB's own ray tracer, diffuse shading) from a camera that
// frames its bounding box. Throws voxspan::Error if the file has no such level set.
ImageRGBA8 render_level_set(const std::filesystem::path& path, const LevelSetView& view = {});

}  // namespace voxspan
