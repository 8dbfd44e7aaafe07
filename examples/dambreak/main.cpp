// dambreak - a WCSPH dam break (sph.h) that calls the in-situ adapter every step, as a real
// solver would: its fluid arrays (SoA, cell order) and its compact neighbour grid go to the
// adapter as views, without a copy. With --config the in-situ runtime renders and writes what
// the YAML file asks (docs/runtime.md); without it the adapter only classifies.
//
// Under mpiexec with more than one rank it is a distributed run (decomposition.h): each rank
// steps the particles of its slab with ghosts from the others, and hands the adapter its
// owned particles followed by its ghosts, and the job's communicator. Started alone (or on
// one rank) it is the serial solver, unchanged.
//
//   [mpiexec -n R] dambreak [--config FILE] [--particles N] [--steps S | --until T]
//            [--stop-file PATH]
//            [--render-every K] [--threads P] [--progress-every K] [--depth-particles D]
//            [--rebalance-every K] [--validate] [--no-render]
#include <mpi.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <voxspan/adapter.h>
#include <voxspan/error.h>
#include <voxspan/insitu.h>
#include <voxspan/mpi.h>

#include "decomposition.h"
#include "sph.h"

namespace {

struct Options {
  dambreak::Config config;
  std::string insitu_config;  // YAML file of the in-situ runtime; empty: classification only
  long steps = 1000;
  double until = 0;       // non-dimensional end time; 0: use steps
  std::string stop_file;  // the run ends once this file exists; empty: none
  long render_every = 10;
  long progress_every = 50;
  long rebalance_every = 50;
  int threads = 0;
  bool validate = false;
};

void usage() {
  std::puts(
      "usage: dambreak [options]\n"
      "  --config FILE        in-situ runtime config (YAML: views, triggers, outputs); its\n"
      "                       triggers replace --render-every\n"
      "  --particles N        fluid particles (10000 to several million; default 100000)\n"
      "  --steps S            time steps to run (default 1000)\n"
      "  --until T            run until Martin & Moyce's T = t sqrt(2g/a) instead\n"
      "  --stop-file PATH     end early, cleanly, at the first step that finds PATH there (the\n"
      "                       last render step, its files written): touch it to stop the run;\n"
      "                       Ctrl-C or SIGTERM to any rank does the same (twice: at once)\n"
      "  --render-every K     adapter render steps (default 10)\n"
      "  --no-render          call the adapter every step but never render (writes nothing)\n"
      "  --validate           have the adapter check the grid against the particles\n"
      "  --depth-particles D  a thin tank D particles deep (quasi-2D)\n"
      "  --tank-length L      tank length in column widths (default 4)\n"
      "  --threads P          worker threads per rank (default: all cores)\n"
      "  --progress-every K   progress line every K steps (default 50; 0: none)\n"
      "  --rebalance-every K  under mpiexec: re-balance the slabs every K steps (default 50;\n"
      "                       0: keep the slabs cut at the start)");
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "dambreak: %s needs a value\n", name);
        std::exit(2);
      }
      return argv[++i];
    };
    auto number = [&](const char* name, double lo, double hi) {
      const char* text = value(name);
      char* end = nullptr;
      const double v = std::strtod(text, &end);
      if (end == text || *end != '\0' || !(v >= lo && v <= hi)) {
        std::fprintf(stderr, "dambreak: %s %s: expected a number in [%g, %g]\n", name, text, lo,
                     hi);
        std::exit(2);
      }
      return v;
    };
    if (a == "--config") o.insitu_config = value("--config");
    else if (a == "--particles") o.config.particles = std::size_t(number("--particles", 8, 1e9));
    else if (a == "--steps") o.steps = long(number("--steps", 0, 1e12));
    else if (a == "--until") o.until = number("--until", 0, 1e6);
    else if (a == "--stop-file") o.stop_file = value("--stop-file");
    else if (a == "--render-every") o.render_every = long(number("--render-every", 1, 1e12));
    else if (a == "--no-render") o.render_every = 0;
    else if (a == "--validate") o.validate = true;
    else if (a == "--depth-particles")
      o.config.depth_particles = int(number("--depth-particles", 1, 1e6));
    else if (a == "--tank-length") o.config.tank_length = number("--tank-length", 1.1, 1e3);
    else if (a == "--threads") o.threads = int(number("--threads", 1, 4096));
    else if (a == "--progress-every") o.progress_every = long(number("--progress-every", 0, 1e12));
    else if (a == "--rebalance-every")
      o.rebalance_every = long(number("--rebalance-every", 0, 1e12));
    else if (a == "--help" || a == "-h") {
      usage();
      std::exit(0);
    } else {
      std::fprintf(stderr, "dambreak: unknown option %s\n", a.c_str());
      usage();
      return false;
    }
  }
  return true;
}

// Ctrl-C (or SIGTERM) ends the run as the stop file does, its last step's files written; a
// second one stops it at once.
volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_interrupt(int) {
  interrupted = 1;
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

// A step's checks: the fluid particles over the ranks, and whether the run ends here (an
// interrupt to any rank, which a batch system's SIGTERM may be; the stop file, looked for by the
// root). In a distributed run both in one reduction a step, so that all ranks end at the same
// step.
struct StepChecks {
  std::uint64_t fluid = 0;
  bool stop = false;
};
StepChecks step_checks(std::uint64_t owned, const std::string& stop_file, bool root,
                       bool distributed) {
  std::error_code unreadable;  // a folder it cannot look into: not there yet
  const bool asked = interrupted != 0 ||
                     (root && !stop_file.empty() && std::filesystem::exists(stop_file, unreadable));
  std::uint64_t sums[2] = {owned, asked ? 1u : 0u};
  if (distributed) MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return {sums[0], sums[1] > 0};
}

voxspan::GridGeometry adapter_geometry(const dambreak::GridShape& s) {
  return {s.origin, s.cell_size, s.dims};
}

// The grid the adapter gets: the solver's own where the rank holds no ghosts; else one cell
// order over the owned particles and the ghosts stored after them.
voxspan::GridView adapter_grid(const dambreak::DamBreak& sim, dambreak::CellOrder& merged) {
  const voxspan::GridGeometry geometry = adapter_geometry(sim.fluid_grid().shape());
  if (sim.fluid().size() == sim.owned_count())
    return voxspan::GridView::offsets(geometry, sim.fluid_grid().offsets().data());
  dambreak::merge_cell_orders(sim.fluid_grid(), sim.ghost_grid(), std::uint32_t(sim.owned_count()),
                              merged);
  return voxspan::GridView::offsets(geometry, merged.offsets.data())
      .with_order(merged.order.data());
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

int run(const Options& o) {
  std::unique_ptr<tbb::global_control> threads;
  if (o.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    std::size_t(o.threads));
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const bool root = rank == 0;
  std::unique_ptr<dambreak::Decomposition> domain;
  if (ranks > 1)
    domain = std::make_unique<dambreak::Decomposition>(MPI_COMM_WORLD, o.rebalance_every);

  using Clock = std::chrono::steady_clock;
  const auto t_setup = Clock::now();
  dambreak::DamBreak sim(o.config, domain.get());
  const std::uint64_t fluid_count = dambreak::sum_over_ranks(sim.owned_count(), MPI_COMM_WORLD);
  if (root) {
    std::printf(
        "dambreak: %llu fluid + %zu wall particles, dx %.4g m, h %.4g m, c0 %.3g m/s, "
        "grid %d x %d x %d cells (set up in %.2f s)\n",
        static_cast<unsigned long long>(fluid_count), sim.walls().size(), sim.dx(),
        sim.smoothing_length(), sim.sound_speed(), sim.fluid_grid().shape().dims[0],
        sim.fluid_grid().shape().dims[1], sim.fluid_grid().shape().dims[2],
        std::chrono::duration<double>(Clock::now() - t_setup).count());
    if (domain)
      std::printf("dambreak: %d ranks, slabs along x re-balanced every %ld steps\n", ranks,
                  o.rebalance_every);
  }

  voxspan::AdapterOptions ao;
  ao.render_every = o.render_every;
  ao.classify.particle_spacing = sim.dx();
  ao.classify.validate = o.validate;
  ao.classify.attributes = {"velocity", "density"};
  if (domain) ao = voxspan::with_communicator(std::move(ao), MPI_COMM_WORLD);
  std::unique_ptr<voxspan::Adapter> adapter;
  try {
    adapter = o.insitu_config.empty() ? std::make_unique<voxspan::Adapter>(ao)
                                      : std::make_unique<voxspan::Adapter>(
                                            voxspan::adapter_from_config_file(o.insitu_config, ao));
  } catch (const voxspan::Error& e) {
    // Every rank failed alike (the runtime agrees on a failure at start-up): said once.
    if (root) std::fprintf(stderr, "dambreak: %s\n", e.what());
    return 1;
  }
  // The tank, drawn by the views: its walls stand still and every rank holds them all, so the
  // root alone gives them, once.
  if (root) {
    const dambreak::Walls& w = sim.walls();
    adapter->set_scenery(voxspan::ParticleView::soa(w.x.data(), w.y.data(), w.z.data(), w.size()));
  }

  const auto t0 = Clock::now();
  auto last = t0;
  long last_step = 0, failed = 0;
  double adapter_seconds = 0;
  std::vector<double> step_seconds;
  dambreak::CellOrder merged;
  std::vector<float> pressure;
  std::vector<double> ids;  // exact up to 2^53
  bool stopped = false;     // the stop file was found: that step was the last
  for (long step = 1;; ++step) {
    if (stopped || (o.until > 0 ? sim.nondimensional_time() >= o.until : step > o.steps)) break;
    const auto ts = Clock::now();
    sim.step();
    step_seconds.push_back(std::chrono::duration<double>(Clock::now() - ts).count());
    const StepChecks checks = step_checks(sim.owned_count(), o.stop_file, root, domain != nullptr);
    stopped = checks.stop;
    if (stopped && interrupted != 0)
      std::fprintf(stderr,
                   "dambreak: %sinterrupted: this step is the last (its files written); "
                   "interrupt again to stop at once\n",
                   ranks > 1 ? ("rank " + std::to_string(rank) + " ").c_str() : "");
    const bool final_step =
        stopped || (o.until > 0 ? sim.nondimensional_time() >= o.until : step == o.steps);
    if (domain && checks.fluid != fluid_count) {
      if (root) std::fprintf(stderr, "dambreak: fluid particles lost at step %ld\n", step);
      return 1;
    }

    const dambreak::Fluid& f = sim.fluid();
    // The pressure and the ids as numbers cost a pass over the particles: on render steps only.
    if (final_step || adapter->is_render_step(step, sim.time())) {
      sim.pressure(pressure);
      ids.assign(f.id.begin(), f.id.end());
    } else {
      pressure.resize(f.size());
      ids.resize(f.size());
    }
    const auto particles = voxspan::ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                               .with_owned(sim.owned_count())
                               .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data())
                               .with_scalar("density", f.rho.data())
                               .with_scalar("pressure", pressure.data())
                               .with_scalar("id", ids.data());
    const voxspan::GridView grid = adapter_grid(sim, merged);
    const auto ta = Clock::now();
    const voxspan::Status status = final_step
                                       ? adapter->execute_last(step, sim.time(), particles, grid)
                                       : adapter->execute(step, sim.time(), particles, grid);
    if (!status.ok()) ++failed;
    adapter_seconds += std::chrono::duration<double>(Clock::now() - ta).count();

    if (o.progress_every > 0 && step % o.progress_every == 0) {
      const auto now = Clock::now();
      const double wall = std::chrono::duration<double>(now - last).count();
      const dambreak::Diagnostics d =
          dambreak::combine_over_ranks(sim.diagnostics(), MPI_COMM_WORLD);
      const voxspan::StepStats& st = adapter->last_stats();
      if (root)
        std::printf(
            "step %6ld  t %.4f s  T %.3f  dt %.3g s  front x/a %.3f  max|drho|/rho0 %.2f%%  "
            "%.3g particles/s  surface shell %zu of %zu%s  in situ %.1f s (%lld steps)\n",
            step, sim.time(), sim.nondimensional_time(), sim.dt(), d.front / o.config.column_width,
            100 * d.max_density_error, double(d.fluid) * double(step - last_step) / wall,
            st.counts.boundary, st.counts.particles, domain ? " on rank 0" : "", adapter_seconds,
            static_cast<long long>(adapter->render_steps()));
      std::fflush(stdout);
      if (d.nonfinite > 0) {
        if (root)
          std::fprintf(stderr, "dambreak: %zu particles became NaN at step %ld\n", d.nonfinite,
                       step);
        return 1;
      }
      last = now;
      last_step = step;
    }
  }
  const auto t_finish = Clock::now();
  adapter->finish();  // the files still being written
  const double finish_seconds = std::chrono::duration<double>(Clock::now() - t_finish).count();
  const double total = std::chrono::duration<double>(Clock::now() - t0).count();
  const double solver = total - adapter_seconds - finish_seconds;
  const long steps = long(sim.steps());
  const dambreak::Diagnostics d = dambreak::combine_over_ranks(sim.diagnostics(), MPI_COMM_WORLD);
  const bool ids_ok = !domain || dambreak::ids_complete(sim.fluid(), sim.owned_count(), fluid_count,
                                                        MPI_COMM_WORLD);
  if (!root) return ids_ok ? 0 : 1;
  std::printf(
      "dambreak: %ld steps to t %.4f s (T %.3f) in %.2f s: %.3g particle-steps/s; "
      "adapter %.2f s (%ld steps in situ, %ld failed)\n",
      steps, sim.time(), sim.nondimensional_time(), total,
      steps > 0 ? double(fluid_count) * double(steps) / solver : 0.0, adapter_seconds,
      long(adapter->render_steps()), failed);
  std::printf(
      "time: solver %.1f s (median step %.2f ms), in situ %.1f s on the solver's thread "
      "(%.1f %% of the solver's time) + %.1f s in finish() (the last files, a live page's "
      "linger)\n",
      solver, 1e3 * median(step_seconds), adapter_seconds,
      solver > 0 ? 100 * adapter_seconds / solver : 0.0, finish_seconds);
  std::printf("final: T %.4f  front x/a %.5f  max|drho|/rho0 %.2f%%  fluid particles %zu\n",
              sim.nondimensional_time(), d.front / o.config.column_width, 100 * d.max_density_error,
              d.fluid);
  if (domain)
    std::printf("mpi: %d ranks, %llu fluid particles on every step, ids %s\n", ranks,
                static_cast<unsigned long long>(fluid_count),
                ids_ok ? "each owned once" : "NOT each owned once");
  if (const std::string summary = adapter->summary(); !summary.empty())
    std::printf("in situ: %s\n", summary.c_str());
  return failed > 0 || !ids_ok ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return 2;
  // Started without mpiexec, Open MPI makes the program a job of one rank.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  const int code = run(o);
  MPI_Finalize();
  return code;
}
