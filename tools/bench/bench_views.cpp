// bench_views: the `particles` and `slice` views and a surface's `color_by` through the runtime (an
// Adapter from a YAML config, as a solver runs them), timed per pass from each render step's stats.
// Figures go to docs/benchmarks.md ("Particle glyphs and slices") with the command that produced
// them.
//   1. [GRIBBLE] Table 1: frames per second and particles drawn without culling, with frustum
//      culling and with occlusion culling, on a dense scene (the dam break's column at rest)
//      and a sparse splashing one (the collapsed column with a third of its particles thrown
//      up as droplets), from a camera that sees part of each; the pictures of the three
//      modes compared pixel for pixel.
//   2. Glyphs for 10^5 to 10^7 particles at 640x360 and 1920x1080: glyph_raster, glyph_shade.
//   3. Slices at 1920x1080 for the same counts: slice_sum, slice_draw.
//   4. A surface view's color_by (the CPU renderer, translucent) at 640x360 and 1920x1080 for
//      the same counts: color_sum (the SPH sums at the first hits), color_draw, and the view's
//      shade pass beside them.
// Scenes: the Ritter-profile dam break of tools/scenes/scenes.h, with a made-up speed field
// (the glyphs' colour and the slice's quantity). Medians over --frames render steps after one
// warm-up step. The views run on the CPU with either renderer (docs/runtime.md), so one
// backend is timed.
//
//   bench_views [--counts 1e5,1e6,1e7] [--table-particles N] [--frames N] [--skip-scaling]
//               [--colors-only]
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/scenes.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"

namespace {

using namespace voxspan;

struct Args : tools::SceneArgs {
  std::string counts = "1e5,1e6,1e7";
  double table_particles = 1e6;
  int frames = 3;
  bool skip_scaling = false;
  bool colors_only = false;
};

constexpr char kUsage[] =
    "usage: bench_views [--counts 1e5,1e6,1e7] [--table-particles N] [--frames N]\n"
    "         [--skip-scaling] [--colors-only]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  return arg.value("--counts", a.counts) || arg.value("--table-particles", a.table_particles) ||
         arg.value("--frames", a.frames) || arg.flag("--skip-scaling", a.skip_scaling) ||
         arg.flag("--colors-only", a.colors_only);
}

// A scene's particles, spacing and speed field.
struct Scene {
  std::string name;
  test::Particles particles;
  std::vector<float> speed;
  double spacing = 0;
  glm::dvec3 lo{1e300}, hi{-1e300};
};

Scene dam_break_scene(const char* name, double count, double t, double spray) {
  test::DamBreak shape;
  shape.spacing = test::dam_break_spacing(shape, count);
  shape.radius = shape.spacing;
  shape.spray_fraction = spray;
  Scene s;
  s.name = name;
  s.spacing = shape.spacing;
  s.particles = test::dam_break(shape, t);
  for (const ParticleSphere& p : s.particles) {
    // a made-up speed: faster towards the front and the floor
    s.speed.push_back(float(std::sqrt(2 * 9.81 * std::max(0.0, shape.height - p.y)) * p.x));
    s.lo = glm::min(s.lo, glm::dvec3(p.x, p.y, p.z));
    s.hi = glm::max(s.hi, glm::dvec3(p.x, p.y, p.z));
  }
  return s;
}

// The view's config: a fixed camera on the scene's box from the front-right and above, at
// `distance` box diagonals from its centre.
std::string config(const std::string& view, const Scene& s, int w, int h, double distance) {
  const glm::dvec3 c = 0.5 * (s.lo + s.hi);
  const glm::dvec3 eye =
      c + distance * glm::length(s.hi - s.lo) * glm::normalize(glm::dvec3(0.6, 0.5, 1.0));
  char text[1024];
  std::snprintf(text, sizeof text,
                "output_folder: bench_views_output\n"
                "outputs: {png: {enabled: false}, stats: {enabled: false}}\n"
                "trigger: {every_steps: 1}\n"
                "views:\n  - {name: v, width: %d, height: %d, %s,\n"
                "     camera: {eye: [%.9g, %.9g, %.9g], target: [%.9g, %.9g, %.9g], fov: 40}}\n",
                w, h, view.c_str(), eye.x, eye.y, eye.z, c.x, c.y, c.z);
  return text;
}

struct Timing {
  std::vector<std::pair<std::string, double>> ms;  // median per pass
  std::int64_t drawn = 0;
  FloatImage picture;
  double total() const {
    double t = 0;
    for (const auto& [name, v] : ms) t += v;
    return t;
  }
};

// Runs the view for 1 + frames render steps; the medians of the passes named.
Timing run(const Scene& s, const std::string& yaml, int frames,
           const std::vector<std::string>& passes) {
  AdapterOptions o;
  o.classify.particle_spacing = s.spacing;
  Adapter a = adapter_from_config_text(yaml, o);
  const ParticleView view =
      ParticleView::aos(&s.particles[0].x, s.particles.size(), sizeof(ParticleSphere))
          .with_scalar("speed", s.speed.data());
  std::vector<std::vector<double>> samples(passes.size());
  Timing t;
  for (int step = 0; step <= frames; ++step) {
    const Status status = a.execute(step, step, view);
    if (!status.ok()) throw voxspan::Error(status.message);
    const ViewResult& r = dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
    if (step == 0) continue;  // the warm-up: storage sized
    for (std::size_t p = 0; p < passes.size(); ++p) samples[p].push_back(r.stats->ms(passes[p]));
    t.drawn = r.stats->count("glyphs_drawn");
    t.picture = *r.picture;
  }
  for (std::size_t p = 0; p < passes.size(); ++p)
    t.ms.emplace_back(passes[p], tools::median(samples[p]));
  return t;
}

const std::vector<std::string> kGlyphPasses = {"glyph_raster", "glyph_shade"};
const std::vector<std::string> kSlicePasses = {"slice_sum", "slice_draw"};
const std::vector<std::string> kColorPasses = {"color_sum", "color_draw", "shade"};

void culling_table(const Args& a) {
  std::printf("\n[GRIBBLE] Table 1: %.3g particles, 640x360, camera at 0.6 box diagonals\n",
              a.table_particles);
  std::printf("%-8s %-10s %10s %8s %14s %10s\n", "scene", "culling", "ms", "fps", "drawn",
              "pixels");
  for (const Scene& s : {dam_break_scene("dense", a.table_particles, 0.0, 0.0),
                         dam_break_scene("sparse", a.table_particles, 0.45, 0.33)}) {
    FloatImage first;
    for (const char* culling : {"none", "frustum", "occlusion"}) {
      const std::string view = std::string("kind: particles, color_by: speed, culling: ") + culling;
      const Timing t = run(s, config(view, s, 640, 360, 0.6), a.frames, kGlyphPasses);
      const bool same = first.rgba.empty() || first.rgba == t.picture.rgba;
      if (first.rgba.empty()) first = t.picture;
      std::printf("%-8s %-10s %10.1f %8.1f %14lld %10s\n", s.name.c_str(), culling, t.total(),
                  1000 / t.total(), static_cast<long long>(t.drawn), same ? "identical" : "DIFFER");
    }
  }
}

void scaling(const Args& a) {
  std::printf("\nglyphs (occlusion culling) and slices, per pass, ms (median of %d)\n", a.frames);
  std::printf("%-10s %-10s %-12s %10s %10s %10s %12s\n", "particles", "size", "view", "pass 1",
              "pass 2", "total", "drawn");
  for (const std::string& count : tools::comma_list(a.counts)) {
    const Scene s = dam_break_scene("dense", std::atof(count.c_str()), 0.3, 0.01);
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) {
      const Timing g =
          run(s, config("kind: particles, color_by: speed", s, w, h, 1.0), a.frames, kGlyphPasses);
      std::printf("%-10zu %4dx%-5d %-12s %10.1f %10.1f %10.1f %12lld\n", s.particles.size(), w, h,
                  "particles", g.ms[0].second, g.ms[1].second, g.total(),
                  static_cast<long long>(g.drawn));
    }
    const Timing sl = run(
        s, config("kind: slice, quantity: speed, plane: {normal: [0, 0, 1]}", s, 1920, 1080, 1.0),
        a.frames, kSlicePasses);
    std::printf("%-10zu %4dx%-5d %-12s %10.1f %10.1f %10.1f\n", s.particles.size(), 1920, 1080,
                "slice", sl.ms[0].second, sl.ms[1].second, sl.total());
  }
}

void surface_colors(const Args& a) {
  std::printf("\nsurface color_by (CPU renderer, translucent), ms (median of %d)\n", a.frames);
  std::printf("%-10s %-10s %10s %10s %10s %12s\n", "particles", "size", "color_sum", "color_draw",
              "color_by", "shade");
  for (const std::string& count : tools::comma_list(a.counts)) {
    const Scene s = dam_break_scene("dense", std::atof(count.c_str()), 0.3, 0.01);
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) {
      const Timing t =
          run(s, "renderer: {backend: cpu}\n" + config("color_by: speed", s, w, h, 1.0), a.frames,
              kColorPasses);
      std::printf("%-10zu %4dx%-5d %10.1f %10.1f %10.1f %12.1f\n", s.particles.size(), w, h,
                  t.ms[0].second, t.ms[1].second, t.ms[0].second + t.ms[1].second, t.ms[2].second);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return tools::tool_main<Args>(
      "bench_views", argc, argv, kUsage,
      [](int c, char** v, Args& a) { return tools::read_args(c, v, a, read_flag) && a.frames > 0; },
      [](const Args& a) {
        std::printf("bench_views: the particles and slice views through the runtime (CPU)\n");
        if (!a.colors_only) culling_table(a);
        if (!a.skip_scaling && !a.colors_only) scaling(a);
        surface_colors(a);
        return 0;
      });
}
