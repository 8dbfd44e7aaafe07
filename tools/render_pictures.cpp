// render_pictures: renders the dam break in every shading mode (paper 001, sec. 3.5, 3.6) and
// writes 8-bit sRGB PNGs, the pictures of docs/images/ and the README.
//
// The scene: a water column of about --particles lattice particles collapsing along a tank at
// --time seconds (Ritter's dam-break profile with a little spray: the test scene of
// tests/render/scenes.h), classified into cells of two spacings so that only the boundary shell
// is voxelized, with the cell states filling the inside. Filter radius: one particle spacing.
// --reference also writes the exact CPU reference's pictures (exact spans, Sobel normals).
//
//   render_pictures [--out DIR] [--particles N] [--time T] [--size WxH] [--alpha DEG]
//                   [--reference] [--platform auto|nvidia|device|surfaceless]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/png_image.h"
#include "render/gl/context.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/reference/reference_shading.h"
#include "render/renderer.h"
#include "scene_cell_states.h"
#include "scenes.h"
#include "voxspan/error.h"

namespace {

using namespace voxspan;

struct Args {
  std::string out = "docs/images";
  double particles = 3e5;
  double time = 0.3;
  int width = 960, height = 540;
  double alpha = 14;
  bool reference = false;
  gl::ContextOptions context;
};

int usage(FILE* out) {
  std::fprintf(out,
               "usage: render_pictures [--out DIR] [--particles N] [--time T] [--size WxH]\n"
               "         [--alpha DEG] [--reference] [--platform auto|nvidia|device|surfaceless]\n");
  return out == stdout ? 0 : 2;
}

bool parse(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    const bool has_value = i + 1 < argc;
    if (k == "--out" && has_value) a.out = argv[++i];
    else if (k == "--particles" && has_value) a.particles = std::atof(argv[++i]);
    else if (k == "--time" && has_value) a.time = std::atof(argv[++i]);
    else if (k == "--size" && has_value) {
      if (std::sscanf(argv[++i], "%dx%d", &a.width, &a.height) != 2) return false;
    } else if (k == "--alpha" && has_value) a.alpha = std::atof(argv[++i]);
    else if (k == "--reference") a.reference = true;
    else if (k == "--platform" && has_value) {
      if (!gl::parse_platform(argv[++i], a.context.platform)) return false;
    } else return false;
  }
  return a.width > 0 && a.height > 0 && a.particles > 0;
}

struct Picture {
  const char* name;
  ShadeMode mode;
  bool deep_ao;
};

void write(const std::filesystem::path& path, const FloatImage& image) {
  write_png(path, linear_to_srgb8(image.rgba, image.width, image.height), false);
  std::printf("wrote %s\n", path.c_str());
}

int run(const Args& a) {
  gl::Context context(a.context);
  gl::ShaderLibrary shaders;
  Renderer renderer(shaders);

  test::DamBreak shape;
  shape.spacing = test::dam_break_spacing(shape, a.particles);
  shape.radius = shape.spacing;
  shape.spray_fraction = 0.004;
  const test::Particles all = test::dam_break(shape, a.time);
  test::TestCells cells = test::classify_for_test(all, 2 * shape.spacing, 8);
  std::printf("dam break: %zu particles, %zu in the boundary shell, spacing %.4f\n", all.size(),
              cells.boundary.size(), shape.spacing);

  Camera camera = test::look_at({1.55, 0.75, 1.15}, {0.52, 0.12, 0.12}, a.width, a.height, 40);
  RenderOptions options;
  options.voxelize.grid.alpha_degrees = a.alpha;
  options.voxelize.gap_bridging = shape.spacing;
  options.surfaces.filter_radius = shape.spacing;
  ShadeOptions& shade = options.shade;
  shade.material.absorption = {2.2, 0.7, 0.3};
  shade.material.scatter_color = {0.03, 0.09, 0.13};
  shade.environment.ground_tile = 0.1;
  shade.ao.radius = 4 * shape.spacing;

  const std::filesystem::path out(a.out);
  std::filesystem::create_directories(out);
  const Picture pictures[] = {{"dambreak_opaque", ShadeMode::opaque, false},
                              {"dambreak_opaque_ao", ShadeMode::opaque, true},
                              {"dambreak_translucent", ShadeMode::translucent, false},
                              {"dambreak_translucent_ao", ShadeMode::translucent, true},
                              {"dambreak_refractive", ShadeMode::refractive, false}};
  for (const Picture& p : pictures) {
    shade.mode = p.mode;
    shade.deep_ao = p.deep_ao;
    gl::PassTimer timer(context.has_gpu_timers());
    FrameStats stats;
    const FloatImage image = renderer.render(camera, cells.boundary, cells.view, options, timer, stats).download();
    timer.collect(stats);
    std::printf("%s: %.0f ms on the GPU side (%s)\n", p.name, stats.total_ms(), stats.json().c_str());
    write(out / (std::string(p.name) + ".png"), image);
    if (a.reference) {
      const SpanImage spans = exact_spans(renderer.voxelizer().image().grid(), cells.boundary,
                                          cells.view, {shape.spacing, 0});
      write(out / (std::string(p.name) + "_reference.png"), reference_shading(spans, shade));
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (argc > 1 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) return usage(stdout);
  if (!parse(argc, argv, a)) return usage(stderr);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_pictures: %s\n", e.what());
    return 1;
  }
}
