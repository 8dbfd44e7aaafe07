// inspect_snapshot: what is in a .vdb snapshot (its grids, their type, voxel size, active
// voxels, bounding box and value range; the file's metadata), and optionally a picture of its
// level set made with OpenVDB's own ray tracer.
//
//   inspect_snapshot FILE.vdb [--png OUT.png] [--grid NAME] [--size WxH]
//                    [--direction X,Y,Z] [--up X,Y,Z]
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "insitu/io/vdb_inspect.h"
#include "insitu/outputs/formats/png_image.h"
#include "voxspan/error.h"

namespace {

const char* kUsage =
    "usage: inspect_snapshot FILE.vdb [--png OUT.png] [--grid NAME] [--size WxH]\n"
    "                        [--direction X,Y,Z] [--up X,Y,Z]\n"
    "Lists the grids of an OpenVDB file and their statistics; with --png, ray-traces its\n"
    "level set (the first one, or --grid NAME) into a picture.\n";

std::array<double, 3> parse_vec3(const std::string& flag, const std::string& text) {
  std::array<double, 3> v{};
  char c1 = 0, c2 = 0;
  std::istringstream s(text);
  if (!(s >> v[0] >> c1 >> v[1] >> c2 >> v[2]) || c1 != ',' || c2 != ',' || !s.eof())
    throw voxspan::make_error(flag, " expects three numbers X,Y,Z; got \"", text, "\"");
  return v;
}

std::string vec3_text(const std::array<double, 3>& v) {
  std::ostringstream s;
  s.precision(5);
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string file, png;
    voxspan::LevelSetView view;
    for (int i = 1; i < argc; ++i) {
      std::string arg = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw voxspan::make_error(arg, " needs a value");
        return argv[++i];
      };
      if (arg == "-h" || arg == "--help") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--png") {
        png = value();
      } else if (arg == "--grid") {
        view.grid = value();
      } else if (arg == "--size") {
        std::string s = value();
        char x = 0;
        std::istringstream in(s);
        if (!(in >> view.width >> x >> view.height) || x != 'x' || !in.eof() || view.width <= 0 ||
            view.height <= 0 || view.width > 16384 || view.height > 16384)
          throw voxspan::make_error("--size expects WxH, e.g. 800x600; got \"", s, "\"");
      } else if (arg == "--direction") {
        view.direction = parse_vec3(arg, value());
      } else if (arg == "--up") {
        view.up = parse_vec3(arg, value());
      } else if (!arg.empty() && arg[0] == '-') {
        throw voxspan::make_error("unknown option ", arg, "\n", kUsage);
      } else if (file.empty()) {
        file = arg;
      } else {
        throw voxspan::make_error("one file at a time (got ", file, " and ", arg, ")");
      }
    }
    if (file.empty()) throw voxspan::make_error("no file given\n", kUsage);

    voxspan::VdbFileSummary summary = voxspan::inspect_vdb(file);
    std::cout << "file " << file << "\n";
    for (const auto& [key, value] : summary.metadata)
      std::cout << "  " << key << ": " << value << "\n";
    std::cout << summary.grids.size() << (summary.grids.size() == 1 ? " grid\n" : " grids\n");
    for (const voxspan::VdbGridSummary& g : summary.grids) {
      std::cout << "grid \"" << g.name << "\"\n"
                << "  type          " << g.value_type << " (" << g.grid_class << ")\n"
                << "  voxel size    " << vec3_text(g.voxel_size) << "\n"
                << "  active voxels " << g.active_voxels << "\n";
      if (g.active_voxels > 0) {
        std::cout << "  index bbox    [" << g.index_min[0] << ", " << g.index_min[1] << ", "
                  << g.index_min[2] << "] .. [" << g.index_max[0] << ", " << g.index_max[1] << ", "
                  << g.index_max[2] << "]\n"
                  << "  world bbox    " << vec3_text(g.world_min) << " .. "
                  << vec3_text(g.world_max) << "\n"
                  << "  value range   " << g.min_value << " .. " << g.max_value
                  << (g.value_type.rfind("vec3", 0) == 0 ? " (lengths)" : "") << "\n";
        if (g.grid_class == "Level Set")
          std::cout << "  volume        " << g.level_set_volume << " (inside the zero level set)\n";
      }
    }
    if (!png.empty()) {
      voxspan::write_png(png, voxspan::render_level_set(file, view));
      std::cout << "picture " << png << " (" << view.width << "x" << view.height << ")\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "inspect_snapshot: error: " << e.what() << "\n";
    return 1;
  }
}
