// bench_live: what the live page (insitu/live/) costs the solver's thread on a render step, with
// each renderer (docs/benchmarks.md, "The live page").
//
// Two adapters on the same dam break particles (the solver does not move: every step the same
// work), one without the live page and one with it (its server listening on a free port of
// 127.0.0.1, no client), stepped in turn, a render step each time. Per renderer it prints:
//   - the solver's thread's time in handing a step to the page (PipelineTotals::seconds_live:
//     the references and numbers put in its mailbox), mean and most;
//   - the median of process() per step without and with the page, and their difference: the
//     whole cost on the solver's thread, the page's own thread (PNG encoding) on the same
//     cores included.
//
//   bench_live [--particles N] [--steps S] [--size WxH] [--renderer cpu|gl|both]
// Defaults: 20000 particles, 200 render steps each, 960x540, both renderers.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tools/common/dambreak_views.h"
#include "tools/common/usage.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"

namespace {

struct Options {
  std::size_t particles = 20000;
  long steps = 200;
  int width = 960, height = 540;
  std::vector<std::string> renderers = {"cpu", "gl"};
};

std::string config(const Options& o, const std::string& renderer, const std::string& folder,
                   bool live) {
  return "output_folder: " + folder +
         "\ntrigger: {every_steps: 1}\nrenderer: {backend: " + renderer +
         "}\nviews: [{name: main, width: " + std::to_string(o.width) +
         ", height: " + std::to_string(o.height) +
         "}]\noutputs: {png: {enabled: false}, stats: {enabled: false}}\n" +
         (live ? "live: {enabled: true}\n" : "");
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

const voxspan::InsituPipeline& pipeline(const voxspan::Adapter& a) {
  return dynamic_cast<const voxspan::InsituPipeline&>(*a.pipeline());
}

void run(const Options& o, const std::string& renderer) {
  dambreak::Config dc;
  dc.particles = o.particles;
  dambreak::DamBreak sim(dc);
  voxspan::AdapterOptions ao;
  ao.classify.particle_spacing = sim.dx();
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("bench_live_" + renderer);
  voxspan::Adapter without = voxspan::adapter_from_config_text(
      config(o, renderer, (folder / "without").string(), false), ao, "without.yaml");
  voxspan::Adapter with = voxspan::adapter_from_config_text(
      config(o, renderer, (folder / "with").string(), true), ao, "with.yaml");
  const auto particles = voxspan::tools::fluid_view(sim.fluid());
  const auto grid = voxspan::tools::fluid_grid(sim);
  std::vector<double> ms_without, ms_with;
  auto step = [&](voxspan::Adapter& a, std::int64_t s, std::vector<double>& out) {
    const double before = pipeline(a).totals().seconds_process;
    if (!a.execute(s, 1e-4 * double(s), particles, grid).ok()) throw voxspan::Error("step failed");
    out.push_back(1e3 * (pipeline(a).totals().seconds_process - before));
  };
  double most_live_ms = 0;
  for (long s = 1; s <= o.steps + 10; ++s) {
    const double live_before = pipeline(with).totals().seconds_live;
    step(without, s, ms_without);
    step(with, s, ms_with);
    if (s > 10)
      most_live_ms =
          std::max(most_live_ms, 1e3 * (pipeline(with).totals().seconds_live - live_before));
  }
  ms_without.erase(ms_without.begin(), ms_without.begin() + 10);  // warm-up
  ms_with.erase(ms_with.begin(), ms_with.begin() + 10);
  const voxspan::PipelineTotals t = pipeline(with).totals();
  const double without_ms = median(ms_without), with_ms = median(ms_with);
  std::printf(
      "%-4s %zu particles, %dx%d, %ld render steps each: handing a step to the page "
      "%.2f us mean, %.2f us most; process() median %.3f ms without, %.3f ms with "
      "(%+.3f ms)\n",
      renderer.c_str(), sim.fluid().size(), o.width, o.height, o.steps,
      1e6 * t.seconds_live / double(t.render_steps), 1e3 * most_live_ms, without_ms, with_ms,
      with_ms - without_ms);
  std::filesystem::remove_all(folder);
}

}  // namespace

constexpr const char* kUsage =
    "usage: bench_live [--particles N] [--steps S] [--size WxH] [--renderer cpu|gl|both]\n"
    "  the live page's cost on the solver's thread per render step, without and with it\n";

int main(int argc, char** argv) {
  if (voxspan::tools::asks_for_help(argc, argv)) return voxspan::tools::print_usage(stdout, kUsage);
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--particles" && i + 1 < argc) o.particles = std::stoul(argv[++i]);
    else if (a == "--steps" && i + 1 < argc) o.steps = std::stol(argv[++i]);
    else if (a == "--size" && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &o.width, &o.height);
    else if (a == "--renderer" && i + 1 < argc) {
      const std::string r = argv[++i];
      o.renderers =
          r == "both" ? std::vector<std::string>{"cpu", "gl"} : std::vector<std::string>{r};
    } else {
      return voxspan::tools::print_usage(stderr, kUsage);
    }
  }
  try {
    for (const std::string& r : o.renderers) run(o, r);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_live: %s\n", e.what());
    return 1;
  }
  return 0;
}
