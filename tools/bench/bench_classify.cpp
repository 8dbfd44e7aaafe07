// bench_classify - classification and boundary compaction (voxspan/classify.h) on the dam
// break, against the cost of one solver step at the same size.
//
//   bench_classify [--particles N[,N...]] [--steps S] [--repeats R] [--threads P] [--until T]
//
// For each size: builds the dam break (and runs it to Martin & Moyce's T = t sqrt(2g/a) with
// --until, to measure a flowing state with more surface), times S solver steps, then classifies the
// solver's own compact grid R times (the adapter's render-step work, with the velocity and density
// attributes compacted too) and reports the median, the throughput in particles per second,
// and the classification's cost as a fraction of one solver step. The same for the layout
// where the solver shares no grid (the adapter's counting sort). Under each size's row, the
// medians of the classification's phases (voxspan/classify.h's ClassifyPhase) for both layouts.
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sph.h"
#include "tools/common/usage.h"
#include "voxspan/classify.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<std::size_t> parse_sizes(const std::string& text) {
  std::vector<std::size_t> sizes;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || v < 1000) {
      std::fprintf(stderr, "bench_classify: bad particle count '%s' (>= 1000)\n", item.c_str());
      std::exit(2);
    }
    sizes.push_back(std::size_t(v));
  }
  return sizes;
}

struct Timing {
  double seconds = 0, classify = 0, compact = 0;
  std::array<double, voxspan::kClassifyPhaseNames.size()> phase_ms{};  // medians, by phase
  voxspan::ClassifyCounts counts;
};

Timing time_classification(const voxspan::ParticleView& view, const voxspan::GridView& grid,
                           const voxspan::ClassifyOptions& options, int repeats) {
  voxspan::Classifier classifier;
  classifier.run(view, grid, options);  // warm: buffers allocated as in the steady state
  std::vector<double> total, classify, compact;
  std::array<std::vector<double>, voxspan::kClassifyPhaseNames.size()> phases;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    const voxspan::Classification& c = classifier.run(view, grid, options);
    total.push_back(seconds_since(t0));
    classify.push_back(c.seconds_classify);
    compact.push_back(c.seconds_compact);
    for (std::size_t p = 0; p < phases.size(); ++p) phases[p].push_back(c.phase_ms[p]);
  }
  Timing t{median(total), median(classify), median(compact), {}, classifier.result().counts};
  for (std::size_t p = 0; p < phases.size(); ++p) t.phase_ms[p] = median(phases[p]);
  return t;
}

// The phases' medians of one layout, on a line of their own.
void print_phases(const char* layout, const Timing& t) {
  std::printf("%10s %-9s", "", layout);
  for (std::size_t p = 0; p < t.phase_ms.size(); ++p)
    std::printf(" %s %.2f", voxspan::kClassifyPhaseNames[p], t.phase_ms[p]);
  std::printf(" ms\n");
}

constexpr char kUsage[] =
    "usage: bench_classify [--particles N[,N...]] [--steps S] [--repeats R] [--threads P] "
    "[--until T]\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes{1000000, 5000000};
  int steps = 3, repeats = 9, threads = 0;
  double until = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--help" || a == "-h") return voxspan::tools::print_usage(stdout, kUsage);
    if (a == "--particles" && v) sizes = parse_sizes(argv[++i]);
    else if (a == "--steps" && v) steps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--repeats" && v) repeats = std::max(1, std::atoi(argv[++i]));
    else if (a == "--threads" && v) threads = std::max(1, std::atoi(argv[++i]));
    else if (a == "--until" && v) until = std::atof(argv[++i]);
    else return voxspan::tools::print_usage(stderr, kUsage);
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  std::size_t(threads));

  std::printf("%10s %9s %10s %9s %11s %10s %9s %10s %11s %9s\n", "particles", "boundary", "step_ms",
              "class_ms", "classify/s", "of_step", "nogrid_ms", "nogrid/s", "count+cells",
              "compact");
  for (std::size_t n : sizes) {
    dambreak::Config config;
    config.particles = n;
    dambreak::DamBreak sim(config);
    while (sim.nondimensional_time() < until) sim.step();
    std::vector<double> step_seconds;
    for (int s = 0; s < steps; ++s) {
      const auto t0 = Clock::now();
      sim.step();
      step_seconds.push_back(seconds_since(t0));
    }
    const double step = median(step_seconds);

    const dambreak::Fluid& f = sim.fluid();
    const auto view = voxspan::ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                          .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
                          .with_scalar("density", f.rho.data());
    const dambreak::GridShape& shape = sim.fluid_grid().shape();
    const voxspan::GridGeometry geometry{shape.origin, shape.cell_size, shape.dims};
    voxspan::ClassifyOptions options;
    options.particle_spacing = sim.dx();
    options.attributes = {"velocity", "density"};
    const Timing own = time_classification(
        view, voxspan::GridView::offsets(geometry, sim.fluid_grid().offsets().data()), options,
        repeats);
    options.cell_size = shape.cell_size;
    const Timing built = time_classification(view, voxspan::GridView(), options, repeats);

    const double np = double(f.size());
    std::printf("%10zu %8.1f%% %10.1f %9.2f %11.3g %9.2f%% %9.2f %10.3g %8.2f ms %6.2f ms\n",
                f.size(), 100.0 * double(own.counts.boundary) / np, 1e3 * step, 1e3 * own.seconds,
                np / own.seconds, 100 * own.seconds / step, 1e3 * built.seconds, np / built.seconds,
                1e3 * own.classify, 1e3 * own.compact);
    print_phases("own grid:", own);
    print_phases("no grid:", built);
    std::fflush(stdout);
  }
  return 0;
}
