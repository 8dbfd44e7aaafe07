// render_pictures: renders the dam break in every shading mode ([ZD15] sec. 3.5, 3.6) and
// writes 8-bit sRGB PNGs: the pictures of docs/images/ and the README.
//
// The fluid: the WCSPH dam-break solver of examples/dambreak run to Martin & Moyce's
// T = t sqrt(2 g / a) (--time) with about --particles fluid particles, its state cached in
// --state (reaching the splash takes minutes on two cores); or, with --ritter (or without the
// examples), the Ritter-profile test scene of tools/scenes/scenes.h at t = --time seconds.
// The adapter's classifier (voxspan/classify.h) keeps only the boundary particles, the cell
// states fill the inside. Gap bridging one particle spacing, filter radius 1.5 spacings.
// --reference also writes the exact CPU reference's pictures (exact spans, Sobel normals).
// --compare DIR compares each picture with DIR's picture of the same name (made by another
// renderer, e.g. an NVIDIA GPU against llvmpipe: tools/scripts/device-check.sh) and prints the PSNR
// and the largest difference.
//
//   render_pictures [--out DIR] [--particles N] [--time T] [--state FILE] [--ritter]
//                   [--size WxH] [--alpha DEG] [--reference] [--compare DIR]
//                   [--platform auto|nvidia|device|surfaceless]
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "insitu/outputs/formats/png_image.h"
#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/renderer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/reference/reference_shading.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/error.h"

namespace {

using namespace voxspan;

struct Args : tools::SceneArgs, tools::StateFlags {
  std::string out = "docs/images";
  bool reference = false;
  std::string compare;  // folder of pictures to compare with; empty: none
};

constexpr char kUsage[] =
    "usage: render_pictures [--out DIR] [--particles N] [--time T] [--state FILE]\n"
    "         [--ritter] [--size WxH] [--alpha DEG] [--reference] [--compare DIR]\n"
    "         [--platform auto|nvidia|device|surfaceless]\n";

// The flags beyond the scene's.
bool read_flag(tools::Arg& arg, Args& a) {
  return arg.value("--out", a.out) || tools::read_state_flag(arg, a) ||
         arg.flag("--reference", a.reference) || arg.value("--compare", a.compare);
}

bool parse(int argc, char** argv, Args& a) {
  return tools::read_args(argc, argv, a, read_flag) && a.particles > 0;
}

struct Picture {
  const char* name;
  ShadeMode mode;
  bool deep_ao;
};

void write(const std::filesystem::path& path, const ImageRGBA8& image) {
  write_png(path, image, false);
  std::printf("wrote %s\n", path.c_str());
}

void write(const std::filesystem::path& path, const FloatImage& image) {
  write(path, linear_to_srgb8(image.rgba, image.width, image.height));
}

// Returns false when the other picture is missing or differs in size.
bool compare(const std::filesystem::path& other, const ImageRGBA8& ours) {
  if (!std::filesystem::exists(other)) {
    std::printf("compare %s: missing\n", other.c_str());
    return false;
  }
  const ImageRGBA8 theirs = read_png(other);
  if (theirs.width != ours.width || theirs.height != ours.height) {
    std::printf("compare %s: %dx%d, ours %dx%d\n", other.c_str(), theirs.width, theirs.height,
                ours.width, ours.height);
    return false;
  }
  const test::ImageDifference d = test::compare_images(ours, theirs);
  std::printf("compare %s: PSNR %.1f dB, largest difference %d/255, mean %.3f/255\n", other.c_str(),
              d.psnr, d.max_levels, d.mean_levels);
  return true;
}

// The look of the pictures, in the scene's own scale (`length`: the column's width).
RenderOptions picture_options(const tools::DamBreakState& s, double alpha) {
  RenderOptions o;
  o.voxelize.grid.alpha_degrees = alpha;
  o.voxelize.gap_bridging = s.spacing;
  o.surfaces.filter_radius = 1.5 * s.spacing;
  ShadeOptions& shade = o.shade;
  shade.material.absorption = glm::dvec3(5.0, 1.8, 0.7) / s.length;
  shade.material.scatter_color = {0.05, 0.16, 0.25};
  shade.environment.up = s.up;
  shade.environment.rest_on_floor(s.ground, s.spacing);
  shade.environment.ground_tile = s.length / 3;
  shade.environment.sun_direction = s.up + glm::dvec3(0.35, -0.3, 0.2);
  shade.ao.radius = 4 * s.spacing;
  return o;
}

int run(const Args& a) {
  gl::Context context(a.context);
  gl::ShaderLibrary shaders;
  Renderer renderer(shaders);

  tools::DamBreakState s = tools::dam_break_state(a, a);
  const Classification& c = s.classification;
  std::printf("%s: %zu surface-shell particles of %zu, %zu inner-full cells\n",
              s.description.c_str(), c.boundary.size(), s.x.size(), c.counts.cells_inner_full);
  s.camera.width = a.width;
  s.camera.height = a.height;
  RenderOptions options = picture_options(s, a.alpha);

  const std::filesystem::path out(a.out);
  bool compared = true;
  std::filesystem::create_directories(out);
  const Picture pictures[] = {{"dambreak_opaque", ShadeMode::opaque, false},
                              {"dambreak_opaque_ao", ShadeMode::opaque, true},
                              {"dambreak_translucent", ShadeMode::translucent, false},
                              {"dambreak_translucent_ao", ShadeMode::translucent, true},
                              {"dambreak_refractive", ShadeMode::refractive, false}};
  for (const Picture& p : pictures) {
    options.shade.mode = p.mode;
    options.shade.deep_ao = p.deep_ao;
    FrameStats stats;
    gl::GpuRecorder recorder(stats, context.has_gpu_timers());
    const FloatImage image =
        renderer.render(s.camera, c.boundary, c.cell_states(), options, recorder).download();
    recorder.collect();
    std::printf("%s: %.0f ms (%s)\n", p.name, stats.total_ms(), stats.json().c_str());
    const ImageRGBA8 picture = linear_to_srgb8(image.rgba, image.width, image.height);
    write(out / (std::string(p.name) + ".png"), picture);
    if (!a.compare.empty())
      compared &=
          compare(std::filesystem::path(a.compare) / (std::string(p.name) + ".png"), picture);
    if (a.reference) {
      const SpanImage spans = exact_spans(renderer.voxelizer().image().grid(), c.boundary,
                                          c.cell_states(), {options.voxelize.gap_bridging, 0});
      write(out / (std::string(p.name) + "_reference.png"),
            reference_shading(spans, options.shade));
    }
  }
  return compared ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("render_pictures", argc, argv, kUsage, parse, run);
}
