// The Adapter: trigger check, classification and compaction on render steps, per-step stats,
// and the hand-off to the pipeline the runtime plugs in. Nothing escapes execute(): every
// failure becomes a Status and a log line.
#include "voxspan/adapter.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <new>
#include <set>
#include <utility>

#include "voxspan/error.h"
#include "voxspan/stopwatch.h"
#include "voxspan/log.h"
#include "floating_point_traps.h"

namespace voxspan {
namespace {

void check_options(const AdapterOptions& options) {
  const ClassifyOptions& o = options.classify;
  auto non_negative = [](const char* name, double v) {
    if (!(v >= 0) || !std::isfinite(v))
      throw make_error("adapter option ", name, " = ", v, " must be a finite number >= 0");
  };
  if (options.render_every < 0)
    throw make_error("adapter option render_every = ", options.render_every, " must be >= 0");
  non_negative("particle_spacing", o.particle_spacing);
  non_negative("radius", o.radius);
  non_negative("cell_size", o.cell_size);
  for (const double c : o.origin)
    if (!std::isfinite(c))
      throw make_error("adapter option origin has a coordinate ", c, ": it must be finite");
  if (o.full_count < 0)
    throw make_error("adapter option full_count = ", o.full_count, " must be >= 0");
  if (!(o.full_fraction > 0) || !std::isfinite(o.full_fraction))
    throw make_error("adapter option full_fraction = ", o.full_fraction, " must be > 0");
  if (o.full_count == 0 && o.particle_spacing == 0)
    throw make_error(
        "adapter options: set particle_spacing (the rest spacing of the "
        "particles) or full_count (particles in a full cell)");
  std::set<std::string> names;
  for (const std::string& name : o.attributes) {
    if (name.empty()) throw make_error("adapter option attributes: an empty attribute name");
    if (!names.insert(name).second)
      throw make_error("adapter option attributes: '", name, "' is listed twice");
  }
}

// Records a failure; the message is dropped if even that allocation fails.
void fail(Status& status, StatusCode code, const char* message) noexcept {
  status.code = code;
  try {
    status.message = message;
  } catch (...) {
    status.message.clear();
  }
}

// Logging must not throw out of execute() either.
template <class... Parts> void log_quietly(LogLevel level, const Parts&... parts) noexcept {
  try {
    log(level, parts...);
  } catch (...) {}
}

// A particle spacing off by a factor (other units, h for dx) gives blobs or dots with no error:
// the cells' occupancy against what a cell holds at rest density says so, once, on the first
// step with 1 000 particles. Returns whether it looked.
bool checked_spacing(std::int64_t step, const ClassifyCounts& c, double spacing) noexcept {
  const std::size_t valid =
      c.particles - std::min(c.particles, c.dropped_nonfinite + c.not_in_grid);
  const std::size_t occupied = c.cells_partial + c.cells_full;
  if (valid < 1000 || occupied == 0 || c.full_count < 1 || !(spacing > 0)) return false;
  const double mean = double(valid) / double(occupied), ratio = mean / c.full_count;
  if (ratio > 4)
    log_quietly(LogLevel::warning, "step ", step, ": the grid's cells hold ", mean,
                " particles on average, ", ratio, " times what a cell holds at rest density at ",
                "particle_spacing ", spacing, ": unless the fluid is compressed that much, the ",
                "spacing is too large (surfaces merge into one blob); check its units");
  else if (mean < 1.25 && c.full_count >= 8)
    log_quietly(LogLevel::warning, "step ", step, ": the grid's cells hold ", mean,
                " particles on average where one at rest density holds ", c.full_count,
                " at particle_spacing ", spacing, ": unless the fluid is spray, the spacing is ",
                "too small (surfaces break into dots); check its units");
  return true;
}

// A point of the fluid to measure the boundary spheres from (ClassifyOptions::origin): the first
// particle with a finite position (floats relative to any point of the fluid hold positions to
// its extent's precision); NaN when none has one. Reads a handful of particles, not all.
std::array<double, 3> some_position(const ParticleView& particles) noexcept {
  bool present = true;
  for (int a = 0; a < 3; ++a) present = present && particles.axis(a).present();
  for (std::size_t i = 0; present && i < particles.size(); ++i)
    if (particles.position_finite(i)) return particles.position(i);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {nan, nan, nan};  // missing positions are the classification's to refuse
}

// The pipelines a process has made. A solver that exits without finish() (a C program returning
// from main, exit() on an error path, Fortran's error stop) would otherwise lose the files still
// queued and race its writer thread against the static destructors that exit() runs. Never
// destroyed: the exit handler reads it after other statics are gone.
struct OpenPipelines {
  std::mutex mutex;
  std::vector<std::weak_ptr<Pipeline>> pipelines;
};

OpenPipelines& open_pipelines() {
  static auto* open = new OpenPipelines;
  return *open;
}

void finish_open_pipelines() {
  const FloatingPointTrapsHeld held;
  OpenPipelines& open = open_pipelines();
  const std::lock_guard lock(open.mutex);
  for (const std::weak_ptr<Pipeline>& p : open.pipelines)
    if (const std::shared_ptr<Pipeline> pipeline = p.lock()) {
      try {
        pipeline->finish();
      } catch (...) {
        // exit() is under way: nothing is left to report to
      }
    }
  open.pipelines.clear();
}

// Registers the handler again for each pipeline: exit() runs handlers and static destructors
// newest first, so the newest registration runs before the statics the pipeline made (OpenVDB's,
// the GL driver's).
void finish_at_exit(const std::shared_ptr<Pipeline>& pipeline) {
  OpenPipelines& open = open_pipelines();
  {
    const std::lock_guard lock(open.mutex);
    std::erase_if(open.pipelines, [](const std::weak_ptr<Pipeline>& p) { return p.expired(); });
    open.pipelines.push_back(pipeline);
  }
  std::atexit(finish_open_pipelines);
}

}  // namespace

struct Adapter::Impl {
  AdapterOptions options;
  Classifier classifier;
  std::shared_ptr<Pipeline> pipeline;
  StepStats stats;
  bool spacing_checked = false;
  // The solver's cell lists are checked against the positions (ClassifyOptions::validate) on
  // render steps until one passes: a grid with the wrong origin, cell size or index base, or
  // particles not stored in its order, would otherwise give a wrong picture and no word.
  bool grid_checked = false;
  bool nonfinite_told = false;
  // The last render step, to say once that a step came twice (its files are written again).
  std::int64_t last_render_step = std::numeric_limits<std::int64_t>::min();
  bool repeat_told = false;
  std::int64_t steps_seen = 0, render_steps = 0, failed_steps = 0;
  double seconds_in_situ = 0;
  std::vector<ParticleSphere> scenery;
  std::uint64_t scenery_version = 0;
  // The boundary spheres' origin (options.classify.origin) is chosen once, on the first render
  // step with a particle on any rank, unless the solver gave one: one frame for every step,
  // rank and output.
  bool origin_chosen = false;

  // Throws what the classification throws (bad input).
  const Classification& classify(std::int64_t step, const ParticleView& particles,
                                 const GridView& grid);
  // The classification with the grid's cell lists checked (grid_checked).
  const Classification& checked_grid(const ParticleView& particles, const GridView& grid);
  // The step's status on every rank of the pipeline (its own when alone).
  void agree();
  // options.classify.origin near the fluid, the same on every rank (collective).
  void choose_origin(const ParticleView& particles) noexcept;
  // Whether the pipeline's triggers that look at the particles want the step.
  bool confirm(std::int64_t step, double time, const ParticleView& particles) noexcept;
  void process(std::int64_t step, double time, const Classification& c,
               const ParticleView& particles, const GridView& grid);
};

const Classification& Adapter::Impl::classify(std::int64_t step, const ParticleView& particles,
                                              const GridView& grid) {
  const bool solver_lists = grid.layout() == GridView::Layout::cell_ranges ||
                            grid.layout() == GridView::Layout::cell_index;
  const bool check_grid = solver_lists && !grid_checked && !options.classify.validate;
  const Classification& c = check_grid ? checked_grid(particles, grid)
                                       : classifier.run(particles, grid, options.classify);
  stats.counts = c.counts;
  stats.seconds_classify = c.seconds_classify;
  stats.seconds_compact = c.seconds_compact;
  stats.rendered = true;
  // Said on the first step that has them; each step's stats line counts them
  // (dropped_nonfinite), where a line a step would bury the solver's own output.
  if (c.counts.dropped_nonfinite > 0 && !std::exchange(nonfinite_told, true))
    log_quietly(LogLevel::warning, "step ", step, ": left out ", c.counts.dropped_nonfinite,
                " particles with a NaN or infinite position, or a NaN, infinite or negative "
                "radius (said once; the stats lines count them each step: dropped_nonfinite)");
  if (c.counts.not_in_grid > 0 &&
      c.counts.not_in_grid + c.counts.dropped_nonfinite >= c.counts.particles) {
    // Every finite particle outside the grid: a picture of nothing would hide the mismatch.
    const GridGeometry& g = c.geometry;
    throw make_error("none of the ", c.counts.not_in_grid, " particles is in a cell of the grid (",
                     g.dims[0], " x ", g.dims[1], " x ", g.dims[2], " cells of ", g.cell_size,
                     " from (", g.origin[0], ", ", g.origin[1], ", ", g.origin[2],
                     ")): the grid's geometry or cell arrays do not match the positions (a wrong "
                     "origin, cell size or stride?)");
  }
  if (c.counts.not_in_grid > 0)
    log_quietly(LogLevel::warning, "step ", step, ": ", c.counts.not_in_grid,
                " particles are in no cell of the grid and were left out");
  if (!spacing_checked)
    spacing_checked = checked_spacing(step, c.counts, options.classify.particle_spacing);
  return c;
}

const Classification& Adapter::Impl::checked_grid(const ParticleView& particles,
                                                  const GridView& grid) {
  ClassifyOptions validating = options.classify;
  validating.validate = true;
  try {
    const Classification& c = classifier.run(particles, grid, validating);
    grid_checked = true;
    return c;
  } catch (const GridMismatch& e) {  // others (an attribute) go as they are
    throw make_error(e.what(),
                     " (the solver's grid does not match its particles: its origin, cell size, "
                     "index base, or the particles' order; checked until a render step passes)");
  }
}

void Adapter::Impl::agree() {
  try {
    Status agreed = pipeline->agree(stats.status);
    if (stats.status.ok() && !agreed.ok()) stats.status = std::move(agreed);
  } catch (const std::exception& e) {
    fail(stats.status, StatusCode::internal_error, e.what());
  }
}

void Adapter::Impl::choose_origin(const ParticleView& particles) noexcept {
  std::array<double, 3> point = some_position(particles);
  if (pipeline) {
    try {
      point = pipeline->agree_point(point);
    } catch (const std::exception& e) {
      log_quietly(LogLevel::error, "choosing the particles' frame origin: ", e.what());
      return;
    }
  }
  if (!std::isfinite(point[0])) return;  // no particle anywhere yet: the next render step
  const ClassifyOptions& o = options.classify;
  const double unit = o.particle_spacing > 0 ? o.particle_spacing
                      : o.radius > 0         ? o.radius
                                             : o.cell_size;
  options.classify.origin = frame_origin_near(point, unit);
  origin_chosen = true;
}

bool Adapter::Impl::confirm(std::int64_t step, double time,
                            const ParticleView& particles) noexcept {
  if (!pipeline) return true;
  try {
    return pipeline->confirm_step(step, time, particles);
  } catch (const std::exception& e) {
    log_quietly(LogLevel::error, "step ", step, ": the pipeline's trigger failed (", e.what(),
                "); step skipped");
  } catch (...) {
    log_quietly(LogLevel::error, "step ", step, ": the pipeline's trigger threw; step skipped");
  }
  return false;
}

void Adapter::Impl::process(std::int64_t step, double time, const Classification& c,
                            const ParticleView& particles, const GridView& grid) {
  const StepData data{step,       time,  c.boundary, c.cell_states(), c.attributes,
                      &particles, &grid, scenery,    scenery_version, c.origin};
  const Stopwatch t0;
  try {
    Status s = pipeline->process(data, stats);
    if (!s.ok()) stats.status = std::move(s);
  } catch (const std::exception& e) {
    fail(stats.status, StatusCode::pipeline_failed, e.what());
  } catch (...) {
    fail(stats.status, StatusCode::pipeline_failed, "unknown exception in the pipeline");
  }
  stats.seconds_pipeline = t0.seconds();
}

Adapter::Adapter(AdapterOptions options) : impl_(std::make_unique<Impl>()) {
  const FloatingPointTrapsHeld held;
  check_options(options);
  impl_->options = std::move(options);
  const std::array<double, 3>& given = impl_->options.classify.origin;
  impl_->origin_chosen = given[0] != 0 || given[1] != 0 || given[2] != 0;
}
Adapter::~Adapter() {
  const FloatingPointTrapsHeld held;  // the pipeline's GL objects go with it
  if (impl_) finish();
  impl_.reset();
}
Adapter::Adapter(Adapter&&) noexcept = default;
Adapter& Adapter::operator=(Adapter&&) noexcept = default;

void Adapter::set_pipeline(std::shared_ptr<Pipeline> pipeline) {
  if (pipeline) finish_at_exit(pipeline);
  impl_->pipeline = std::move(pipeline);
}

std::size_t Adapter::set_scenery(const ParticleView& scenery) {
  Impl& m = *impl_;
  const std::size_t dropped = pack_spheres(scenery, m.options.classify, m.scenery);
  ++m.scenery_version;
  if (dropped > 0)
    log_quietly(
        LogLevel::warning, "scenery: left out ", dropped,
        " particles with a NaN or infinite position, or a NaN, infinite or negative radius");
  return m.scenery.size();
}

std::span<const ParticleSphere> Adapter::scenery() const { return impl_->scenery; }

bool Adapter::is_render_step(std::int64_t step, double time) const noexcept {
  if (!impl_) return false;  // moved from
  const std::int64_t every = impl_->options.render_every;
  if (every <= 0 || step % every != 0) return false;
  if (!impl_->pipeline) return true;
  try {
    return impl_->pipeline->wants_step(step, time);
  } catch (...) {
    log_quietly(LogLevel::error, "step ", step, ": the pipeline's trigger threw; step skipped");
    return false;
  }
}

Status Adapter::execute(std::int64_t step, double time, const ParticleView& particles,
                        const GridView& grid) noexcept {
  if (!impl_) {
    log_quietly(LogLevel::error, "step ", step, ": execute() on an adapter that was moved from");
    return {StatusCode::invalid_input, "execute() on an adapter that was moved from"};
  }
  Impl& m = *impl_;
  ++m.steps_seen;
  if (!is_render_step(step, time)) return {};
  const FloatingPointTrapsHeld held;
  const Stopwatch t0;
  if (!m.confirm(step, time, particles)) {
    m.seconds_in_situ += t0.seconds();
    return {};
  }

  ++m.render_steps;
  if (step == m.last_render_step && !std::exchange(m.repeat_told, true))
    log_quietly(LogLevel::warning, "step ", step,
                " came twice: its files are written again and its stats line repeats (a solver "
                "calls execute once a step; said once)");
  m.last_render_step = step;
  StepStats& s = m.stats;
  s.step = step;
  s.time = time;
  s.rendered = false;
  s.status = {};
  s.counts = {};
  s.seconds_classify = s.seconds_compact = s.seconds_pipeline = 0;
  // Collective: before anything that may fail on one rank alone.
  if (!m.origin_chosen) m.choose_origin(particles);
  const Classification* c = nullptr;
  try {
    if (!std::isfinite(time))
      throw make_error("the simulated time is ", time,
                       ": pass the solver's time (finite; 0 when it keeps none)");
    c = &m.classify(step, particles, grid);
  } catch (const Error& e) {
    fail(s.status, StatusCode::invalid_input, e.what());
  } catch (const std::bad_alloc&) {
    fail(s.status, StatusCode::internal_error, "out of memory");
    try {  // the sizes that asked for it, where memory is left to say them
      const GridGeometry& g = grid.geometry();
      std::string what =
          "out of memory classifying " + std::to_string(particles.size()) + " particles";
      if (grid.layout() != GridView::Layout::none)
        what += " on a grid of " + std::to_string(g.dims[0]) + " x " + std::to_string(g.dims[1]) +
                " x " + std::to_string(g.dims[2]) + " cells";
      fail(s.status, StatusCode::internal_error, what.c_str());
    } catch (...) {  // "out of memory" stands
    }
  } catch (const std::exception& e) {
    fail(s.status, StatusCode::internal_error, e.what());
  } catch (...) {
    fail(s.status, StatusCode::internal_error, "unknown exception");
  }
  // With ranks, a failure on one is the step's failure on all: they skip it together. After the
  // pipeline they agree again, for what fails on one rank alone (the root's shading, outputs).
  if (m.pipeline) m.agree();
  if (m.pipeline && s.status.ok()) {
    m.process(step, time, *c, particles, grid);
    m.agree();
  }
  s.seconds_total = t0.seconds();
  m.seconds_in_situ += s.seconds_total;
  if (!s.status.ok()) {
    ++m.failed_steps;
    // One line for the job, not one per rank.
    if (!m.pipeline || m.pipeline->reports_failures())
      log_quietly(LogLevel::error, "step ", step, ": ", s.status.message);
  }
  try {
    return s.status;
  } catch (...) {
    return Status{s.status.code, {}};
  }
}

Status Adapter::execute_last(std::int64_t step, double time, const ParticleView& particles,
                             const GridView& grid) noexcept {
  if (impl_ && impl_->pipeline) {
    try {
      impl_->pipeline->mark_last_step(step);
    } catch (...) {
      log_quietly(LogLevel::error, "step ", step, ": the pipeline could not mark the last step");
    }
  }
  return execute(step, time, particles, grid);
}

void Adapter::finish() noexcept {
  if (!impl_ || !impl_->pipeline) return;
  const FloatingPointTrapsHeld held;
  try {
    impl_->pipeline->finish();
  } catch (const std::exception& e) {
    log_quietly(LogLevel::error, "finishing the pipeline: ", e.what());
  } catch (...) {
    log_quietly(LogLevel::error, "finishing the pipeline: unknown exception");
  }
}

std::string Adapter::summary() const {
  return impl_->pipeline ? impl_->pipeline->summary() : std::string();
}

std::shared_ptr<Pipeline> Adapter::pipeline() const { return impl_->pipeline; }
double Adapter::seconds_in_situ() const { return impl_->seconds_in_situ; }

const StepStats& Adapter::last_stats() const { return impl_->stats; }
const Classification& Adapter::last_classification() const { return impl_->classifier.result(); }
const AdapterOptions& Adapter::options() const { return impl_->options; }
std::int64_t Adapter::steps_seen() const { return impl_->steps_seen; }
std::int64_t Adapter::render_steps() const { return impl_->render_steps; }
std::int64_t Adapter::failed_steps() const { return impl_->failed_steps; }

}  // namespace voxspan
