// bench_adaptive: adaptive sampling under an error tolerance ([HOK16];
// render/cpu/volume_adaptive.h) on three scenes in one run, as the paper's Table 2 (time per stage
// and speed-up per tolerance, and its variants) and Table 3 (the largest error, the share of rays
// and the frames past the tolerance). The scenes: the solver's dam break (its height above the
// floor through the view's default transfer function; --time, --particles, cached in --state), a
// radial concentration through a transfer function with a narrow opacity spike, and a 3D
// checkerboard of concentrations 0 and 1 in cubes 5 spacings wide (tools/scenes/adaptive_scenes.h;
// each a block of --side^3 particles). Each scene is drawn from --frames camera angles (turned 30
// degrees apart about its target), every adaptive frame right after the full-rate one of its angle
// (after one warm-up pair).
//
// Rows: the full rate (-); each tolerance (--tolerances) at relax 1 ([HOK16]'s setting) and at
// relax 0 (the guarantee); then at 0.004 and relax 1 the variants (AdaptiveOptions::Rules): no
// greedy step (each cell within the tolerance on its own), z only (no super-pixels), no surface
// rule, super-pixels only (no sparser samples along the rays). Columns: grid (project, sort and
// bin), adapt (the planning: thread-milliseconds over the threads), RC (the march less the
// planning) and total, medians over the angles in milliseconds; speed-ups of RC and total (the
// medians of the pairs' ratios; the full rate's against itself is the machine's noise); the largest
// channel change from the full-rate picture (any channel, alpha included), the largest share of a
// frame's rays past the tolerance (1e-6 of slack) and the frames past it; the share of samples
// skipped and the cells taken coarse and as super-pixels, summed over the angles.
//
//   bench_adaptive [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH] [--frames F]
//                  [--side N] [--tolerances E,...] [--scenes dambreak,radial,checkerboard]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <tbb/info.h>

#include "render/cpu/volume_caster.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/dambreak_volume.h"
#include "tools/common/picture_change.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/adaptive_scenes.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;
using Scene = test::AdaptiveScene;

struct Args : tools::BenchArgs, tools::StateFlags {
  Args() {
    width = 640, height = 360;
    time = 2;
    state = "build/dambreak_state_T2.bin";
  }
  int side = 48;
  std::vector<double> tolerances = {0.001, 0.004, 0.01};
  std::vector<std::string> scenes = {"dambreak", "radial", "checkerboard"};
};

constexpr char kUsage[] =
    "usage: bench_adaptive [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F] [--side N] [--tolerances E,...]\n"
    "         [--scenes dambreak,radial,checkerboard]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--tolerances")) {
    a.tolerances.clear();
    for (const std::string& e : tools::comma_list(v)) a.tolerances.push_back(std::atof(e.c_str()));
    return !a.tolerances.empty() && std::all_of(a.tolerances.begin(), a.tolerances.end(),
                                                [](double e) { return e > 0 && e <= 1; });
  }
  if (const char* v = arg.value("--scenes")) {
    a.scenes = tools::comma_list(v);
    return !a.scenes.empty() && std::all_of(a.scenes.begin(), a.scenes.end(), [](auto& s) {
      return s == "dambreak" || s == "radial" || s == "checkerboard";
    });
  }
  if (arg.value("--side", a.side)) return a.side >= 4;
  return tools::read_state_flag(arg, a) || tools::read_bench_flag(arg, a);
}

bool parse(int argc, char** argv, Args& a) { return tools::read_args(argc, argv, a, read_flag); }

struct Row {
  std::string name;
  AdaptiveOptions adaptive;  // error_tolerance 0: the full rate
};

std::vector<Row> rows(const Args& a) {
  std::vector<Row> out{{"-", {}}};
  for (double relax : {1.0, 0.0})
    for (double e : a.tolerances)
      out.push_back({"relax " + std::to_string(int(relax)), {e, relax}});
  const auto variant = [](const char* name, auto change) {
    AdaptiveOptions o{0.004, 1};
    change(o.rules);
    return Row{name, o};
  };
  using Rules = AdaptiveOptions::Rules;
  out.push_back(variant("no greedy step", [](Rules& r) { r.greedy = false; }));
  out.push_back(variant("z only", [](Rules& r) { r.super_pixels = false; }));
  out.push_back(variant("no surface rule", [](Rules& r) { r.surface_rule = false; }));
  out.push_back(variant("super-pixels only", [](Rules& r) { r.coarse = false; }));
  return out;
}

// One frame's times: grid (project, sort, bin), adapt (planning over the threads), RC (march less
// planning), total.
struct Times {
  double grid = 0, adapt = 0, rc = 0, total = 0;
};
Times run_timed(VolumeCaster& caster, const Scene& scene, const Camera& camera,
                const VolumeOptions& o, VolumeFrame& out, VolumeCounts& counts) {
  std::array<double, kVolumeCastPhaseNames.size()> phase{};
  const Stopwatch watch;
  counts = caster.run(camera, scene.particles, o, out, &phase);
  Times t;
  t.total = watch.ms();
  t.grid = phase[std::size_t(VolumeCastPhase::project)] +
           phase[std::size_t(VolumeCastPhase::sort)] + phase[std::size_t(VolumeCastPhase::bin)];
  t.adapt = counts.planning_ms / double(tbb::info::default_concurrency());
  t.rc = phase[std::size_t(VolumeCastPhase::march)] - t.adapt;
  return t;
}

// The largest channel change of `a` from `b`, and how many pixels have a channel past `tolerance`.
std::pair<double, std::int64_t> change(const FloatImage& a, const FloatImage& b, double tolerance) {
  double largest = 0;
  std::int64_t over = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double d = tools::worst_channel(a, b, x, y);
      largest = std::max(largest, d);
      over += d > tolerance + tools::kToleranceSlack ? 1 : 0;
    }
  return {largest, over};
}

void bench_scene(const Args& a, const Scene& scene) {
  std::printf("\n%s: %zu particles, %dx%d, %d angles\n", scene.name.c_str(), scene.particles.size(),
              a.width, a.height, a.frames);
  std::printf("%-18s %6s | %7s %7s %8s %8s | %6s %6s | %9s %8s %6s | %7s %7s %7s\n", "row", "E_I",
              "grid", "adapt", "RC", "total", "RC x", "tot x", "largest", "rays > E", "frames",
              "skipped", "coarse", "super");
  std::vector<Camera> cameras;
  for (int f = 0; f < a.frames; ++f) cameras.push_back(orbited(scene.camera, 30.0 * f, 0));
  VolumeCaster caster;
  for (const Row& row : rows(a)) {
    VolumeOptions o = scene.options;
    o.adaptive = row.adaptive;
    const VolumeOptions full = scene.options;
    std::vector<double> grid, adapt, rc, total, rc_up, total_up;
    double largest = 0, worst_share = 0;
    int frames_over = 0;
    std::int64_t skipped = 0, samples = 0, coarse = 0, super = 0;
    for (int f = -1; f < a.frames; ++f) {
      const Camera& camera = cameras[std::size_t(std::max(f, 0))];
      VolumeFrame exact, frame;
      VolumeCounts cf, c;
      const Times tf = run_timed(caster, scene, camera, full, exact, cf);
      const Times t = run_timed(caster, scene, camera, o, frame, c);
      if (f < 0) continue;  // the warm-up pair
      grid.push_back(t.grid), adapt.push_back(t.adapt), rc.push_back(t.rc);
      total.push_back(t.total);
      rc_up.push_back(tf.rc / t.rc), total_up.push_back(tf.total / t.total);
      if (row.adaptive.error_tolerance > 0) {
        const auto [d, over] = change(frame.picture, exact.picture, row.adaptive.error_tolerance);
        largest = std::max(largest, d);
        worst_share = std::max(worst_share, 100.0 * double(over) / double(a.width * a.height));
        frames_over += over > 0 ? 1 : 0;
      }
      skipped += c.samples_skipped, samples += c.samples + c.samples_skipped;
      coarse += c.cells_coarse, super += c.cells_super_pixel;
    }
    std::printf("%-18s %6s | %7.1f %7.1f %8.1f %8.1f | %6.2f %6.2f |", row.name.c_str(),
                row.adaptive.error_tolerance > 0
                    ? std::to_string(row.adaptive.error_tolerance).substr(0, 5).c_str()
                    : "-",
                tools::median(grid), tools::median(adapt), tools::median(rc), tools::median(total),
                tools::median(rc_up), tools::median(total_up));
    if (row.adaptive.error_tolerance > 0)
      std::printf(" %9.2e %7.3f%% %3d/%-2d | %6.1f%% %7lld %7lld\n", largest, worst_share,
                  frames_over, a.frames,
                  100.0 * double(skipped) / double(std::max<std::int64_t>(samples, 1)),
                  static_cast<long long>(coarse), static_cast<long long>(super));
    else std::printf(" %9s %8s %6s | %7s %7s %7s\n", "", "", "", "", "", "");
  }
}

int run(const Args& a) {
  std::vector<Scene> scenes;
  for (const std::string& name : a.scenes) {
    if (name == "dambreak") {
      tools::DamBreakState s = tools::dam_break_state(a, a);
      s.camera.width = a.width, s.camera.height = a.height;
      const std::vector<VolumeParticle> p = tools::dam_break_particles(s, true);
      scenes.push_back({s.description + ", height", p, s.camera,
                        tools::dam_break_volume_options(s, p, true, -1, VolumeMode::dvr, 1)});
      continue;
    }
    scenes.push_back(name == "radial" ? test::radial_scene(a.width, a.height, a.side)
                                      : test::checkerboard_scene(a.width, a.height, a.side));
  }
  std::printf(
      "threads %d (adapt: thread-ms over the threads); times in ms, medians over the "
      "angles\n",
      tbb::info::default_concurrency());
  for (const Scene& scene : scenes) bench_scene(a, scene);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_adaptive", argc, argv, kUsage, parse, run);
}
