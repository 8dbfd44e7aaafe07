// bench_voxelize: times the voxelization (frame, upload, bin, clear, splat, compress) on a
// dam-break scene and prints milliseconds per pass (median over frames), voxels and particles
// per second, the peak GPU memory, and the speed-up of binning particles to tiles once over the
// paper's re-splat of every particle for every tile, measured in the same run.
//
// The scene: a water column (0.3 x 0.6 x 0.3) of about --particles lattice particles collapsing
// along a tank (Ritter's dam-break profile at --time seconds), with a little spray. Cells of two
// particle spacings are classified by the solver side's classifier (voxspan/classify.h, through
// tools/scenes/scene_cell_states.h): only the boundary shell (particles of cells that
// are not inner: within about one cell of the surface) is voxelized, with the cell states
// skipping inner-empty and filling inner-full cells; --all-particles voxelizes every particle.
//
//   bench_voxelize [--particles N] [--time T] [--size WxH] [--alpha DEG] [--max-layers L]
//                  [--budget-mib M]... [--frames F] [--threads per_pixel|per_particle|both]
//                  [--no-resplat] [--all-particles] [--accuracy] [--json] [--pgm FILE]
//                  [--save-spans FILE] [--compare-spans FILE]
//                  [--platform auto|nvidia|device|surfaceless]
// --pgm writes the inside length per pixel as a grey image (a check of what was timed).
// --save-spans writes the span image of one more frame (the first budget's tiles); on another
// machine --compare-spans compares its own with it (an NVIDIA GPU against llvmpipe: the same
// spans, ideally bit for bit).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/shader_library.h"
#include "render/gl/voxelizer.h"
#include "render/reference/exact_spans.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/scene_cell_states.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"
#include "voxspan/error.h"

namespace {

using namespace voxspan;

struct Args : tools::BenchArgs {
  Args() { particles = 1e6, time = 0.25; }
  std::vector<double> budgets_mib;
  std::vector<SplatThreads> threads = {SplatThreads::per_pixel, SplatThreads::per_particle};
  bool resplat = true;
  bool accuracy = false;
  std::string pgm;
  std::string save_spans, compare_spans;
};

const char* kPasses[] = {"frame", "upload", "bin", "clear", "splat", "compress"};

constexpr char kUsage[] =
    "usage: bench_voxelize [--particles N] [--time T] [--size WxH] [--alpha DEG]\n"
    "         [--max-layers L] [--budget-mib M]... [--frames F]\n"
    "         [--threads per_pixel|per_particle|both] [--no-resplat] [--all-particles]\n"
    "         [--accuracy] [--json] [--pgm FILE] [--save-spans FILE] [--compare-spans FILE]\n"
    "         [--platform auto|nvidia|device|surfaceless]\n";

// --threads per_pixel|per_particle|both (both: the default list).
bool read_threads(const std::string& v, std::vector<SplatThreads>& threads) {
  if (v == "per_pixel") threads = {SplatThreads::per_pixel};
  else if (v == "per_particle") threads = {SplatThreads::per_particle};
  else return v == "both";
  return true;
}

// The flags beyond the scene's.
bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--budget-mib")) {
    a.budgets_mib.push_back(std::atof(v));
    return true;
  }
  if (const char* v = arg.value("--threads")) return read_threads(v, a.threads);
  return tools::read_bench_flag(arg, a) || arg.flag("--no-resplat", a.resplat, false) ||
         arg.flag("--accuracy", a.accuracy) || arg.value("--pgm", a.pgm) ||
         arg.value("--save-spans", a.save_spans) || arg.value("--compare-spans", a.compare_spans);
}

bool parse(int argc, char** argv, Args& a) {
  if (!tools::read_args(argc, argv, a, read_flag)) return false;
  if (a.budgets_mib.empty()) a.budgets_mib = {1024, 16};
  return true;
}

struct Result {
  std::map<std::string, double> ms;  // median per pass
  double total_ms = 0;
  FrameStats last;
};

Result time_frames(Voxelizer& voxelizer, const gl::Context& context, const Camera& camera,
                   const test::Particles& particles, const CellStatesView& cells,
                   const VoxelizeOptions& options, int frames) {
  std::map<std::string, std::vector<double>> samples;
  std::vector<double> totals;
  Result r;
  for (int f = -1; f < frames; ++f) {  // frame -1 warms up (allocations, shader caches)
    gl::reset_memory_peak();
    FrameStats stats;
    gl::GpuRecorder recorder(stats, context.has_gpu_timers());
    voxelizer.run(camera, particles, cells, options, recorder);
    recorder.collect();
    if (f < 0) continue;
    for (const char* p : kPasses) samples[p].push_back(stats.ms(p));
    totals.push_back(stats.total_ms());
    r.last = stats;
  }
  for (auto& [pass, v] : samples) r.ms[pass] = tools::median(v);
  r.total_ms = tools::median(totals);
  return r;
}

void print_row(const char* label, const Result& r) {
  const FrameStats& s = r.last;
  const double grid_ms = r.ms.at("clear") + r.ms.at("splat") + r.ms.at("compress");
  std::printf("%-34s", label);
  for (const char* p : kPasses) std::printf(" %9.1f", r.ms.at(p));
  std::printf(" %9.1f %8.2f %8.2f %8.0f\n", r.total_ms,
              double(s.count("voxels")) / (grid_ms * 1e-3) * 1e-9,
              double(s.count("particles.input")) / (r.total_ms * 1e-3) * 1e-6,
              double(s.gpu_peak_bytes) / (1 << 20));
}

// The inside length per pixel, scaled to the largest, as an 8-bit PGM.
void write_inside_pgm(const SpanImage& image, const std::string& path) {
  float most = 0;
  for (const PixelSpans& p : image.pixels) most = std::max(most, p.inside);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw make_error("cannot write ", path);
  std::fprintf(f, "P5\n%d %d\n255\n", image.width(), image.height());
  for (const PixelSpans& p : image.pixels) std::fputc(most > 0 ? int(255 * p.inside / most) : 0, f);
  std::fclose(f);
}

int run(const Args& a) {
  gl::Context context(a.context);
  tools::print_renderer(context);

  test::DamBreak shape;
  shape.spacing = test::dam_break_spacing(shape, a.particles);
  shape.radius = shape.spacing;
  const auto t0 = std::chrono::steady_clock::now();
  const test::Particles all = test::dam_break(shape, a.time);
  test::TestCells cells = test::classify_for_test(all, 2 * shape.spacing, 8);
  const double scene_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const test::Particles& input = a.all_particles ? all : cells.boundary;
  const CellStatesView view = a.all_particles ? CellStatesView{} : cells.view;
  // Close enough that the water fills much of the image, as in the paper's views.
  const Camera camera = test::frame_scene(all, {0.35, -0.45, -1}, a.width, a.height, 45, 0.75);
  std::printf(
      "scene: dam break at t = %.2f s, %zu particles (spacing %.3g), %zu voxelized (%s), "
      "cells %dx%dx%d (%lld inner-full, %lld inner-empty); made in %.1f s\n",
      a.time, all.size(), shape.spacing, input.size(), a.all_particles ? "all" : "boundary shell",
      cells.view.dims[0], cells.view.dims[1], cells.view.dims[2],
      static_cast<long long>(cells.inner_full_cells),
      static_cast<long long>(cells.inner_empty_cells), scene_s);

  gl::ShaderLibrary shaders;
  Voxelizer voxelizer(shaders);
  VoxelizeOptions base;
  base.grid.alpha_degrees = a.alpha;
  base.grid.max_layers = a.max_layers;
  base.gap_bridging = shape.spacing;

  bool first = true;
  for (double budget : a.budgets_mib) {
    for (SplatThreads threads : a.threads) {
      VoxelizeOptions o = base;
      o.tiles.memory_budget = static_cast<std::size_t>(budget * (1 << 20));
      o.splat_threads = threads;
      const char* thread_name = threads == SplatThreads::per_pixel ? "per pixel" : "per particle";
      const Result lists = time_frames(voxelizer, context, camera, input, view, o, a.frames);
      if (first) {
        const FrameStats& s = lists.last;
        std::printf(
            "grid: %dx%d x %lld layers (needed %lld, alpha %.2f deg%s), near %.4g far %.4g, "
            "%lld voxels; %lld large spheres\n",
            a.width, a.height, static_cast<long long>(s.count("grid.layers")),
            static_cast<long long>(s.count("grid.layers_needed")), s.figure("grid.alpha_degrees"),
            s.count("grid.layer_cap_hit") ? ", capped" : "", s.figure("grid.near"),
            s.figure("grid.far"), static_cast<long long>(s.count("voxels")),
            static_cast<long long>(s.count("bin.large")));
        std::printf("\n%-34s", "configuration (median ms)");
        for (const char* p : kPasses) std::printf(" %9s", p);
        std::printf(" %9s %8s %8s %8s\n", "total", "Gvox/s", "Mpart/s", "peak MiB");
        first = false;
      }
      char label[96];
      std::snprintf(label, sizeof label, "%.0f MiB, %lld tiles, lists, %s", budget,
                    static_cast<long long>(lists.last.count("tiles")), thread_name);
      print_row(label, lists);
      if (a.json) std::printf("  %s\n", lists.last.json().c_str());
      if (a.resplat && lists.last.count("tiles") > 1) {
        o.binning = Binning::resplat_all;
        const Result resplat = time_frames(voxelizer, context, camera, input, view, o, a.frames);
        std::snprintf(label, sizeof label, "%.0f MiB, %lld tiles, re-splat all, %s", budget,
                      static_cast<long long>(resplat.last.count("tiles")), thread_name);
        print_row(label, resplat);
        if (a.json) std::printf("  %s\n", resplat.last.json().c_str());
        std::printf("  speed-up of binning once: bin+splat %.2fx, whole voxelization %.2fx\n",
                    (resplat.ms.at("bin") + resplat.ms.at("splat")) /
                        (lists.ms.at("bin") + lists.ms.at("splat")),
                    resplat.total_ms / lists.total_ms);
      }
    }
  }
  if (a.accuracy || !a.pgm.empty() || !a.save_spans.empty() || !a.compare_spans.empty()) {
    VoxelizeOptions o = base;
    o.tiles.memory_budget = static_cast<std::size_t>(a.budgets_mib.front() * (1 << 20));
    FrameStats stats;
    gl::GpuRecorder recorder(stats, context.has_gpu_timers());
    const SpanImage gpu = voxelizer.run(camera, input, view, o, recorder).download();
    if (!a.pgm.empty()) write_inside_pgm(gpu, a.pgm);
    if (!a.save_spans.empty()) test::save_spans(gpu, a.save_spans);
    if (!a.compare_spans.empty()) {
      const SpanImage other = test::load_spans(a.compare_spans, gpu.grid);
      std::printf("\nagainst %s: %s; %s\n", a.compare_spans.c_str(),
                  test::identical(gpu, other) ? "identical, bit for bit" : "not identical",
                  test::compare_spans(gpu, other, 1e-3).summary().c_str());
    }
    if (!a.accuracy) return 0;
    const auto r0 = std::chrono::steady_clock::now();
    const SpanImage ref = exact_spans(gpu.grid, input, view, {o.gap_bridging, o.max_spans});
    const double ref_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
    std::printf("\naccuracy against the exact reference (%.1f s on the CPU): %s\n", ref_s,
                test::compare_spans(gpu, ref).summary().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_voxelize", argc, argv, kUsage, parse, run);
}
