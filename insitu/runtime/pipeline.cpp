#include "insitu/runtime/pipeline.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include "insitu/outputs/formats/stats_record.h"
#include "insitu/parallel/communicator.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/host_memory.h"
#include "insitu/runtime/live_page.h"
#include "insitu/runtime/output_folder.h"
#include "insitu/runtime/rank_stats.h"
#include "insitu/runtime/registry.h"
#include "insitu/runtime/schedule.h"
#include "insitu/runtime/step_record.h"
#include "insitu/runtime/step_scene.h"
#include "insitu/views/legend.h"
#include "insitu/views/span_compositor.h"
#include "insitu/views/view.h"
#include "insitu/views/view_framing.h"
#include "render/backend.h"
#include "render/gl/shader_library.h"
#include "voxspan/error.h"
#include "voxspan/log.h"
#include "voxspan/stopwatch.h"

namespace voxspan {
namespace {

// Adds a failure to a step's: every view and output that failed is named, not the first alone.
void add_failure(std::string& failure, const std::string& what) {
  if (what.empty()) return;
  if (!failure.empty()) failure += "; ";
  failure += what;
}

// The log level from the config, before anything else logs.
Config with_log_level(const Config& config) {
  LogLevel level;
  if (!config.log_level.empty() && parse_log_level(config.log_level, level)) set_log_level(level);
  return config;
}

// The run's hold on output_folder (on the root, where an output writes under it), taken before
// anything is written there; a folder that holds an earlier run's files is said once.
std::unique_ptr<FolderLock> lock_output_folder(const Config& config, const Communicator* comm,
                                               std::vector<std::filesystem::path>& made) {
  if (comm != nullptr && !comm->root()) return nullptr;
  const bool under = std::any_of(config.outputs.begin(), config.outputs.end(), [&](const auto& o) {
    return o.settings->enabled && !std::filesystem::path(o.settings->folder).is_absolute();
  });
  if (!under) return nullptr;
  const std::filesystem::path folder = config.output_folder;
  std::error_code ec;
  bool earlier = false;  // a file other than a lock a killed run left (one is enough to know)
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.path().filename() != ".voxspan.lock") {
      earlier = true;
      break;
    }
  made = prepare_output_folder(folder, "output_folder");
  auto lock = std::make_unique<FolderLock>(folder, "output_folder");
  if (earlier)
    log_warning("output folder ", folder.string(),
                " holds files of an earlier run: files of the "
                "same names are replaced, the others stay (a new output_folder keeps runs apart)");
  return lock;
}

// The run's hold on each output's own folder outside output_folder (an absolute `folder`): two
// runs that share one would replace each other's files.
void lock_absolute_folders(const Config& config, const Communicator* comm,
                           std::vector<std::unique_ptr<FolderLock>>& locks) {
  if (comm != nullptr && !comm->root()) return;
  std::vector<std::filesystem::path> held;
  const std::filesystem::path under = std::filesystem::weakly_canonical(config.output_folder);
  for (const ConfiguredOutput& o : config.outputs) {
    if (!o.settings->enabled || !std::filesystem::path(o.settings->folder).is_absolute()) continue;
    const std::filesystem::path folder = std::filesystem::weakly_canonical(o.settings->folder);
    const auto [inside, _] =
        std::mismatch(under.begin(), under.end(), folder.begin(), folder.end());
    if (inside == under.end() || std::find(held.begin(), held.end(), folder) != held.end())
      continue;
    locks.push_back(std::make_unique<FolderLock>(folder, "outputs." + o.kind + ".folder"));
    held.push_back(folder);
  }
}

// Folders first: a bad folder is reported before the (slower) GL start-up. Ranks on one node
// take its GPUs in turn unless the config names one.
gl::ContextOptions prepared(const Config& config, const Communicator* comm,
                            std::vector<std::filesystem::path>& made,
                            std::vector<std::unique_ptr<FolderLock>>& locks) {
  std::vector<std::filesystem::path> made_above;  // output_folder and its parents, removed last
  if (auto lock = lock_output_folder(config, comm, made_above)) locks.push_back(std::move(lock));
  made = prepare_output_folders(config);
  lock_absolute_folders(config, comm, locks);
  made.insert(made.end(), made_above.begin(), made_above.end());
  const int device = config.renderer.gpu_device ? int(*config.renderer.gpu_device)
                     : comm != nullptr          ? comm->node_rank()
                                                : -1;
  return {config.renderer.platform, config.renderer.debug, device};
}

// The depth range of every rank's visible spheres: each fits the same grid.
DepthRange combine_depths(Communicator& comm, const DepthRange& local) {
  DepthRange all = local;
  double lo_hi[2] = {local.lo, -local.hi};
  comm.min(lo_hi);
  all.lo = lo_hi[0];
  all.hi = -lo_hi[1];
  std::int64_t visible[1] = {local.counts.visible};
  comm.sum(visible);
  all.counts.visible = visible[0];
  return all;
}

// Host bytes a view takes per pixel, by estimate: 77 measured (peak RSS of render_particles
// with a translucent and a refractive view, the dam break of the MPI tests, CPU renderer, from
// 640x360 to 3840x2160: picture, depth, span image, surfaces, shading), with room for deeper
// fluid. A 16384x16384 view (26 GB) used to pass the config and die of std::bad_alloc 34 s in.
constexpr double kViewBytesPerPixel = 96;

// Refuses at start-up the views that would not fit the host memory they may take.
void check_view_memory(const Config& config) {
  double limit_mib = 0;
  if (config.renderer.host_memory_mib) {
    limit_mib = *config.renderer.host_memory_mib;
  } else {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page <= 0) return;  // unknown machine: nothing to check against
    limit_mib = 0.5 * double(pages) * double(page) / double(1 << 20);
  }
  double need_mib = 0;
  std::ostringstream views;
  for (const ConfiguredView& v : config.views) {
    const double mib = kViewBytesPerPixel * double(v.settings->width) * double(v.settings->height) /
                       double(1 << 20);
    need_mib += mib;
    views << (views.tellp() > 0 ? ", " : "") << v.settings->name << " " << v.settings->width << "x"
          << v.settings->height << " " << std::lround(mib) << " MiB";
  }
  if (need_mib <= limit_mib) return;
  throw make_error("the views need about ", std::lround(need_mib), " MiB of host memory (",
                   views.str(), "; ", kViewBytesPerPixel, " bytes a pixel by estimate), over ",
                   "the ", std::lround(limit_mib), " MiB they may take (renderer.host_memory_mib",
                   config.renderer.host_memory_mib ? "" : ", by default half this machine's",
                   "): make the views smaller or raise the limit");
}

struct ViewState {
  std::string name;
  std::unique_ptr<View> view;
  ViewFraming framing;
  ViewProducts products;
  // The rendered pictures, traded out of `products` after each render (no copy), `latest`
  // held until the next: the outputs' jobs keep their own references.
  std::unique_ptr<PicturePool> pictures;
  SharedPicture latest;
  std::string caption;  // this step's, its storage kept
  Camera camera;        // this step's framing's (the live page's offset left out)
  // The orbits' (outputs.cinema): their products, their depth images' pool, their passes.
  ViewProducts orbit_products;
  std::unique_ptr<PicturePool> depths;
  FrameStats orbit_stats;
  bool jump_told = false;  // the framing's jump is said once
};

struct OutputState {
  const OutputKind* kind;
  std::unique_ptr<Output> output;  // null when the output is disabled
  // The orbits it asks for (kind->orbits), on every rank: views by index, empty when none.
  OrbitRequest orbits;
  std::vector<std::size_t> orbit_views;
};

}  // namespace

struct InsituPipeline::Impl {
  const Config config;
  const double spacing;
  Communicator* const comm;  // null in one process
  Schedule schedule;
  StepPlan plan;
  std::int64_t planned_step = std::numeric_limits<std::int64_t>::min();
  double planned_time = 0;
  std::int64_t last_step = std::numeric_limits<std::int64_t>::min();
  // agree() runs after the classification and again after process(): the ranks' steps are
  // compared in the first only (every rank runs process() exactly when all agreed in it).
  bool processed = false;

  std::vector<std::filesystem::path> made_folders;        // removed at the end if no step ran
  std::vector<std::unique_ptr<FolderLock>> folder_locks;  // released before they are
  bool processed_any = false;
  BackendChoice backend;  // its GL context, when the GL renderer draws
  std::thread::id gl_thread = std::this_thread::get_id();
  gl::ShaderLibrary shaders;
  std::unique_ptr<Recorder> recorder;  // the renderer's: every view's passes and counts
  BackgroundWriter writer;  // before the outputs, whose jobs it runs; drained before they go
  std::vector<std::string> view_names;
  std::vector<ViewState> views;
  std::vector<OutputState> outputs;
  StatsRecord record;                        // the views' sections are where their passes report
  std::vector<ViewResult> results;           // per view, this step's products for the outputs
  std::vector<OrbitPicture> orbit_pictures;  // this step's, for the outputs that asked
  PipelineTotals totals;
  bool linear_pictures = false;  // keep_linear_pictures()

  Impl(const Config& c, double particle_spacing, Communicator* communicator)
      : config(with_log_level(c)),
        spacing(particle_spacing),
        comm(communicator),
        schedule(config, communicator),
        plan(schedule.blank()),
        backend(choose_backend(config.renderer.backend,
                               prepared(config, communicator, made_folders, folder_locks))),
        recorder(make_recorder(backend)),
        writer(config.writer),
        scene(communicator) {
    for (const ConfiguredView& v : config.views) view_names.push_back(v.settings->name);
    check_view_memory(config);
    const ViewContext view_context = make_view_context();
    views.reserve(config.views.size());
    for (const ConfiguredView& v : config.views) {
      std::unique_ptr<View> view = registered_view_kind(v.kind).make(*v.settings, view_context);
      const LegendMargins clear = view->framing_margins();
      views.push_back({v.settings->name,
                       std::move(view),
                       ViewFraming(*v.settings, clear),
                       {},
                       std::make_unique<PicturePool>(pictures_per_view(config), v.settings->name),
                       {},
                       {},
                       {},
                       {},
                       std::make_unique<PicturePool>(0),
                       {}});
    }
    record.views.reserve(views.size());
    for (const ViewState& v : views) record.view(v.name);  // made once: their addresses stay
    results.resize(views.size());
    for (const ConfiguredOutput& o : config.outputs) make_output(o);
    if (config.live.enabled)
      live = std::make_unique<LivePage>(config.live, view_names, reports_here(), comm);
  }

  ~Impl() {
    live.reset();  // its references to the pictures dropped before their pools go
    writer.drain();
    for (OutputState& o : outputs)
      if (o.output) o.output->close();
    outputs.clear();  // their files closed (an unused stats file removed) before the folders
    folder_locks.clear();
    // Only where no step ran: under MPI another rank may still be writing into a folder
    // that is empty here.
    if (!processed_any) remove_empty_folders(made_folders);
  }

  // With ranks: the views fit one grid, and their span images meet in a compositor.
  ViewContext make_view_context() {
    ViewContext c{shaders, config.renderer, backend.backend, spacing, {}, {}};
    if (comm == nullptr || comm->size() == 1) return c;
    c.span_stages = [this](const MergeSettings& m) {
      std::vector<std::unique_ptr<SpanStage>> stages;
      stages.push_back(std::make_unique<SpanCompositor>(*comm, m, config.renderer.composite));
      return stages;
    };
    c.combine_ranks = [this](const DepthRange& local) { return combine_depths(*comm, local); };
    c.comm = comm;
    return c;
  }

  void make_output(const ConfiguredOutput& o) {
    const OutputKind& kind = registered_output_kind(o.kind);
    // One the config turned on that draws from views, with none (`views: []`): nothing to write.
    const bool from_views = kind.needs.any() || kind.orbits;
    if (o.settings->enabled && from_views && config.views.empty() &&
        !kind.config.defaults()->enabled)
      throw make_error("outputs.", o.kind, " is enabled but the config has no views (views: []), ",
                       "so it would write nothing: add a view, or enabled: false");
    const bool here = !kind.root_only || comm == nullptr || comm->root();
    totals.outputs.push_back({o.kind, kind.noun, o.settings->enabled && here, {}});
    OutputState state{&kind, nullptr, {}, {}};
    if (o.settings->enabled && kind.orbits) {
      state.orbits = kind.orbits(*o.settings);
      state.orbit_views = orbit_views(state.orbits.views);
      orbit_pictures.reserve(orbit_pictures.capacity() + state.orbit_views.size() *
                                                             state.orbits.phi.size() *
                                                             state.orbits.theta.size());
    }
    if (!o.settings->enabled || !here) {
      outputs.push_back(std::move(state));
      return;
    }
    // Slots per pool: the queue's jobs, one running, one being filled.
    const OutputContext c{config,
                          config.folder_of(*o.settings),
                          view_names,
                          spacing,
                          writer,
                          std::size_t(config.writer.queue_size) + 2,
                          config.writer.fsync,
                          comm};
    state.output = kind.make(*o.settings, c);
    outputs.push_back(std::move(state));
  }

  // The views an output's orbits name, by index (every view when it names none); the config
  // has checked the names (check_named_views).
  std::vector<std::size_t> orbit_views(std::span<const std::string> names) const {
    std::vector<std::size_t> chosen;
    for (std::size_t i = 0; i < views.size(); ++i)
      if (names.empty() || std::find(names.begin(), names.end(), view_names[i]) != names.end())
        chosen.push_back(i);
    return chosen;
  }

  // The orbits of every output due on this step, into orbit_pictures; each output's first
  // failure comes back (empty when all went well). Every rank renders them alike.
  std::string render_orbits(const StepData& data, const StepPlan& p) {
    orbit_pictures.clear();
    std::string failure;
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      const OutputState& out = outputs[o];
      if (!p.outputs[o] || out.orbit_views.empty()) continue;
      bool failed = false;
      const ViewNeeds needs{.picture = true, .first_hit_depth = out.orbits.depth};
      for (const std::size_t i : out.orbit_views) {
        ViewState& v = views[i];
        for (const std::int64_t phi : out.orbits.phi)
          for (const std::int64_t theta : out.orbits.theta) {
            v.orbit_stats.zero();
            recorder->record_into(v.orbit_stats);
            try {
              const Camera camera =
                  orbited(v.camera, double(phi), double(theta), v.framing.pivot());
              const bool shown = v.view->render(
                  {data, camera, v.framing.box(), needs, true, &scene.scenery(), scene.flat_axis()},
                  *recorder, v.orbit_products);
              recorder->collect();
              if (!shown) {
                drop_pending(v.orbit_products);
                continue;
              }
              OrbitPicture& picture = orbit_pictures.emplace_back();
              picture.view = i, picture.phi = phi, picture.theta = theta;
              picture.picture = take_picture(i, data, v.orbit_products);
              if (needs.first_hit_depth)
                picture.depth = v.depths->take(v.orbit_products.first_hit_depth);
            } catch (const std::exception& e) {
              recorder->collect();
              drop_pending(v.orbit_products);
              if (!std::exchange(failed, true))
                add_failure(failure, "outputs." + std::string(out.kind->config.name) + ": view " +
                                         v.name + " at phi " + std::to_string(phi) + ", theta " +
                                         std::to_string(theta) + ": " + e.what());
            }
          }
      }
    }
    return failure;
  }

  // The writer's queue, the job it runs, the latest picture; with the live page, the one its
  // mailbox holds and the one it encodes.
  static std::size_t pictures_per_view(const Config& config) {
    return std::size_t(config.writer.queue_size) + 2 + (config.live.enabled ? 2 : 0);
  }

  void make_current() {
    if (!backend.context || std::this_thread::get_id() == gl_thread) return;
    backend.context->make_current();
    gl_thread = std::this_thread::get_id();
  }

  // What the outputs due on this step, the live page and the caller want from the views.
  ViewNeeds needs(const StepPlan& p) const {
    ViewNeeds n;
    for (std::size_t i = 0; i < outputs.size(); ++i)
      if (p.outputs[i]) n |= outputs[i].kind->needs;
    n.picture |= feeds_live();  // it shows every render step's, as 8-bit sRGB
    n.linear_picture |= linear_pictures;
    return n;
  }

  // Renders every view; the failures come back, each view's (empty when all went well).
  std::string render_views(const StepData& data, const ViewNeeds& needs) {
    std::string failure;
    const Bounds step_box = scene.fluid_box(data.boundary, data.origin);
    const Scenery& scenery = scene.update_scenery(data);
    Bounds with_scenery = step_box;
    with_scenery.add(scenery.box);
    for (std::size_t i = 0; i < views.size(); ++i) {
      ViewState& v = views[i];
      FrameStats& stats = record.views[i].second;
      stats.zero();
      results[i] = {.name = v.name, .stats = &stats};
      recorder->record_into(stats);
      try {
        v.camera =
            v.framing.update(v.view->draws_scenery() ? with_scenery : step_box, scene.flat_axis());
        const Camera camera = live ? live->camera(i, v.camera, v.framing.pivot()) : v.camera;
        if (v.framing.jumped() && !v.jump_told && reports_here()) {
          v.jump_told = true;
          log_warning("view ", v.name, ": the automatic framing jumped (the fluid's box now ",
                      point_text(v.framing.box().lo), " to ", point_text(v.framing.box().hi),
                      ", over 4 times its size before); said once");
        }
        const bool shown = v.view->render(
            {data, camera, v.framing.box(), needs, false, &scenery, scene.flat_axis()}, *recorder,
            v.products);
        recorder->collect();
        for (const FrameStats::Pass& pass : stats.passes)
          totals.passes.add_time(pass.name, pass.ms);
        if (!shown) {  // an MPI rank that only voxelized: the root shows the view
          drop_pending(v.products);
          continue;
        }
        ++totals.frames;
        v.latest.reset();  // its buffer, unless a job holds it, is the one traded in
        v.latest = take_picture(i, data, v.products);
        results[i].picture = v.latest.target();
        results[i].shared_picture = &v.latest;
        if (needs.first_hit_depth) results[i].first_hit_depth = &v.products.first_hit_depth;
        if (needs.spans) results[i].spans = v.products.shaded_spans;
        if (needs.field) results[i].field = v.products.shaded_field;
        if (needs.deep) results[i].deep = v.products.shaded_deep;
      } catch (const std::exception& e) {
        recorder->collect();  // closes the scopes of the failed frame
        drop_pending(v.products);
        ++totals.failed_views;
        add_failure(failure, "view " + v.name + ": " + e.what());
      }
    }
    return failure;
  }

  // The view's picture traded into its pool, to be finished by its first reader: its pixels
  // may still be on their way from the GPU, and its caption (the fields filled from the step)
  // is drawn on them then, on the writer's thread when a file's job reads first.
  SharedPicture take_picture(std::size_t view, const StepData& data, ViewProducts& products) {
    ViewState& v = views[view];
    const std::string& pattern = config.views[view].settings->caption;
    if (!pattern.empty()) expand_caption(pattern, {data.step, data.time, v.name}, v.caption);
    const PictureFinish finish{std::exchange(products.pending_picture, nullptr),
                               pattern.empty() ? std::string_view() : v.caption, data.step};
    // With the live page, its mailbox's picture and the one its encoder reads or keeps for
    // later may both be held when the next is taken: three buffers, made at the first picture
    // rather than on the step where the encoder first lags.
    const std::size_t reserved = feeds_live() ? 3 : 0;
    if (std::exchange(products.picture_is_srgb8, false)) {
      v.pictures->reserve(products.srgb8_picture, reserved);
      return v.pictures->take(products.srgb8_picture, finish);
    }
    v.pictures->reserve(products.picture, reserved);
    return v.pictures->take(products.picture, finish);
  }

  // A failed frame's read, if it issued one, goes back unread.
  static void drop_pending(ViewProducts& products) {
    if (products.pending_picture != nullptr)
      std::exchange(products.pending_picture, nullptr)->release();
  }

  // The latest pictures finished for a caller that reads them (latest_views()); one whose
  // pixels never came is said and left out.
  void finish_latest() {
    for (std::size_t i = 0; i < views.size(); ++i) {
      if (results[i].shared_picture == nullptr) continue;
      try {
        results[i].shared_picture->get();
      } catch (const std::exception& e) {
        log_error(e.what());
        results[i].picture = nullptr;
        results[i].shared_picture = nullptr;
      }
    }
  }

  // Hands the step to every output due whose `reports_step` is as asked.
  void write_outputs(const OutputStep& step, const StepPlan& p, bool reports_step,
                     std::string& failure) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      OutputState& o = outputs[i];
      if (!p.outputs[i] || !o.output || o.kind->reports_step != reports_step) continue;
      ++totals.outputs[i].due;
      try {
        o.output->write(step);
      } catch (const std::exception& e) {
        add_failure(failure, "outputs." + std::string(o.kind->config.name) + ": " + e.what());
      }
    }
  }

  // Every rank takes part in the record (its stats go to the root) where one writes it.
  bool any_reports_step(const StepPlan& p) const {
    for (std::size_t i = 0; i < outputs.size(); ++i)
      if (p.outputs[i] && outputs[i].kind->reports_step &&
          (outputs[i].output || (comm != nullptr && config.outputs[i].settings->enabled)))
        return true;
    return false;
  }

  void fill_record(const StepData& data, const StepStats& stats, double render_ms,
                   double outputs_ms, const Stopwatch& process, std::int64_t bytes_before) {
    const WriterStats writer_stats = writer.stats();
    const StepRecordInput in{data.step,  data.time,    &stats,        render_ms,
                             outputs_ms, process.ms(), &writer_stats, host_memory()};
    fill_step_record(in, record);
    if (comm == nullptr || comm->size() == 1) return;
    const std::int64_t sent = comm->bytes_sent() - bytes_before;
    record.totals.set_count("mpi.bytes_sent", sent);
    combine_rank_records(*comm, sent, record);
  }

  bool reports_here() const { return comm == nullptr || comm->root(); }

  StepScene scene;  // what the views frame and show besides the fluid, agreed over ranks

  std::unique_ptr<LivePage> live;  // when the live page is enabled
  bool feeds_live() const { return live && live->feeds(); }
};

const OutputTally& PipelineTotals::output(std::string_view kind) const {
  for (const OutputTotals& o : outputs)
    if (o.kind == kind) return o.tally;
  throw make_error("no output \"", kind, "\" in the totals");
}

double PipelineTotals::writer_seconds() const {
  double s = 0;
  for (const OutputTotals& o : outputs) s += o.tally.writer_seconds;
  return s;
}

namespace {

// With ranks, every one must have read the same config: the first key that differs is named.
void check_same_config(Communicator& comm, const Config& config) {
  std::string mine;
  for (const std::string& line : config_lines(config)) mine += line + "\n";
  const auto bytes = std::as_bytes(std::span(mine.data(), mine.size()));
  const std::vector<std::vector<std::byte>> all = comm.gather(bytes);
  std::string verdict;
  for (std::size_t r = 1; r < all.size() && verdict.empty(); ++r) {
    std::istringstream root_lines(mine),
        rank_lines(std::string(reinterpret_cast<const char*>(all[r].data()), all[r].size()));
    std::string a, b;
    for (bool more_a = true, more_b = true; (more_a || more_b) && verdict.empty();) {
      more_a = bool(std::getline(root_lines, a));
      more_b = bool(std::getline(rank_lines, b));
      if (!more_a) a.clear();
      if (!more_b) b.clear();
      if (a == b) continue;
      const std::string key = (a.empty() ? b : a).substr(0, (a.empty() ? b : a).find(": "));
      verdict = "rank " + std::to_string(r) + "'s config differs from rank 0's at " + key +
                ": rank 0 has \"" + a + "\", rank " + std::to_string(r) + " has \"" + b + "\"";
    }
  }
  verdict = comm.broadcast(verdict);
  if (!verdict.empty()) throw Error(verdict);
}

std::unique_ptr<Communicator> communicator(const std::optional<int>& mpi_comm) {
  if (!mpi_comm) return nullptr;
  return std::make_unique<Communicator>(*mpi_comm);
}

}  // namespace

InsituPipeline::InsituPipeline(const Config& config, double particle_spacing,
                               std::optional<int> mpi_comm)
    : comm_(communicator(mpi_comm)) {
  // The job's lines come from rank 0; what another rank says alone (its writer's failures)
  // says which rank it is.
  if (comm_ && !comm_->root()) set_log_tag("rank " + std::to_string(comm_->rank()));
  if (comm_) check_same_config(*comm_, config);
  // Every rank makes its part (folders, GL context, passes); a failure on any is one on all.
  std::string failure;
  try {
    impl_ = std::make_unique<Impl>(config, particle_spacing, comm_.get());
  } catch (const std::exception& e) {
    if (!comm_) throw;
    failure = e.what();
  }
  if (comm_) {
    if (!failure.empty()) impl_.reset();
    comm_->agree_or_throw(failure.empty(), failure);
  }
  if (!comm_ || comm_->root()) log_info("in situ: ", description());
}

Status InsituPipeline::agree(const Status& local) {
  if (!comm_) return local;
  // Ranks at different steps (one skipped a call) would composite one step's particles with
  // another's: said on every rank, each step, until they meet again.
  if (!std::exchange(impl_->processed, false)) {
    double steps[2] = {double(impl_->planned_step), -double(impl_->planned_step)};
    comm_->min(steps);
    if (steps[0] != -steps[1]) {
      std::ostringstream why;
      why << "the ranks are at different steps (" << std::int64_t(steps[0]) << " to "
          << std::int64_t(-steps[1]) << "): every rank must call execute with the same steps";
      return {StatusCode::invalid_input, why.str()};
    }
  }
  const Agreement agreed = comm_->agree(local.ok(), local.message);
  if (agreed.ok || !local.ok()) return local;
  return {StatusCode::pipeline_failed,
          "step abandoned: rank " + std::to_string(agreed.rank) + ": " + agreed.message};
}

std::array<double, 3> InsituPipeline::agree_point(const std::array<double, 3>& local) {
  if (!comm_) return local;
  // A rank without a point says +inf, which loses every min; inf on every rank: none has one.
  std::array<double, 3> point;
  for (std::size_t a = 0; a < 3; ++a)
    point[a] = std::isfinite(local[0]) ? local[a] : std::numeric_limits<double>::infinity();
  comm_->min(point);
  if (std::isinf(point[0])) point.fill(std::numeric_limits<double>::quiet_NaN());
  return point;
}

bool InsituPipeline::reports_failures() const { return !comm_ || comm_->root(); }

InsituPipeline::~InsituPipeline() {
  try {
    finish();
  } catch (...) {}
}

bool InsituPipeline::wants_step(std::int64_t step, double time) {
  Impl& m = *impl_;
  // Idempotent per step: is_render_step() and execute() may both ask (a NaN time too, which
  // the adapter then refuses: planned twice, `first` and `every_steps` would fire on neither).
  const bool same_time = time == m.planned_time || (std::isnan(time) && std::isnan(m.planned_time));
  if (step != m.planned_step || !same_time) {
    m.plan.clear();
    m.schedule.plan(step, time, step == m.last_step, m.plan);
    m.planned_step = step;
    m.planned_time = time;
  }
  return m.plan.any() || m.plan.conditions;
}

bool InsituPipeline::confirm_step(std::int64_t step, double time, const ParticleView& particles) {
  Impl& m = *impl_;
  wants_step(step, time);
  m.schedule.decide(step, time, particles, m.plan);  // once a step: it clears plan.conditions
  return m.plan.any();
}

void InsituPipeline::mark_last_step(std::int64_t step) {
  Impl& m = *impl_;
  m.last_step = step;
  m.writer.keep_every_file();
  // Already planned without knowing it was the last: add the `last` conditions (the
  // particles' conditions stay as they were: decided or still waiting).
  if (step != m.planned_step) return;
  const bool conditions = m.plan.conditions;
  m.schedule.plan(step, m.planned_time, true, m.plan);
  m.plan.conditions = conditions;
}

Status InsituPipeline::process(const StepData& data, const StepStats& stats) {
  Impl& m = *impl_;
  m.processed_any = true;
  m.processed = true;  // the step's second agree() follows
  const Stopwatch process;
  const std::int64_t bytes_before = m.comm != nullptr ? m.comm->bytes_sent() : 0;
  if (data.step != m.planned_step) wants_step(data.step, data.time);
  // Called without the adapter's confirm_step (a tool driving the pipeline itself).
  if (m.plan.conditions && data.particles != nullptr)
    m.schedule.decide(data.step, data.time, *data.particles, m.plan);
  const StepPlan& p = m.plan;
  m.make_current();

  std::string failure;
  double render_ms = 0;
  m.orbit_pictures.clear();  // the last step's references go
  if (p.render) {
    const Stopwatch render;
    if (m.live) m.live->take_cameras();
    failure = m.render_views(data, m.needs(p));
    add_failure(failure, m.render_orbits(data, p));
    ++m.totals.render_steps;
    render_ms = render.ms();
  } else {
    for (std::size_t i = 0; i < m.results.size(); ++i) m.results[i] = {m.views[i].name};
    // A stats line of a step that rendered nothing has no views' figures (not the last ones').
    for (auto& view : m.record.views) view.second.zero();
  }
  const Stopwatch outputs;
  OutputStep step{data, m.results, nullptr, m.orbit_pictures};
  m.write_outputs(step, p, false, failure);
  const double outputs_ms = outputs.ms();
  if (m.any_reports_step(p)) {
    m.fill_record(data, stats, render_ms, outputs_ms, process, bytes_before);
    m.record.error = failure;  // capacity kept: a failing step allocates at most once
    step.record = &m.record;
    m.write_outputs(step, p, true, failure);
  }

  if (p.render && m.live)
    m.totals.seconds_live += m.live->publish(data, stats, m.results, outputs_ms, process.ms());
  m.totals.seconds_render += 1e-3 * render_ms;
  m.totals.seconds_outputs += outputs.seconds();
  m.totals.seconds_process += process.seconds();
  if (failure.empty()) return {};
  return {StatusCode::pipeline_failed, failure};
}

void InsituPipeline::finish() {
  impl_->writer.drain();
  if (impl_->live) impl_->live->finish();
  // The run's files are written: the folder is free for the next run (a solver or a Python
  // `with` block may make it before this adapter goes).
  impl_->folder_locks.clear();
}

PipelineTotals InsituPipeline::totals() const {
  PipelineTotals t = impl_->totals;
  for (std::size_t i = 0; i < impl_->outputs.size(); ++i)
    if (impl_->outputs[i].output) t.outputs[i].tally = impl_->outputs[i].output->tally();
  t.writer = impl_->writer.stats();
  return t;
}

const Config& InsituPipeline::config() const { return impl_->config; }

void InsituPipeline::keep_linear_pictures(bool keep) { impl_->linear_pictures = keep; }

std::span<const ViewResult> InsituPipeline::latest_views() const {
  impl_->finish_latest();
  return impl_->results;
}

std::string InsituPipeline::description() const {
  const Impl& m = *impl_;
  std::ostringstream s;
  s << describe(m.backend) << ", " << m.views.size() << (m.views.size() == 1 ? " view" : " views");
  for (std::size_t i = 0; i < m.views.size(); ++i)
    s << (i ? ", " : " (") << m.views[i].name << " " << m.views[i].view->description()
      << (i + 1 == m.views.size() ? ")" : "");
  s << "; outputs in " << m.config.output_folder << ":";
  for (const ConfiguredOutput& o : m.config.outputs)
    if (o.settings->enabled) s << " " << o.kind;
  return s.str();
}

std::string InsituPipeline::summary() const {
  const PipelineTotals t = totals();
  std::ostringstream s;
  s.precision(3);
  s << t.render_steps << " render steps, " << t.frames << " views rendered";
  if (t.failed_views) s << " (" << t.failed_views << " failed)";
  s << "; written:";
  const char* separator = " ";
  std::int64_t no_slot = 0;
  for (const OutputTotals& o : t.outputs) {
    if (!o.enabled && o.tally.written == 0) continue;
    s << separator << o.tally.written << " " << o.noun;
    separator = ", ";
    no_slot += o.tally.no_slot;
  }
  if (*separator == ' ') s << " nothing (no output is enabled)";
  // Asked for before finish(): the counts are of the files written so far.
  const std::uint64_t pending = t.writer.submitted - t.writer.completed - t.writer.failed;
  if (pending > 0) s << " (" << pending << " more files being written; finish() waits for them)";
  for (const OutputTotals& o : t.outputs)
    if (o.enabled && o.due == 0) s << "; outputs." << o.kind << "'s trigger never fired";
  // Each rank's writer writes its own files (VTK pieces) and says its failures itself.
  const char* here = comm_ && comm_->size() > 1 ? " on rank 0" : "";
  if (t.writer.failed)
    s << "; " << t.writer.failed << " files failed" << here << " (first: " << t.writer.first_error
      << ")";
  if (t.writer.dropped)
    s << "; " << t.writer.dropped << " files dropped" << here << " (writer queue full)";
  if (no_slot) s << "; " << no_slot << " files not written (no free copy buffer)";
  if (t.writer.waits)
    s << "; the solver waited " << t.writer.waits << " times for a full writer queue";
  s << "; on the solver's thread " << t.seconds_process << " s (render " << t.seconds_render
    << " s, outputs " << t.seconds_outputs << " s), writer thread " << t.writer_seconds() << " s";
  return s.str();
}

}  // namespace voxspan
