// voxspan/adapter.h - the entry point a solver calls every step:
//
//   voxspan::AdapterOptions options;
//   options.render_every = 10;
//   options.classify.particle_spacing = dx;
//   voxspan::Adapter adapter(options);                      // throws voxspan::Error if invalid
//   for (step...) {
//     ...advance the solver...
//     adapter.execute(step, time, ParticleView::soa(x, y, z, n), GridView::offsets(g, offsets));
//   }
//
// Or with the in-situ runtime behind it, configured by a YAML file (voxspan/insitu.h,
// docs/runtime.md): views, triggers, PNG frames, stats, OpenVDB and VTK snapshots:
//
//   voxspan::Adapter adapter = voxspan::adapter_from_config_file("insitu.yaml", options);
//   for (step...) adapter.execute(step, time, particles, grid);   // last: execute_last(...)
//   adapter.finish();                                               // waits for the files
//
// execute() never throws into the solver and costs nothing on a step that is not a render
// step (no allocation, no pass over the particles; but a trigger on a condition reads the
// attributes it names on every step, in one pass). On a render step it classifies the cells,
// compacts the boundary particles (voxspan/classify.h) and hands them, with the cell states
// and the step's stats, to the Pipeline plugged in behind it (the renderer and outputs).
// Standard library only; no GL, VTK or OpenVDB.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "voxspan/cell_states.h"
#include "voxspan/classify.h"
#include "voxspan/grid.h"
#include "voxspan/particles.h"

namespace voxspan {

struct AdapterOptions {
  // A step is a render step when step % render_every == 0 (and the pipeline wants it);
  // 0 never renders.
  std::int64_t render_every = 1;
  // Full count, particle spacing, radius, built-grid cell size, validation, ghosts and the
  // attributes to compact: see voxspan/classify.h. particle_spacing or full_count is needed.
  ClassifyOptions classify;
  // The MPI communicator of the job, as its Fortran handle (MPI_Fint: what MPI_Comm_c2f gives;
  // voxspan/mpi.h sets it from an MPI_Comm). None: one process, no MPI call is made.
  std::optional<int> mpi_comm;
};

enum class StatusCode : int { ok = 0, invalid_input = 1, pipeline_failed = 2, internal_error = 3 };

struct Status {
  StatusCode code = StatusCode::ok;
  std::string message;

  bool ok() const { return code == StatusCode::ok; }
};

// What one execute() did. Occupancy counts (empty/partial/full) include the inner cells.
struct StepStats {
  std::int64_t step = -1;
  double time = 0;
  bool rendered = false;  // a render step that completed classification
  Status status;
  ClassifyCounts counts;  // particles total/owned/boundary/dropped, cells per state
  double seconds_classify = 0, seconds_compact = 0, seconds_pipeline = 0, seconds_total = 0;
};

// Everything a render step produced, valid during Pipeline::process() only.
struct StepData {
  std::int64_t step = 0;
  double time = 0;
  std::span<const ParticleSphere> boundary;  // the boundary particles, packed float4
  CellStatesView cells;                      // one state byte per cell
  std::span<const Attribute> attributes;     // in boundary order
  const ParticleView* particles = nullptr;   // all particles, for outputs that want them
  const GridView* grid = nullptr;            // the grid as the solver passed it
  // The solver's walls and obstacles (Adapter::set_scenery), this process's; the version
  // changes whenever they do (0: never given).
  std::span<const ParticleSphere> scenery;
  std::uint64_t scenery_version = 0;
  // World coordinates of the boundary spheres' (0, 0, 0) (Classification::origin): the same on
  // every step and every rank. The scenery and the cell states are in world coordinates.
  std::array<double, 3> origin{0, 0, 0};
};

// What the runtime plugs in behind the adapter: rendering and outputs.
class Pipeline {
 public:
  virtual ~Pipeline() = default;
  // Called on every step that passes the adapter's render_every filter, before any work:
  // must be cheap and must not allocate. Lets the runtime's own triggers decide; true also
  // where they must look at the step's particles to decide (confirm_step).
  virtual bool wants_step(std::int64_t /*step*/, double /*time*/) { return true; }
  // Called after wants_step() said yes, with the step's particles, before the classification:
  // false when the triggers that look at the particles (conditions on their attributes) leave
  // the step with nothing to do. Must not allocate; in an MPI job every rank calls it on the
  // same steps.
  virtual bool confirm_step(std::int64_t /*step*/, double /*time*/,
                            const ParticleView& /*particles*/) {
    return true;
  }
  // Called on every step the pipeline wants, after the classification and again after
  // process(), with the status here (ok, or why it failed). A pipeline spread over MPI ranks
  // returns the step's status on all of them (a failure on any rank, naming it), so that
  // every rank skips a failed step together and none waits for another; one process returns
  // `local`.
  virtual Status agree(const Status& local) { return local; }
  // Called on render steps before the classification until the boundary spheres' frame origin
  // is chosen (ClassifyOptions::origin), with a point of this process's fluid (NaN where it has
  // none): the point every process chooses from. A pipeline spread over MPI ranks returns the
  // same on all (per axis the least of the ranks' points: within the fluid's box); one process
  // returns `local`.
  virtual std::array<double, 3> agree_point(const std::array<double, 3>& local) { return local; }
  // False on the processes that must not log the step's failures (every MPI rank but one).
  virtual bool reports_failures() const { return true; }
  // A render step's data. Exceptions are caught and reported as pipeline_failed; a returned
  // error status is passed on as it is.
  virtual Status process(const StepData& data, const StepStats& stats) = 0;
  // The solver says `step` is its last (Adapter::execute_last), before asking wants_step for
  // it: triggers with `last` fire on it.
  virtual void mark_last_step(std::int64_t /*step*/) {}
  // Completes what is pending (files still being written). Called by Adapter::finish() and
  // when the adapter goes; a second call does nothing.
  virtual void finish() {}
  // What the pipeline did, in a line for the solver's terminal (frames, files, time).
  virtual std::string summary() const { return {}; }
};

class Adapter {
 public:
  // Throws voxspan::Error naming the bad option (e.g. no spacing and no full count).
  explicit Adapter(AdapterOptions options);
  ~Adapter();
  Adapter(const Adapter&) = delete;
  Adapter& operator=(const Adapter&) = delete;
  Adapter(Adapter&&) noexcept;
  Adapter& operator=(Adapter&&) noexcept;

  void set_pipeline(std::shared_ptr<Pipeline> pipeline);

  // The solver's walls and obstacles, copied: the views draw them as opaque solids (docs/
  // runtime.md, "Scenery"). Walls that stand still are given once; moving ones again whenever
  // they have moved (each call costs one copy and makes the views draw them anew). Radii as the
  // classification takes them (the view's, the options' radius, or the spacing). Particles with
  // a NaN or infinite position or a NaN, infinite or negative radius are left out and counted;
  // returns the count kept. Throws voxspan::Error when no radius can be found. Under MPI each rank
  // gives its own part.
  std::size_t set_scenery(const ParticleView& scenery);
  // The scenery kept from the last set_scenery (empty when none was given).
  std::span<const ParticleSphere> scenery() const;

  // The per-step call. Returns ok on a step that is not a render step. Never throws; errors
  // are logged (voxspan/log.h) and returned.
  Status execute(std::int64_t step, double time, const ParticleView& particles,
                 const GridView& grid = GridView()) noexcept;

  // execute() for the solver's last step: the triggers with `last: true` fire on it.
  Status execute_last(std::int64_t step, double time, const ParticleView& particles,
                      const GridView& grid = GridView()) noexcept;
  // Waits for the pipeline's pending work (files being written); the destructor does it too,
  // and so does the process's exit (exit(), a return from main) for an adapter never destroyed.
  // A drain, not an end: steps may follow it (the files of the steps before are complete
  // then, for a solver that reads them back); the summary covers every step so far.
  void finish() noexcept;
  // The pipeline's summary line (empty without a pipeline).
  std::string summary() const;
  std::shared_ptr<Pipeline> pipeline() const;
  // Wall time of all render steps (classification, compaction and the pipeline) and of the
  // steps whose conditions were checked, seconds.
  double seconds_in_situ() const;

  // Whether execute(step, time, ...) would do any work: a render step, or a step whose
  // triggers look at the particles first (conditions, docs/runtime.md), which may render.
  // On such a step the solver passes every attribute the conditions name.
  bool is_render_step(std::int64_t step, double time) const noexcept;

  // The stats of the latest render step (step == -1 before the first).
  const StepStats& last_stats() const;
  // The classification of the latest render step that got that far.
  const Classification& last_classification() const;
  const AdapterOptions& options() const;

  std::int64_t steps_seen() const;
  std::int64_t render_steps() const;
  std::int64_t failed_steps() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxspan
