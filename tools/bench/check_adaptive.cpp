// check_adaptive: adaptive sampling under an error tolerance ([HOK16]; `views[i].adaptive`)
// over a whole dam-break run (docs/benchmarks.md, "Volume views"). The WCSPH solver
// (examples/dambreak) runs from the column's release with volume views of one field, one at the
// full rate and one per (tolerance, relax), all automatically framed alike, rendered every
// --every steps through the runtime for --frames render steps; each adaptive picture is held
// against the full-rate one of its step.
//   - relax 0 is a guarantee: a channel off by more than the tolerance (plus 1e-6 for float
//     rounding) is a bug; the tool prints where and exits 1 (3 when relax 0 skipped no sample
//     at all, or with --renderer gl when a frame was drawn on the CPU past llvmpipe's loop
//     budget: then nothing, or not the GL march, was checked).
//   - relax > 0 trades the guarantee for speed: the tool prints [HOK16]'s Table 3 for it, the
//     share of rays (pixels) and of frames over the tolerance and the largest error.
// Each view's mean render time over the run and its speed-up over the full rate's follow (the
// views render one after the other in each step, under the same load).
//   - --converged S adds a full-rate view sampled S times as densely along the rays, the
//     stand-in for the converged integral (DVR's error halves with each doubling of the sampling:
//     docs/benchmarks.md, "Sampling against error"): the full rate's and each adaptive view's
//     largest and mean error against it, so that what adaptivity adds is seen beside the
//     sampling's own error.
//
//   check_adaptive [--particles N] [--tank-length L] [--frames F] [--every K] [--size WxH]
//                  [--tolerances E,...] [--relax R,...] [--quantity NAME] [--converged S]
//                  [--renderer gl|cpu]
// Defaults: 20000 particles, the main job's 3a tank, 1000 render steps every 3 solver steps,
// 320x180, tolerances 0.001, 0.004, 0.01, relax 0 and 1, the speed (`velocity`), the CPU
// renderer (`renderer.backend`; gl: the GL volume march, llvmpipe included).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tools/common/dambreak_views.h"
#include "tools/common/picture_change.h"
#include "tools/common/tool_args.h"
#include "tools/common/usage.h"
#include "voxspan/insitu.h"

namespace {

struct Options {
  std::size_t particles = 20000;
  double tank_length = 3;
  long frames = 1000;
  long every = 3;
  int width = 320, height = 180;
  std::vector<double> tolerances = {0.001, 0.004, 0.01};
  std::vector<double> relaxes = {0, 1};
  std::string quantity = "velocity";
  double converged = 0;  // the converged stand-in's sampling; 0: none
  std::string renderer = "cpu";
};

// How far one view's pictures lie from the converged stand-in's over the run (the worst channel
// of each pixel).
struct Deviation {
  double largest = 0, sum = 0;
  long long rays = 0;
  void add(const voxspan::FloatImage& picture, const voxspan::FloatImage& converged);
  double mean() const { return sum / double(std::max(1LL, rays)); }
};

// One adaptive view's tally over the run.
struct Tally {
  double tolerance = 0, relax = 0;
  long long rays = 0, rays_over = 0;  // pixels compared, pixels with a channel past
  long frames_over = 0;
  double largest = 0;
  double ms = 0;                       // the view's render time, summed over the run
  long long samples = 0, skipped = 0;  // composited and skipped samples, summed
  Deviation from_converged;
};

std::vector<double> numbers(const char* text) {
  std::vector<double> out;
  for (const std::string& item : voxspan::tools::comma_list(text))
    out.push_back(std::atof(item.c_str()));
  return out;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (v == nullptr) return false;
    if (a == "--particles") o.particles = std::size_t(std::atof(v));
    else if (a == "--tank-length") o.tank_length = std::atof(v);
    else if (a == "--frames") o.frames = std::atol(v);
    else if (a == "--every") o.every = std::atol(v);
    else if (a == "--size") {
      if (!voxspan::tools::parse_size(v, o.width, o.height)) return false;
    } else if (a == "--tolerances") o.tolerances = numbers(v);
    else if (a == "--relax") o.relaxes = numbers(v);
    else if (a == "--quantity") o.quantity = v;
    else if (a == "--converged") o.converged = std::atof(v);
    else if (a == "--renderer") o.renderer = v;
    else return false;
    ++i;
  }
  const auto in_unit = [](double e) { return e >= 0 && e <= 1; };
  return (o.renderer == "cpu" || o.renderer == "gl") && o.particles > 0 && o.frames > 0 &&
         o.every > 0 && o.width > 0 && o.height > 0 &&
         std::all_of(o.tolerances.begin(), o.tolerances.end(),
                     [](double e) { return e > 0 && e <= 1; }) &&
         std::all_of(o.relaxes.begin(), o.relaxes.end(), in_unit) &&
         (o.converged == 0 || (o.converged >= 1 && o.converged <= 16));
}

// The views: `full` first, then one per (tolerance, relax) in the tallies' order, then the
// converged stand-in if asked.
std::string config_text(const Options& o, const std::vector<Tally>& tallies) {
  const std::string common = "kind: volume, width: " + std::to_string(o.width) +
                             ", height: " + std::to_string(o.height) + ", quantity: " + o.quantity +
                             ", caption: '', legend: false";
  std::string text = "output_folder: " +
                     (std::filesystem::temp_directory_path() / "voxspan-check-adaptive").string() +
                     "\nlog_level: warning\noutputs: {png: {enabled: false}, stats: {enabled: "
                     "false}}\nrenderer: {backend: " +
                     o.renderer + "}\ntrigger: {every_steps: " + std::to_string(o.every) +
                     "}\nviews:\n  - {name: full, " + common + "}\n";
  for (std::size_t k = 0; k < tallies.size(); ++k)
    text += "  - {name: adaptive" + std::to_string(k) + ", " + common +
            ", adaptive: {error_tolerance: " + std::to_string(tallies[k].tolerance) +
            ", relax: " + std::to_string(tallies[k].relax) + "}}\n";
  if (o.converged > 0)
    text +=
        "  - {name: converged, " + common + ", sampling: " + std::to_string(o.converged) + "}\n";
  return text;
}

using voxspan::tools::fluid_grid;
using voxspan::tools::fluid_view;
using voxspan::tools::kToleranceSlack;
using voxspan::tools::worst_channel;

void Deviation::add(const voxspan::FloatImage& picture, const voxspan::FloatImage& converged) {
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x) {
      const double e = worst_channel(picture, converged, x, y);
      largest = std::max(largest, e);
      sum += e;
      ++rays;
    }
}

// Adds one step's adaptive picture against its full-rate one; prints a relax-0 violation.
void tally(const voxspan::FloatImage& full, const voxspan::FloatImage& adaptive, long step,
           Tally& t) {
  bool frame_over = false;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) {
      const double worst = worst_channel(full, adaptive, x, y);
      t.largest = std::max(t.largest, worst);
      ++t.rays;
      if (worst <= t.tolerance + kToleranceSlack) continue;
      ++t.rays_over;
      frame_over = true;
      if (t.relax == 0 && t.rays_over <= 5)
        std::printf("VIOLATION tolerance %g relax 0: step %ld pixel (%d, %d) off by %.3e\n",
                    t.tolerance, step, x, y, worst);
    }
  t.frames_over += frame_over;
}

int run(const Options& o) {
  std::vector<Tally> tallies;
  for (double relax : o.relaxes)
    for (double tolerance : o.tolerances) {
      Tally& t = tallies.emplace_back();
      t.tolerance = tolerance, t.relax = relax;
    }
  dambreak::Config scene;
  scene.particles = o.particles;
  scene.tank_length = o.tank_length;
  dambreak::DamBreak sim(scene);
  voxspan::AdapterOptions options;
  options.classify.particle_spacing = sim.dx();
  voxspan::Adapter adapter = voxspan::adapter_from_config_text(config_text(o, tallies), options);
  auto& pipeline = dynamic_cast<voxspan::InsituPipeline&>(*adapter.pipeline());
  pipeline.keep_linear_pictures();  // the renderers' floats, not the GL renderer's 8-bit sRGB
  std::printf(
      "dam break: %zu fluid particles; %zu adaptive views of %s at %dx%d against the "
      "full rate, %ld render steps every %ld steps, %s renderer\n",
      sim.fluid().size(), tallies.size(), o.quantity.c_str(), o.width, o.height, o.frames, o.every,
      o.renderer.c_str());
  long frames = 0;
  double full_ms = 0;
  Deviation full_from_converged;
  // GL: the views' frames drawn by the CPU caster (past llvmpipe's loop budget), not checked on GL.
  long long on_cpu = 0;
  while (frames < o.frames) {
    sim.step();
    const long step = long(sim.steps());
    const voxspan::Status s =
        adapter.execute(step, sim.time(), fluid_view(sim.fluid()), fluid_grid(sim));
    if (!s.ok()) {
      std::fprintf(stderr, "check_adaptive: step %ld: %s\n", step, s.message.c_str());
      return 2;
    }
    if (step % o.every != 0) continue;
    const auto views = pipeline.latest_views();
    full_ms += views[0].stats->total_ms();
    const voxspan::FloatImage* converged = o.converged > 0 ? views.back().picture : nullptr;
    if (converged != nullptr) full_from_converged.add(*views[0].picture, *converged);
    for (const auto& v : views) on_cpu += v.stats->count("volume.gl_frames_on_cpu");
    for (std::size_t k = 0; k < tallies.size(); ++k) {
      tally(*views[0].picture, *views[k + 1].picture, step, tallies[k]);
      if (converged != nullptr) tallies[k].from_converged.add(*views[k + 1].picture, *converged);
      const voxspan::FrameStats& stats = *views[k + 1].stats;
      tallies[k].ms += stats.total_ms();
      tallies[k].samples += stats.count("volume.samples");
      tallies[k].skipped += stats.count("volume.samples_skipped");
    }
    if (++frames % 100 == 0)
      std::printf("  %ld render steps (step %ld, T %.2f)\n", frames, step,
                  sim.nondimensional_time());
  }
  if (o.renderer == "gl")
    std::printf("\nGL frames drawn on the CPU (past llvmpipe's loop budget): %lld of %zu\n", on_cpu,
                std::size_t(frames) * (tallies.size() + 1));
  std::printf("\nfull rate: %.1f ms a frame\n%9s %5s | %12s %14s %12s %10s | %8s %8s %8s\n",
              full_ms / double(frames), "tolerance", "relax", "rays over", "share of rays",
              "frames over", "largest", "ms", "speed-up", "skipped");
  bool violated = false;
  long long skipped_at_relax_0 = 0;
  for (const Tally& t : tallies) {
    std::printf("%9g %5g | %12lld %13.5f%% %6ld/%-5ld %10.3e | %8.1f %8.2f %7.1f%%\n", t.tolerance,
                t.relax, t.rays_over, 100.0 * double(t.rays_over) / double(std::max(1LL, t.rays)),
                t.frames_over, frames, t.largest, t.ms / double(frames), full_ms / t.ms,
                100.0 * double(t.skipped) / double(std::max(1LL, t.samples + t.skipped)));
    violated = violated || (t.relax == 0 && t.rays_over > 0);
    if (t.relax == 0) skipped_at_relax_0 += t.skipped;
  }
  if (o.converged > 0) {
    std::printf(
        "\nagainst the full rate sampled %g times as densely (worst channel per pixel)\n"
        "%9s %5s | %10s %10s\n%15s | %10.3e %10.3e\n",
        o.converged, "tolerance", "relax", "largest", "mean", "full rate",
        full_from_converged.largest, full_from_converged.mean());
    for (const Tally& t : tallies)
      std::printf("%9g %5g | %10.3e %10.3e\n", t.tolerance, t.relax, t.from_converged.largest,
                  t.from_converged.mean());
  }
  if (!violated && on_cpu > 0) {
    std::printf("check_adaptive: frames drawn on the CPU: not the GL march's; fewer particles\n");
    return 3;
  }
  // A guarantee that skipped nothing proved nothing: the scene or the tolerances are wrong.
  if (!violated && skipped_at_relax_0 == 0 &&
      std::any_of(tallies.begin(), tallies.end(), [](const Tally& t) { return t.relax == 0; })) {
    std::printf("check_adaptive: relax 0 skipped no sample: nothing was checked\n");
    return 3;
  }
  return violated ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  constexpr char kUsage[] =
      "usage: check_adaptive [--particles N] [--tank-length L] [--frames F] [--every K]\n"
      "         [--size WxH] [--tolerances E,...] [--relax R,...] [--quantity NAME]\n"
      "         [--converged S] [--renderer gl|cpu]\n";
  if (voxspan::tools::asks_for_help(argc, argv)) return voxspan::tools::print_usage(stdout, kUsage);
  Options o;
  if (!parse(argc, argv, o)) return voxspan::tools::print_usage(stderr, kUsage);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "check_adaptive: %s\n", e.what());
    return 2;
  }
}
