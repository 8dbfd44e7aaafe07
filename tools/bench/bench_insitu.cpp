// bench_insitu: what the in-situ runtime costs a solver (docs/benchmarks.md, "In-situ cost").
//   1. a step that is not a render step, through Adapter::execute with the whole runtime behind
//      it (the main job's views, GL context made, every output enabled on its own trigger);
//   2. the dam break at the main job's settings (its views, its particle count) run three
//      times for the same steps: the solver alone, with rendering every K steps, and with
//      rendering plus VDB snapshots every V steps; the in-situ cost is the extra wall time over
//      the solver alone, split into what the solver's thread spent (per pass) and what the
//      writer's thread spent beside it (PNG encoding, snapshots) on the same cores.
//
//   bench_insitu [--config FILE] [--particles N] [--tank-length L] [--start T] [--steps S]
//                [--render-every K] [--vdb-every V] [--non-render-steps M] [--skip-runs]
//                [--size WxH] [--view NAME]... [--linear-pictures]
// --linear-pictures: the pictures stay linear floats, read back at 16 bytes a pixel and encoded
// to sRGB on the writer's thread (InsituPipeline::keep_linear_pictures), as before the GL
// renderer made them 8-bit on the GPU where only PNG files take them.
// Defaults: examples/dambreak/main-job.yaml, 100000 particles, the main job's 3a tank, runs
// from the flowing state at T = 1.5 (the solver advances there once, untimed, and every run
// starts from a copy), 300 steps, K = 10, V = 100.
// The tool links the runtime statically (the same adapter code a solver gets from
// libvoxspan.so, one indirect call fewer), so it can read the pipeline's totals.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "insitu/runtime/adapter_config.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "insitu/views/surface_view.h"
#include "tools/common/dambreak_views.h"
#include "tools/common/usage.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Options {
  std::string config = "examples/dambreak/main-job.yaml";
  std::size_t particles = 100000;
  double tank_length = 3;
  double start = 1.5;  // Martin & Moyce's T where the runs start
  long steps = 300;
  long render_every = 10;
  long vdb_every = 100;
  long non_render_steps = 20000000;
  bool runs = true;
  int width = 0, height = 0;       // 0: the config's view sizes
  std::vector<std::string> views;  // keep only these views (all when empty)
  bool linear_pictures = false;
};

using voxspan::tools::fluid_grid;
using voxspan::tools::fluid_view;

voxspan::AdapterOptions adapter_options(const dambreak::DamBreak& sim) {
  voxspan::AdapterOptions o;
  o.classify.particle_spacing = sim.dx();
  return o;
}

// How a view looks: a surface view's shading, else its kind's settings type.
std::string view_look(const voxspan::ViewSettings& v) {
  if (const auto* s = dynamic_cast<const voxspan::SurfaceSettings*>(&v))
    return voxspan::shade_mode_name(s->shading);
  return "view";
}

// 1. A non-render step: the schedule says no, nothing else happens.
void bench_non_render(const voxspan::Config& base, dambreak::DamBreak& sim, long steps) {
  voxspan::Config config = base;
  const voxspan::TriggerSpec far{1000000000000LL, 0, false, false};
  config.trigger = far;
  for (voxspan::ConfiguredOutput& out : config.outputs) {
    out.settings->trigger = far;
    if (out.kind == "vdb" || out.kind == "vtk") out.settings->enabled = true;
  }
  voxspan::Adapter adapter = voxspan::make_insitu_adapter(config, adapter_options(sim));
  long failures = 0;
  // The call alone, on views made once...
  const auto particles = fluid_view(sim.fluid());
  const auto grid = fluid_grid(sim);
  auto t0 = Clock::now();
  for (long step = 1; step <= steps; ++step)
    failures += !adapter.execute(step, 1e-5 * double(step), particles, grid).ok();
  const double call = seconds_since(t0);
  // ... and as a solver does it, the views made afresh every step.
  t0 = Clock::now();
  for (long step = steps + 1; step <= 2 * steps; ++step)
    failures +=
        !adapter.execute(step, 1e-5 * double(step), fluid_view(sim.fluid()), fluid_grid(sim)).ok();
  const double with_views = seconds_since(t0);
  std::printf(
      "non-render step: Adapter::execute %.1f ns; with the particle and grid views made "
      "each step %.1f ns (%ld steps each, %lld render steps, %ld failures)\n",
      1e9 * call / double(steps), 1e9 * with_views / double(steps), steps,
      static_cast<long long>(adapter.render_steps()), failures);
}

struct RunFigures {
  double wall = 0, solver = 0, in_situ = 0, finish = 0;
  voxspan::PipelineTotals totals;
};

RunFigures run(const dambreak::DamBreak& start, long steps, const voxspan::Config* config,
               bool linear_pictures = false) {
  dambreak::DamBreak sim = start;
  RunFigures f;
  std::unique_ptr<voxspan::Adapter> adapter;
  if (config)
    adapter = std::make_unique<voxspan::Adapter>(
        voxspan::make_insitu_adapter(*config, adapter_options(sim)));
  if (adapter && linear_pictures)
    std::static_pointer_cast<voxspan::InsituPipeline>(adapter->pipeline())->keep_linear_pictures();
  const auto t0 = Clock::now();
  const std::int64_t first = sim.steps();
  for (long i = 1; i <= steps; ++i) {
    const auto ts = Clock::now();
    sim.step();
    f.solver += seconds_since(ts);
    if (!adapter) continue;
    const auto ta = Clock::now();
    adapter->execute(first + i, sim.time(), fluid_view(sim.fluid()), fluid_grid(sim));
    f.in_situ += seconds_since(ta);
  }
  if (adapter) {
    const auto tf = Clock::now();
    adapter->finish();
    f.finish = seconds_since(tf);
    f.totals = std::static_pointer_cast<voxspan::InsituPipeline>(adapter->pipeline())->totals();
  }
  f.wall = seconds_since(t0);
  return f;
}

void report(const char* name, const RunFigures& f, const RunFigures& alone, long steps) {
  const double extra = f.wall - alone.wall;
  std::printf(
      "%-34s wall %7.1f s  solver %6.1f s  in situ on solver thread %6.1f s  "
      "+ finish %4.1f s  extra wall over solver alone %+7.1f s = %6.1f %%\n",
      name, f.wall, f.solver, f.in_situ, f.finish, extra, 100 * extra / alone.wall);
  if (f.totals.render_steps == 0 && f.totals.output("vdb").written == 0) return;
  const voxspan::PipelineTotals& t = f.totals;
  std::printf(
      "    %lld render steps (%.2f s each on the solver's thread), %lld PNG, %lld VDB; "
      "writer thread %.1f s\n",
      static_cast<long long>(t.render_steps),
      t.render_steps ? t.seconds_process / double(t.render_steps) : 0.0,
      static_cast<long long>(t.output("png").written),
      static_cast<long long>(t.output("vdb").written), t.writer_seconds());
  std::printf("    per render step, ms:");
  for (const voxspan::FrameStats::Pass& pass : t.passes.passes)
    std::printf(" %s %.1f", pass.name.c_str(),
                pass.ms / double(std::max<std::int64_t>(t.render_steps, 1)));
  std::printf(
      "; classify+compact+outputs %.1f\n",
      1e3 * (f.in_situ - t.seconds_render) / double(std::max<std::int64_t>(t.render_steps, 1)));
  (void)steps;
}

constexpr char kUsage[] =
    "usage: bench_insitu [--config FILE] [--particles N] [--tank-length L] [--start T]\n"
    "                    [--steps S] [--render-every K] [--vdb-every V] [--non-render-steps M]\n"
    "                    [--skip-runs] [--size WxH] [--view NAME]... [--linear-pictures]\n";

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_insitu: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") std::exit(voxspan::tools::print_usage(stdout, kUsage));
    else if (a == "--config") o.config = value();
    else if (a == "--particles") o.particles = std::size_t(std::atof(value()));
    else if (a == "--steps") o.steps = std::atol(value());
    else if (a == "--tank-length") o.tank_length = std::atof(value());
    else if (a == "--start") o.start = std::atof(value());
    else if (a == "--render-every") o.render_every = std::atol(value());
    else if (a == "--vdb-every") o.vdb_every = std::atol(value());
    else if (a == "--non-render-steps") o.non_render_steps = std::atol(value());
    else if (a == "--skip-runs") o.runs = false;
    else if (a == "--linear-pictures") o.linear_pictures = true;
    else if (a == "--view") o.views.push_back(value());
    else if (a == "--size") {
      if (std::sscanf(value(), "%dx%d", &o.width, &o.height) != 2) {
        std::fprintf(stderr, "bench_insitu: --size expects WxH\n");
        return false;
      }
    } else {
      std::fprintf(stderr, "bench_insitu: unknown option %s\n", a.c_str());
      return false;
    }
  }
  return o.steps > 0 && o.render_every > 0 && o.vdb_every > 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return voxspan::tools::print_usage(stderr, kUsage);
  try {
    voxspan::Config config = voxspan::load_config_file(o.config);
    config.log_level = "warning";
    config.output_folder =
        (std::filesystem::temp_directory_path() / "voxspan-bench-insitu").string();
    std::filesystem::remove_all(config.output_folder);
    if (!o.views.empty())
      std::erase_if(config.views, [&](const voxspan::ConfiguredView& v) {
        return std::find(o.views.begin(), o.views.end(), v.settings->name) == o.views.end();
      });
    for (voxspan::ConfiguredView& v : config.views)
      if (o.width > 0) v.settings->width = o.width, v.settings->height = o.height;
    dambreak::Config scene;
    scene.particles = o.particles;
    scene.tank_length = o.tank_length;
    dambreak::DamBreak start(scene);
    {
      dambreak::DamBreak& sim = start;
      std::printf("dam break: %zu fluid particles, dx %.4g m; config %s: %zu views",
                  sim.fluid().size(), sim.dx(), o.config.c_str(), config.views.size());
      for (const voxspan::ConfiguredView& v : config.views)
        std::printf(" (%s %s %dx%d)", v.settings->name.c_str(), view_look(*v.settings).c_str(),
                    v.settings->width, v.settings->height);
      std::printf("\n");
      sim.step();
      bench_non_render(config, sim, o.non_render_steps);
    }
    if (!o.runs) return 0;
    while (start.nondimensional_time() < o.start) start.step();
    std::printf("runs start at step %lld, T %.2f (front x/a %.2f)\n",
                static_cast<long long>(start.steps()), start.nondimensional_time(),
                start.diagnostics().front / scene.column_width);

    // Rendering every K steps (PNG and stats with it), no snapshots; then with snapshots.
    config.trigger = {o.render_every, 0, true, true};
    config.output("png").trigger = config.output("stats").trigger = config.trigger;
    config.output("vdb").enabled = false;
    config.output("vtk").enabled = false;
    voxspan::Config with_vdb = config;
    with_vdb.output("vdb").enabled = true;
    with_vdb.output("vdb").trigger = {o.vdb_every, 0, false, false};

    std::printf("%ld solver steps per run; render every %ld steps; snapshots every %ld steps\n",
                o.steps, o.render_every, o.vdb_every);
    const RunFigures alone = run(start, o.steps, nullptr);
    std::printf("%-34s wall %7.1f s  solver %6.1f s (%.1f ms per step)\n", "solver alone",
                alone.wall, alone.solver, 1e3 * alone.solver / double(o.steps));
    std::fflush(stdout);
    const RunFigures rendered = run(start, o.steps, &config, o.linear_pictures);
    report("render, no snapshots", rendered, alone, o.steps);
    std::fflush(stdout);
    const RunFigures snapshots = run(start, o.steps, &with_vdb, o.linear_pictures);
    report("render + VDB snapshots", snapshots, alone, o.steps);
    std::filesystem::remove_all(config.output_folder);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_insitu: %s\n", e.what());
    return 1;
  }
  return 0;
}
