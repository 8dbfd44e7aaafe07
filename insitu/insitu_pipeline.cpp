#include "insitu/insitu_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <sstream>
#include <thread>

#include "insitu/host_memory.h"
#include "insitu/output_folder.h"
#include "insitu/schedule.h"
#include "insitu/step_record.h"
#include "insitu/view_framing.h"
#include "insitu/view_renderer.h"
#include "render/gl/context.h"
#include "render/gl/info.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

gl::ContextOptions context_options(const RendererConfig& r) {
  gl::ContextOptions o;
  switch (r.platform) {
    case GlPlatformChoice::automatic: o.platform = gl::Platform::automatic; break;
    case GlPlatformChoice::nvidia: o.platform = gl::Platform::nvidia; break;
    case GlPlatformChoice::device: o.platform = gl::Platform::device; break;
    case GlPlatformChoice::surfaceless: o.platform = gl::Platform::surfaceless; break;
  }
  o.debug = r.debug;
  return o;
}

// The log level from the config, before anything else logs.
Config with_log_level(const Config& config) {
  LogLevel level;
  if (!config.log_level.empty() && parse_log_level(config.log_level, level)) set_log_level(level);
  return config;
}

struct ViewState {
  ViewConfig config;
  ViewRenderSettings settings;
  ViewFraming framing;
  FrameStats stats;
  ViewImage scratch;  // the picture when no PNG is due (or no slot was free)

  ViewState(const ViewConfig& view, const RendererConfig& renderer, double spacing)
      : config(view), settings(view_render_settings(view, renderer, spacing)), framing(view) {}
};

}  // namespace

struct InsituPipeline::Impl {
  const Config config;
  const double spacing;
  Schedule schedule;
  StepPlan plan;
  std::int64_t planned_step = std::numeric_limits<std::int64_t>::min();
  double planned_time = 0;
  std::int64_t last_step = std::numeric_limits<std::int64_t>::min();

  gl::Context context;
  std::thread::id gl_thread = std::this_thread::get_id();
  gl::ShaderLibrary shaders;
  ViewRenderer renderer;
  gl::PassTimer timer;
  std::vector<ViewState> views;
  StepOutputs outputs;
  std::vector<ViewRecordSource> view_sources;  // the views' names and stats, for the record
  StatsRecord record;
  PipelineTotals totals;
  std::size_t largest_view_pixels = 0;

  Impl(const Config& c, double particle_spacing)
      : config(with_log_level(c)), spacing(particle_spacing), schedule(config),
        context(prepared(config)), renderer(shaders), timer(context.has_gpu_timers()),
        views(make_views(config, particle_spacing)),
        outputs(config, view_names(config), particle_spacing) {
    for (const ViewState& v : views) {
      view_sources.push_back({&v.config.name, &v.stats});
      largest_view_pixels = std::max(largest_view_pixels, std::size_t(v.config.width) * std::size_t(v.config.height));
    }
  }

  // Folders first: a bad folder is reported before the (slower) GL start-up.
  static gl::ContextOptions prepared(const Config& config) {
    prepare_output_folders(config);
    return context_options(config.renderer);
  }
  static std::vector<ViewState> make_views(const Config& config, double spacing) {
    std::vector<ViewState> v;
    v.reserve(config.views.size());
    for (const ViewConfig& view : config.views) v.emplace_back(view, config.renderer, spacing);
    return v;
  }
  static std::vector<std::string> view_names(const Config& config) {
    std::vector<std::string> names;
    for (const ViewConfig& view : config.views) names.push_back(view.name);
    return names;
  }

  void make_current() {
    if (std::this_thread::get_id() == gl_thread) return;
    context.make_current();
    gl_thread = std::this_thread::get_id();
  }

  // Renders every view; the first failure's message comes back (empty when all went well).
  std::string render_views(const StepData& data, bool png) {
    std::string failure;
    for (std::size_t i = 0; i < views.size(); ++i) {
      ViewState& v = views[i];
      StepOutputs::Frame* frame = png ? outputs.acquire_frame() : nullptr;
      ViewImage& image = frame != nullptr ? frame->image : v.scratch;
      image.rgba.reserve(4 * largest_view_pixels);  // a pooled frame serves every view
      zero(v.stats);
      try {
        const Camera camera = v.framing.update(data.boundary);
        renderer.render(v.settings, camera, v.framing.box(), data.boundary, data.cells, timer,
                        v.stats, image);
        timer.collect(v.stats);
        for (const FrameStats::Pass& pass : v.stats.passes) totals.passes.add_time(pass.name, pass.ms);
        ++totals.frames;
      } catch (const std::exception& e) {
        timer.collect(v.stats);  // closes the scopes of the failed frame
        ++totals.failed_views;
        if (failure.empty()) failure = "view " + v.config.name + ": " + e.what();
        outputs.release_frame(frame);
        continue;
      }
      if (frame != nullptr) totals.png_submitted += outputs.submit_png(i, data.step, frame);
    }
    return failure;
  }

  void write_snapshots(const StepData& data, const StepPlan& p, std::string& failure) {
    auto guarded = [&](const char* what, auto submit) {
      try {
        return submit();
      } catch (const std::exception& e) {
        if (failure.empty()) failure = std::string(what) + ": " + e.what();
        return false;
      }
    };
    if (p.vdb) totals.vdb_submitted += guarded("VDB snapshot", [&] { return outputs.submit_vdb(data); });
    if (p.vtk) totals.vtk_submitted += guarded("VTK files", [&] { return outputs.submit_vtk(data); });
  }

  void write_stats(const StepData& data, const StepStats& stats, double render_ms,
                   double outputs_ms, Clock::time_point t0) {
    record.zero();
    const WriterStats writer = outputs.writer_stats();
    const StepRecordInput in{data.step, data.time, &stats, render_ms, outputs_ms,
                             1e3 * seconds_since(t0), view_sources, &writer, host_memory()};
    fill_step_record(in, record);
    totals.stats_submitted += outputs.submit_stats(record);
  }
};

InsituPipeline::InsituPipeline(const Config& config, double particle_spacing)
    : impl_(std::make_unique<Impl>(config, particle_spacing)) {
  log_info("in situ: ", description());
}

InsituPipeline::~InsituPipeline() {
  try {
    finish();
  } catch (...) {
  }
}

bool InsituPipeline::wants_step(std::int64_t step, double time) {
  Impl& m = *impl_;
  // Idempotent per step: is_render_step() and execute() may both ask.
  if (step != m.planned_step || time != m.planned_time) {
    m.plan = m.schedule.plan(step, time, step == m.last_step);
    m.planned_step = step;
    m.planned_time = time;
  }
  return m.plan.any();
}

void InsituPipeline::mark_last_step(std::int64_t step) {
  Impl& m = *impl_;
  m.last_step = step;
  if (step != m.planned_step) return;
  // Already planned without knowing it was the last: add the `last` conditions.
  const StepPlan last = m.schedule.plan(step, m.planned_time, true);
  m.plan.render |= last.render;
  m.plan.png |= last.png;
  m.plan.stats |= last.stats;
  m.plan.vdb |= last.vdb;
  m.plan.vtk |= last.vtk;
}

Status InsituPipeline::process(const StepData& data, const StepStats& stats) {
  Impl& m = *impl_;
  const auto t0 = Clock::now();
  if (data.step != m.planned_step) wants_step(data.step, data.time);
  const StepPlan p = m.plan;
  m.make_current();

  std::string failure;
  double render_ms = 0;
  if (p.render) {
    const auto t = Clock::now();
    failure = m.render_views(data, p.png);
    ++m.totals.render_steps;
    render_ms = 1e3 * seconds_since(t);
  }
  const auto t_out = Clock::now();
  m.write_snapshots(data, p, failure);
  const double outputs_ms = 1e3 * seconds_since(t_out);
  if (p.stats) m.write_stats(data, stats, render_ms, outputs_ms, t0);

  m.totals.seconds_render += 1e-3 * render_ms;
  m.totals.seconds_outputs += seconds_since(t_out);
  m.totals.seconds_process += seconds_since(t0);
  if (failure.empty()) return {};
  return {StatusCode::pipeline_failed, failure};
}

void InsituPipeline::finish() { impl_->outputs.drain(); }

PipelineTotals InsituPipeline::totals() const {
  PipelineTotals t = impl_->totals;
  t.written = impl_->outputs.counts();
  t.writer = impl_->outputs.writer_stats();
  return t;
}

const Config& InsituPipeline::config() const { return impl_->config; }

std::string InsituPipeline::description() const {
  const Impl& m = *impl_;
  std::ostringstream s;
  s << m.context.description() << ", " << m.views.size() << (m.views.size() == 1 ? " view" : " views");
  for (std::size_t i = 0; i < m.views.size(); ++i) {
    const ViewConfig& v = m.views[i].config;
    s << (i ? ", " : " (") << v.name << " " << shading_mode_name(v.shading) << " " << v.width << "x"
      << v.height << (i + 1 == m.views.size() ? ")" : "");
  }
  const OutputsConfig& o = m.config.outputs;
  s << "; outputs in " << m.config.output_folder << ":";
  if (o.png.enabled) s << " png";
  if (o.stats.enabled) s << " stats";
  if (o.vdb.enabled) s << " vdb";
  if (o.vtk.enabled) s << " vtk";
  return s.str();
}

std::string InsituPipeline::summary() const {
  const PipelineTotals t = totals();
  std::ostringstream s;
  s.precision(3);
  s << t.render_steps << " render steps, " << t.frames << " views rendered";
  if (t.failed_views) s << " (" << t.failed_views << " failed)";
  s << "; written: " << t.written.png << " PNG, " << t.written.vdb << " VDB, " << t.written.vtk
    << " VTK sets, " << t.written.stats << " stats lines";
  if (t.writer.failed) s << "; " << t.writer.failed << " files failed (first: " << t.writer.first_error << ")";
  if (t.writer.dropped) s << "; " << t.writer.dropped << " files dropped (writer queue full)";
  if (t.writer.waits) s << "; the solver waited " << t.writer.waits << " times for a full writer queue";
  s << "; on the solver's thread " << t.seconds_process << " s (render " << t.seconds_render
    << " s, outputs " << t.seconds_outputs << " s), writer thread " << t.written.writer_seconds
    << " s";
  return s.str();
}

}  // namespace voxspan
