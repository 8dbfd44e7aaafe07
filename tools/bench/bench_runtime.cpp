// bench_runtime: what the runtime costs the solver. Figures go to docs/benchmarks.md
// ("Runtime"), with the command that produced them.
//   1. the per-step check (Schedule::plan) on steps where nothing is due: the cost of a
//      non-render step; and with triggers on conditions (Schedule::decide), which reduce the
//      particles on every step;
//   2. the writer: submit cost with a full queue (policy drop), throughput of 1 MiB files
//      with and without fsync, PNG frames (encode + write), and an OpenVDB snapshot of a
//      lattice block from its boundary particles.
//
//   bench_runtime [--steps N] [--folder DIR] [--block N] [--keep 1] [--particles N]
// (--keep 1 leaves the files in the folder, e.g. snap.vdb for inspect_snapshot.)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <atomic>
#include <random>
#include <string>
#include <thread>
#include <vector>
#include <unistd.h>

#include "insitu/outputs/formats/png_image.h"
#include "insitu/outputs/formats/vdb_snapshot.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/background_writer.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/schedule.h"
#include "tools/common/usage.h"
#include "tools/scenes/lattice.h"

namespace {

using Clock = std::chrono::steady_clock;
// prefix + n + suffix (written out: GCC 12 warns falsely on chained string +).
std::string numbered(const char* prefix, int n, const char* suffix) {
  std::string s(prefix);
  s.append(std::to_string(n)).append(suffix);
  return s;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The plan of steps where nothing is due, with every output enabled on its own trigger.
void bench_schedule(std::int64_t steps) {
  voxspan::Config config = voxspan::load_config_string(R"(
trigger: {every_steps: 1000000000, every_time: 1.0e9, first: false, last: true}
outputs:
  vdb: {enabled: true, trigger: {every_steps: 1000000000}}
  vtk: {enabled: true, trigger: {every_time: 1.0e9}}
)");
  voxspan::Schedule schedule(config);
  schedule.plan(0, 0);  // the first call starts the triggers
  double time = 0;
  std::int64_t due = 0;
  auto t0 = Clock::now();
  for (std::int64_t step = 1; step <= steps; ++step) {
    time += 1e-4;
    due += schedule.plan(step, time).any();
  }
  double s = seconds_since(t0);
  std::printf("schedule.plan, nothing due    %.2f ns per step (%lld steps, %lld due)\n",
              1e9 * s / double(steps), static_cast<long long>(steps), static_cast<long long>(due));
}

// A step whose conditions are checked and nothing fires: plan and decide, over `n` particles
// of float positions, velocity and pressure (a solver's arrays), on every core.
void bench_conditions(std::size_t n) {
  std::vector<float> x(n), y(n), z(n), v(3 * n), p(n);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = unit(rng), y[i] = unit(rng), z[i] = unit(rng), p[i] = 1000 * unit(rng);
    for (int a = 0; a < 3; ++a) v[3 * i + std::size_t(a)] = unit(rng) - 0.5f;
  }
  const auto particles = voxspan::ParticleView::soa(x.data(), y.data(), z.data(), n)
                             .with_vector("velocity", v.data())
                             .with_scalar("pressure", p.data());
  for (const char* when :
       {"max(velocity) > 1e9", "max(velocity) > 1e9 and time > 0.3",
        "max(velocity) > 1e9 or mean(pressure, low) > 1e9 or max(x) > 1e9 or count(low) < 0"}) {
    voxspan::Schedule schedule(voxspan::load_config_string(
        std::string("boxes: {low: [[0, 0, 0], [1, 1, 0.5]]}\ntrigger: {when: \"") + when +
        "\"}\n"));
    voxspan::StepPlan plan = schedule.blank();
    // The median and the fastest step: the machine is shared, the fastest is the pass's own.
    std::vector<double> ms;
    for (int step = -3; step < 100; ++step) {  // 3 to warm up
      auto t0 = Clock::now();
      plan.clear();
      schedule.plan(step, 0.01 * step, false, plan);
      schedule.decide(step, 0.01 * step, particles, plan);
      if (step >= 0) ms.push_back(1e3 * seconds_since(t0));
    }
    std::sort(ms.begin(), ms.end());
    std::printf(
        "conditions, nothing fires     %.3f ms per step (fastest %.3f), %zu particles: %s\n",
        ms[ms.size() / 2], ms.front(), n, when);
  }
}

void bench_submit_when_full() {
  voxspan::BackgroundWriter writer(4, voxspan::QueuePolicy::drop);
  std::atomic<bool> release{false};
  std::atomic<bool> started{false};
  writer.submit("blocker", [&] {
    started = true;
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  while (!started) std::this_thread::yield();
  for (int i = 0; i < 4; ++i) writer.submit("fill", [] {});
  const int n = 200000;
  auto t0 = Clock::now();
  int accepted = 0;
  for (int i = 0; i < n; ++i) accepted += writer.submit("frame", [] {});
  double s = seconds_since(t0);
  release = true;
  writer.drain();
  std::printf("submit to a full queue (drop) %.0f ns per call (%d of %d accepted)\n", 1e9 * s / n,
              accepted, n);
}

void bench_files(const std::filesystem::path& folder, bool sync) {
  const int files = 64;
  const std::size_t bytes = std::size_t(1) << 20;
  auto payload = std::make_shared<std::string>(bytes, 'v');
  double submit_seconds = 0;
  auto t0 = Clock::now();
  {
    voxspan::BackgroundWriter writer(8, voxspan::QueuePolicy::wait);
    for (int i = 0; i < files; ++i) {
      auto s0 = Clock::now();
      writer.submit("file", [=] {
        voxspan::write_file_atomically(folder / numbered("f", i, ".bin"), *payload, sync);
      });
      submit_seconds += seconds_since(s0);
    }
    writer.drain();
  }
  double s = seconds_since(t0);
  std::printf(
      "1 MiB files, fsync %-3s       %.0f MiB/s (%d files in %.2f s; the caller waited "
      "%.2f s in submit)\n",
      sync ? "on" : "off", files / s, files, s, submit_seconds);
}

void bench_png(const std::filesystem::path& folder) {
  const int w = 960, h = 540, frames = 20;
  std::vector<float> linear(std::size_t(w) * h * 4);
  // Random pixels: the worst case for zlib (a rendered frame compresses several times better).
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (float& v : linear) v = unit(rng);
  double convert = 0, encode = 0;
  std::size_t bytes = 0;
  for (int f = 0; f < frames; ++f) {
    auto t0 = Clock::now();
    voxspan::ImageRGBA8 image = voxspan::linear_to_srgb8(linear, w, h, true);
    convert += seconds_since(t0);
    t0 = Clock::now();
    std::string png = voxspan::encode_png(image);
    voxspan::write_file_atomically(folder / numbered("frame", f, ".png"), png, true);
    encode += seconds_since(t0);
    bytes = png.size();
  }
  std::printf("PNG 960x540, random pixels: sRGB %.1f ms, encode+write %.1f ms, %zu KiB\n",
              1e3 * convert / frames, 1e3 * encode / frames, bytes >> 10);
}

void bench_vdb(const std::filesystem::path& folder, int side) {
  const double dx = 0.01;
  voxspan::test::LatticeScene scene = voxspan::test::make_lattice_block(side, dx, float(dx / 2));
  std::vector<float> pressure(scene.boundary.size(), 1.f);
  std::vector<voxspan::AttributeSpan> attributes = {{"pressure", 1, pressure}};
  auto t0 = Clock::now();
  voxspan::VdbSnapshotReport r = voxspan::write_vdb_snapshot(
      folder / "snap.vdb", {scene.boundary, scene.cells(), attributes, 0, 0}, {});
  double s = seconds_since(t0);
  std::printf(
      "VDB snapshot, %d^3 block      %.2f s (%zu particles, %zu boundary, %zu inner-full "
      "cells, %llu voxels, %.1f MiB)\n",
      side, s, scene.all.size(), scene.boundary.size(), r.inner_full_cells,
      static_cast<unsigned long long>(r.level_set_voxels), double(r.bytes) / (1 << 20));
  for (const voxspan::FrameStats::Pass& stage : r.timings.passes)
    std::printf("  %-16s %8.0f ms\n", stage.name.c_str(), stage.ms);
}

}  // namespace

int main(int argc, char** argv) {
  std::int64_t steps = 100000000;
  int block = 46;
  bool keep = false;                // 46^3 = 97 336 particles, about the main job's count
  std::size_t particles = 1000000;  // for the conditions
  std::filesystem::path folder =
      std::filesystem::temp_directory_path() / numbered("voxspan-bench-", int(::getpid()), "");
  constexpr char kUsage[] =
      "usage: bench_runtime [--steps N] [--folder DIR] [--block N] [--keep 1] [--particles N]\n";
  for (int i = 1; i < argc; i += 2) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") return voxspan::tools::print_usage(stdout, kUsage);
    if (i + 1 >= argc) return voxspan::tools::print_usage(stderr, kUsage);  // a flag alone
    if (a == "--steps") steps = std::stoll(argv[i + 1]);
    else if (a == "--folder") folder = argv[i + 1];
    else if (a == "--block") block = std::stoi(argv[i + 1]);
    else if (a == "--keep") keep = std::stoi(argv[i + 1]) != 0;
    else if (a == "--particles") particles = std::size_t(std::stod(argv[i + 1]));
    else return voxspan::tools::print_usage(stderr, kUsage);
  }
  std::filesystem::create_directories(folder);
  bench_schedule(steps);
  bench_conditions(particles);
  bench_submit_when_full();
  bench_files(folder, false);
  bench_files(folder, true);
  bench_png(folder);
  bench_vdb(folder, block);
  if (!keep) std::filesystem::remove_all(folder);
  return 0;
}
