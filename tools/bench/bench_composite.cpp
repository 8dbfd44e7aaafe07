// bench_composite: what compositing the ranks' span images costs, per scheme, image size and
// rank count (docs/benchmarks.md, "Compositing across ranks"; docs/design.md, "Compositing
// across ranks", draws the choice of scheme from it). Under mpiexec -n N every rank builds the
// Ritter-profile dam break (tools/common/dambreak_state.h), keeps its part (--splits: compact slabs
// or interleaved, with ghosts, as render_particles does: tools/common/rank_split.h), classifies it
// as the adapter would and renders the runtime's surface view (insitu/views/surface_view.cpp) with
// the runtime's span compositor (insitu/views/span_compositor.h) of each scheme; rank 0 shades.
//
// Per configuration, medians over --frames frames after one warm-up:
//  * per pass, the slowest rank's time and the mean over the ranks (the runtime's aggregation,
//    insitu/runtime/rank_stats.h); `step` is the view's whole render, wall clock. `wait` is a
//    barrier the benchmark puts before the compositor, so that `composite` is the exchange and
//    the merge, not the wait for the slowest rank's voxelization;
//  * the bytes each rank sent (composite.bytes_sent) against its share of the final span
//    image (the composite's encoded bytes / N);
//  * from the span images of the warm-up frame, encoded as they travel (insitu/parallel/
//    span_merge.h): the messages the scheme sends (the collectives as point-to-point messages),
//    the bytes it sends per rank (a check on the measured ones: a note when they differ), and,
//    per size, what merging every rank's image on one rank costs (per byte, and per pixel and
//    part given: the merge looks at every part for each pixel), decoding the composite and
//    encoding it (medians of five), for the projections of docs/benchmarks.md.
// One rank renders without a compositor: its row is the baseline. The schemes' views take
// turns frame by frame, so that the machine's load touches them alike. Oversubscribed (more
// ranks than cores) the timings say little; the bytes and messages hold.
//
//   mpiexec --oversubscribe -n N bench_composite [--particles N] [--time T] [--sizes WxH,...]
//       [--size WxH] [--schemes direct_send,root] [--splits slabs,interleaved] [--frames F]
//       [--alpha DEG] [--max-layers L] [--budget-mib M] [--all-particles] [--json]
//       [--csv FILE] [--platform auto|nvidia|device|surfaceless]
// Defaults: the scene of 1e5 particles in the initial column (119 781 at t = 0.3 s), 640x360,
// 1920x1080 and 3840x2160, both schemes, slabs, 3 frames, the runtime's view defaults
// (translucent, alpha 14 deg, 512 MiB). Table on stdout (rank 0); --csv: one line per row,
// every pass's slowest and mean time.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/parallel/communicator.h"
#include "insitu/parallel/span_merge.h"
#include "insitu/runtime/rank_stats.h"
#include "insitu/runtime/registry.h"
#include "insitu/views/span_compositor.h"
#include "insitu/views/surface_view.h"
#include "insitu/views/view_framing.h"
#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/shader_library.h"
#include "render/stat_names.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/rank_split.h"
#include "tools/common/tool_args.h"
#include "tools/common/usage.h"
#include "voxspan/classify.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;

struct Size {
  int width = 0, height = 0;
};

struct Args : tools::BenchArgs {
  Args() { width = height = 0; }  // --size WxH: that size only
  std::vector<Size> sizes = {{640, 360}, {1920, 1080}, {3840, 2160}};
  std::vector<CompositeScheme> schemes = {CompositeScheme::direct_send, CompositeScheme::root};
  std::vector<tools::Split> splits = {tools::Split::slabs};
  double budget_mib = 512;
  std::string csv;
};

constexpr char kUsage[] =
    "usage: mpiexec -n N bench_composite [--particles N] [--time T] [--sizes WxH,...]\n"
    "         [--size WxH] [--schemes direct_send,root] [--splits slabs,interleaved]\n"
    "         [--frames F] [--alpha DEG] [--max-layers L] [--budget-mib M] [--all-particles]\n"
    "         [--json] [--csv FILE] [--platform auto|nvidia|device|surfaceless]\n";

// The passes of a surface view's step, in order; `wait` is the benchmark's barrier (with the GL
// renderer the view reads its span image back before the barrier even on one rank).
constexpr StatName kWait{"wait"};
const StatName kVoxelize[] = {pass::frame, pass::upload, pass::bin,
                              pass::clear, pass::splat,  pass::compress};
const StatName kComposite[] = {pass::composite_download, pass::composite, pass::composite_upload};
const StatName kSurfaces[] = {pass::connect, pass::filter, pass::normals,
                              pass::deep_ao, pass::shade,  pass::readback};

bool read_sizes(const char* list, std::vector<Size>& out) {
  out.clear();
  for (const std::string& item : tools::comma_list(list)) {
    Size size;
    if (!tools::parse_size(item.c_str(), size.width, size.height)) return false;
    out.push_back(size);
  }
  return !out.empty();
}

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--sizes")) return read_sizes(v, a.sizes);
  if (const char* v = arg.value("--schemes"))
    return tools::read_names(v, kCompositeSchemeNames, a.schemes);
  if (const char* v = arg.value("--splits"))
    return tools::read_names(v, tools::kSplitNames, a.splits);
  return tools::read_bench_flag(arg, a) || arg.value("--budget-mib", a.budget_mib) ||
         arg.value("--csv", a.csv);
}

bool parse(int argc, char** argv, Args& a) {
  if (!tools::read_args(argc, argv, a, read_flag) || !(a.particles > 0)) return false;
  if (a.width > 0) a.sizes = {{a.width, a.height}};
  return true;
}

// The scene every rank builds whole, and this rank's part of it.
struct Scene {
  tools::DamBreakState state;
  Bounds box;  // of every sphere: the ground plane lies under it
  Classification part;
  std::vector<ParticleSphere> owned;  // --all-particles: voxelized as they are, no cell states
  StepData step;
};

// This rank's particles (its own, then its ghosts) classified as the adapter classifies them
// in an MPI job: ghosts count towards the cells' occupancy but are another rank's to voxelize.
void take_part(Scene& s, tools::Split split, const Communicator& comm, bool all_particles) {
  const tools::DamBreakState& d = s.state;
  std::vector<std::array<double, 3>> all(d.x.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = {d.x[i], d.y[i], d.z[i]};
  const tools::RankPart part =
      tools::split_particles(all, split, comm.rank(), comm.size(), tools::ghost_margin(d.spacing));
  std::vector<std::array<double, 3>> mine;
  for (std::size_t i : part.indices) mine.push_back(all[i]);
  ClassifyOptions options;
  options.particle_spacing = d.spacing;
  options.include_ghosts = false;
  auto view = ParticleView::aos(mine.empty() ? nullptr : mine[0].data(), mine.size());
  s.part = classify(view.with_owned(part.owned), GridView(), options);
  s.owned.clear();
  for (std::size_t k = 0; k < part.owned; ++k)
    s.owned.push_back({float(mine[k][0]), float(mine[k][1]), float(mine[k][2]), float(d.spacing)});
  s.step = StepData{};
  s.step.boundary = all_particles ? s.owned : s.part.boundary;
  if (!all_particles) s.step.cells = s.part.cell_states();
}

Scene make_scene(const Args& a) {
  Scene s{tools::ritter_dam_break(a.particles, a.time < 0 ? 0.3 : a.time), {}, {}, {}, {}};
  std::vector<ParticleSphere> spheres;
  for (std::size_t i = 0; i < s.state.x.size(); ++i)
    spheres.push_back({s.state.x[i], s.state.y[i], s.state.z[i], float(s.state.spacing)});
  s.box = Bounds::of_spheres(spheres);
  return s;
}

// The runtime's default surface view of the given size, from the scene's camera.
SurfaceSettings view_settings(const Scene& s, const Args& a, Size size) {
  SurfaceSettings v;
  v.name = "composite";
  v.width = size.width;
  v.height = size.height;
  v.alpha_degrees = a.alpha;
  v.max_layers = a.max_layers;
  const Camera& c = s.state.camera;
  v.camera.automatic = false;
  v.camera.eye = {c.eye.x, c.eye.y, c.eye.z};
  v.camera.target = {c.target.x, c.target.y, c.target.z};
  v.camera.up = {c.up.x, c.up.y, c.up.z};
  v.camera.fov_degrees = c.fov_y_degrees;
  return v;
}

// Every rank's depth range made one, so that all voxelize into the same grid.
DepthRange combined(Communicator& comm, const DepthRange& local) {
  DepthRange all = local;
  double near_far[2] = {local.lo, -local.hi};
  comm.min(near_far);
  std::int64_t visible[1] = {local.counts.visible};
  comm.sum(visible);
  all.lo = near_far[0], all.hi = -near_far[1], all.counts.visible = visible[0];
  return all;
}

// Per rank of `ranks`: the bytes of its band of rows of `image`, encoded (direct send).
std::vector<std::int64_t> band_sizes(const SpanImage& image, int ranks) {
  std::vector<std::int64_t> bands;
  for (int r = 0; r < ranks; ++r) {
    const RowBand band = band_of(r, ranks, image.height());
    bands.push_back(std::int64_t(encode_rows(image, band.begin, band.end).size()));
  }
  return bands;
}

// The stage before the compositor: on the warm-up frame it keeps this rank's span image as
// the compositor would send it; on every frame it waits for every rank (`wait`), so that the
// compositor's time is its own, and drops the bytes counted so far, so that the compositor
// counts only what it sends.
class RankProbe final : public SpanStage {
 public:
  RankProbe(Communicator& comm, const MergeSettings& settings) : merge(settings), comm_(comm) {}

  const SpanImage* run(const SpanImage* spans, const std::string&, Recorder& recorder) override {
    if (capture && spans != nullptr) keep(*spans);
    wait(recorder);
    return spans;
  }

  bool capture = false;
  const MergeSettings merge;
  PerspectiveGrid grid;
  std::vector<std::byte> image;       // every pixel with spans
  std::vector<std::int64_t> to_band;  // its part of every rank's band of rows

 private:
  void wait(Recorder& recorder) {
    auto t = recorder.host(kWait);
    comm_.agree(true, {});
  }
  void keep(const SpanImage& local) {
    grid = local.grid;
    image = encode_rows(local, 0, local.height());
    to_band = band_sizes(local, comm_.size());
  }

  Communicator& comm_;
};

// Every rank's span image of the warm-up frame, on the root (empty elsewhere), merged there as
// the root scheme merges them, with the time of the merge's steps (medians of a few repeats).
struct Composite {
  std::vector<std::vector<std::byte>> images;      // per rank, as it travels
  std::vector<std::vector<std::int64_t>> to_band;  // per rank, its part of each rank's band
  std::vector<std::int64_t> final_bands;           // the composite's band of each rank
  std::int64_t input_bytes = 0, final_bytes = 0;
  double merge_ms = 0;   // every rank's image into the composite (encoded)
  double decode_ms = 0;  // the composite into a span image (the root's upload does it)
  double encode_ms = 0;  // the composite's span image encoded again (what a rank's send costs)
  // What the merge spends per pixel of the composite on each part it is given, empty or not
  // (it looks at every part's next pixel for each pixel): the images merged among kPaddedParts
  // parts, the rest empty, against the merge of the images alone.
  double part_scan_ns = 0;
};

constexpr std::size_t kPaddedParts = 1024;

std::vector<std::int64_t> as_counts(const std::vector<std::byte>& bytes) {
  std::vector<std::int64_t> v(bytes.size() / sizeof(std::int64_t));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(std::int64_t));
  return v;
}

// The median time of `repeats` runs of `work`.
template <class Work> double median_ms(int repeats, Work&& work) {
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const Stopwatch t;
    work();
    ms.push_back(t.ms());
  }
  return tools::median(ms);
}

// Repeats of the merge timings: they are cheap beside a frame, and the machine is noisy.
constexpr int kMergeRepeats = 5;

// Collective.
Composite gather_composite(Communicator& comm, const RankProbe& probe, int repeats) {
  Composite c;
  c.images = comm.gather(probe.image);
  const auto bands = comm.gather(std::as_bytes(std::span(probe.to_band)));
  if (!comm.root()) return c;
  for (const auto& b : bands) c.to_band.push_back(as_counts(b));
  for (const auto& image : c.images) c.input_bytes += std::int64_t(image.size());
  std::vector<std::byte> merged;
  c.merge_ms = median_ms(repeats, [&] { merged = merge_rows(probe.grid, c.images, probe.merge); });
  c.final_bytes = std::int64_t(merged.size());
  SpanImage image;
  c.decode_ms =
      median_ms(repeats, [&] { image = decode_image(probe.grid, std::span(&merged, 1)); });
  c.encode_ms = median_ms(repeats, [&] { merged = encode_rows(image, 0, image.height()); });
  c.final_bands = band_sizes(image, comm.size());
  std::vector<std::vector<std::byte>> padded = c.images;
  padded.resize(std::max(kPaddedParts, padded.size()));
  const double padded_ms = median_ms(repeats, [&] { merge_rows(probe.grid, padded, probe.merge); });
  std::int64_t pixels = 0;
  for (const PixelSpans& p : image.pixels) pixels += p.count > 0;
  const double scans = double(pixels) * double(padded.size() - c.images.size());
  if (scans > 0) c.part_scan_ns = 1e6 * (padded_ms - c.merge_ms) / scans;
  return c;
}

// What a scheme sends, from every rank's span image: per rank the bytes as the communicator
// counts them (the agreement, the counts, the data) and the messages, the collectives taken as
// point-to-point messages (an all-to-all: one per pair of ranks; a gather: one per rank).
struct Traffic {
  std::vector<std::int64_t> bytes;
  std::int64_t data_messages = 0, most_data_messages = 0;  // non-empty ones: all, one rank's
  std::int64_t count_messages = 0;                         // of the sizes
  std::int64_t root_receives = 0;                          // bytes
};

constexpr std::int64_t kCount = sizeof(int);  // a message size, as the collectives send it

// The all-to-all of the bands (sizes first), then the merged bands gathered (sizes first).
Traffic direct_send_traffic(const Composite& c) {
  const int n = int(c.to_band.size());
  Traffic t;
  for (int r = 0; r < n; ++r) {
    const std::vector<std::int64_t>& sends = c.to_band[std::size_t(r)];
    std::int64_t bytes = kCount + kCount * (n - 1) + kCount, messages = 0;  // agree, sizes
    for (int d = 0; d < n; ++d)
      if (d != r) bytes += sends[std::size_t(d)], messages += sends[std::size_t(d)] > 0;
    if (r != 0) {
      const std::int64_t band = c.final_bands[std::size_t(r)];
      bytes += band, messages += band > 0;
      t.root_receives += sends[0] + band;
    }
    t.bytes.push_back(bytes);
    t.data_messages += messages;
    t.most_data_messages = std::max(t.most_data_messages, messages);
  }
  t.count_messages = std::int64_t(n) * (n - 1) + (n - 1);
  return t;
}

// Every image gathered on the root (sizes first).
Traffic root_traffic(const Composite& c) {
  const int n = int(c.images.size());
  Traffic t;
  for (int r = 0; r < n; ++r) {
    const std::int64_t sent = r == 0 ? 0 : std::int64_t(c.images[std::size_t(r)].size());
    t.bytes.push_back(kCount + kCount + sent);  // agree, size, image
    t.data_messages += sent > 0;
    t.root_receives += sent;
  }
  t.most_data_messages = std::min<std::int64_t>(t.data_messages, 1);
  t.count_messages = n - 1;
  return t;
}

Traffic traffic_of(CompositeScheme scheme, const Composite& c) {
  return scheme == CompositeScheme::root ? root_traffic(c) : direct_send_traffic(c);
}

// One scheme's medians over the frames (root).
struct Figures {
  CompositeScheme scheme;
  std::map<std::string, std::vector<double>> slowest_ms, mean_ms;  // per pass, and "step"
  std::map<std::string, double> slowest, mean;                     // their medians
  std::vector<std::int64_t> sent;  // composite.bytes_sent per rank, last frame
  FrameStats last;                 // the last frame's record (slowest rank, summed counts)
  Traffic traffic;

  void add(const StatsRecord& r) {
    slowest_ms["step"].push_back(r.totals.ms("step"));
    mean_ms["step"].push_back(r.ranks.totals_mean.ms("step"));
    for (const FrameStats::Pass& p : r.views.front().second.passes)
      slowest_ms[p.name].push_back(p.ms);
    for (const FrameStats::Pass& p : r.ranks.views_mean.front().second.passes)
      mean_ms[p.name].push_back(p.ms);
    sent = r.ranks.bytes_sent;
    last = r.views.front().second;
  }
  void finish(const Composite& c) {
    for (const auto& [name, v] : slowest_ms) slowest[name] = tools::median(v);
    for (const auto& [name, v] : mean_ms) mean[name] = tools::median(v);
    traffic = traffic_of(scheme, c);
  }
};

// One frame's record of every rank, combined on the root as the runtime combines them.
StatsRecord combine(Communicator& comm, const FrameStats& view, double step_ms) {
  StatsRecord record;
  record.view("composite") = view;
  record.totals.add_time("step", step_ms);
  combine_rank_records(comm, view.count("composite.bytes_sent"), record);
  return record;
}

struct SizeFigures {
  Composite composite;
  std::vector<Figures> schemes;
};

class Bench {
 public:
  Bench(const Args& a, Communicator& comm, const gl::Context& context)
      : a_(a), comm_(comm), context_(context) {}

  // Views of `size`, one per scheme (one without a compositor on one rank), rendered in turn
  // frame after frame, so that the machine's load changes touch every scheme alike.
  SizeFigures measure(const Scene& scene, Size size) {
    const SurfaceSettings settings = view_settings(scene, a_, size);
    const Camera camera = frame_camera(settings, scene.box);
    const ViewStep step{scene.step, camera, scene.box, ViewNeeds{true, false}};
    std::vector<SchemeView> views;
    SizeFigures out;
    for (CompositeScheme scheme : a_.schemes) {
      views.push_back(make_view(scene, settings, scheme));
      out.schemes.push_back({scheme, {}, {}, {}, {}, {}, {}, {}});
      if (comm_.size() == 1) break;
    }
    for (int frame = -1; frame < a_.frames; ++frame)
      for (std::size_t k = 0; k < views.size(); ++k) {
        views[k].probe->capture = frame < 0 && k == 0;
        const StatsRecord r = render_frame(*views[k].view, step);
        if (frame >= 0 && comm_.root()) out.schemes[k].add(r);
      }
    out.composite = gather_composite(comm_, *views.front().probe, kMergeRepeats);
    for (Figures& f : out.schemes) f.finish(out.composite);
    return out;
  }

 private:
  struct SchemeView {
    std::unique_ptr<View> view;
    RankProbe* probe = nullptr;
  };

  // The surface view with the probe before the compositor of `scheme` (none on one rank).
  SchemeView make_view(const Scene& scene, const SurfaceSettings& settings,
                       CompositeScheme scheme) {
    RendererConfig renderer;
    renderer.gpu_memory_mib = a_.budget_mib;
    renderer.composite = scheme;
    SchemeView v;
    ViewContext c{shaders_, renderer, RenderBackend::gl, scene.state.spacing, {}, {}};
    c.span_stages = [&](const MergeSettings& m) {
      std::vector<std::unique_ptr<SpanStage>> stages;
      auto probe = std::make_unique<RankProbe>(comm_, m);
      v.probe = probe.get();
      stages.push_back(std::move(probe));
      if (comm_.size() > 1) stages.push_back(std::make_unique<SpanCompositor>(comm_, m, scheme));
      return stages;
    };
    c.combine_ranks = [this](const DepthRange& local) { return combined(comm_, local); };
    v.view = registered_view_kind("surface").make(settings, c);
    return v;
  }

  StatsRecord render_frame(View& view, const ViewStep& step) {
    FrameStats stats;
    gl::GpuRecorder recorder(stats, context_.has_gpu_timers());
    const Stopwatch wall;
    view.render(step, recorder, products_);
    recorder.collect();
    return combine(comm_, stats, wall.ms());
  }

  const Args& a_;
  Communicator& comm_;
  const gl::Context& context_;
  gl::ShaderLibrary shaders_;
  ViewProducts products_;
};

// ---- output (rank 0)

double sum_of(const std::map<std::string, double>& ms, std::span<const StatName> passes) {
  double total = 0;
  for (StatName p : passes)
    if (auto it = ms.find(std::string(p.text)); it != ms.end()) total += it->second;
  return total;
}

double at(const std::map<std::string, double>& ms, std::string_view pass) {
  const auto it = ms.find(std::string(pass));
  return it == ms.end() ? 0 : it->second;
}

struct Row {
  std::string split;
  int ranks;
  Size size;
  std::string scheme;
  const Figures& f;
  const Composite& c;

  double composite_ms() const { return sum_of(f.slowest, kComposite); }
  double share_bytes() const { return double(c.final_bytes) / ranks; }
  double ratio() const { return share_bytes() > 0 ? double(most_sent()) / share_bytes() : 0; }
  std::int64_t most_sent() const {
    return f.sent.empty() ? 0 : *std::max_element(f.sent.begin(), f.sent.end());
  }
  double mean_sent() const {
    double s = 0;
    for (std::int64_t b : f.sent) s += double(b);
    return f.sent.empty() ? 0 : s / double(f.sent.size());
  }
};

constexpr double kKiB = 1024;

void print_header() {
  const char* format =
      "%-11s %5s %9s %-11s | %8s %8s %7s %7s %7s %7s %8s | %5s | %8s %8s %8s %5s | %5s %5s %6s "
      "| %8s\n";
  std::printf(format, "split", "ranks", "size", "scheme", "step", "voxelize", "wait", "c_down",
              "compose", "c_up", "surfaces", "comp", "sent max", "mean", "share", "ratio", "data",
              "/rank", "counts", "root");
  std::printf(format, "", "", "", "", "ms", "ms", "ms", "ms", "ms", "ms", "ms", "%", "KiB", "KiB",
              "KiB", "", "msgs", "", "msgs", "recv KiB");
}

void print_row(const Row& r) {
  const Figures& f = r.f;
  const Traffic& t = f.traffic;
  char size[24];
  std::snprintf(size, sizeof size, "%dx%d", r.size.width, r.size.height);
  const double step = at(f.slowest, "step");
  std::printf(
      "%-11s %5d %9s %-11s | %8.1f %8.1f %7.1f %7.1f %7.1f %7.1f %8.1f | %5.1f | %8.1f %8.1f "
      "%8.1f %5.2f | %5lld %5lld %6lld | %8.1f\n",
      r.split.c_str(), r.ranks, size, r.scheme.c_str(), step, sum_of(f.slowest, kVoxelize),
      at(f.slowest, kWait), at(f.slowest, kComposite[0]), at(f.slowest, kComposite[1]),
      at(f.slowest, kComposite[2]), sum_of(f.slowest, kSurfaces),
      step > 0 ? 100 * r.composite_ms() / step : 0, double(r.most_sent()) / kKiB,
      r.mean_sent() / kKiB, r.share_bytes() / kKiB, r.ratio(),
      static_cast<long long>(t.data_messages), static_cast<long long>(t.most_data_messages),
      static_cast<long long>(t.count_messages), double(t.root_receives) / kKiB);
}

// The merge's figures of a size: the same images whatever the scheme.
void print_merge(const Composite& c, int ranks) {
  std::printf(
      "  merge: %d images, %.1f KiB, into %.1f KiB on one rank in %.1f ms (%.2f ns/B), %.2f ns "
      "per composite pixel and part given; decode %.1f ms, encode %.1f ms\n",
      ranks, double(c.input_bytes) / kKiB, double(c.final_bytes) / kKiB, c.merge_ms,
      c.input_bytes > 0 ? 1e6 * c.merge_ms / double(c.input_bytes) : 0, c.part_scan_ns, c.decode_ms,
      c.encode_ms);
}

std::vector<StatName> all_passes() {
  std::vector<StatName> p(std::begin(kVoxelize), std::end(kVoxelize));
  p.push_back(kWait);
  p.insert(p.end(), std::begin(kComposite), std::end(kComposite));
  p.insert(p.end(), std::begin(kSurfaces), std::end(kSurfaces));
  return p;
}

void csv_header(std::ostream& out) {
  out << "split,ranks,width,height,scheme,step_ms,step_ms_mean";
  for (StatName p : all_passes()) out << ',' << p.text << "_ms," << p.text << "_ms_mean";
  out << ",bytes_sent_max,bytes_sent_mean,bytes_expected_max,final_bytes,share_bytes,ratio,"
         "data_messages,data_messages_max_rank,count_messages,root_received_bytes,"
         "input_bytes,merge_ms,decode_ms,encode_ms,part_scan_ns,spans_stored\n";
}

void csv_row(std::ostream& out, const Row& r) {
  const Figures& f = r.f;
  const Traffic& t = f.traffic;
  out << r.split << ',' << r.ranks << ',' << r.size.width << ',' << r.size.height << ',' << r.scheme
      << ',' << at(f.slowest, "step") << ',' << at(f.mean, "step");
  for (StatName p : all_passes()) out << ',' << at(f.slowest, p) << ',' << at(f.mean, p);
  const std::int64_t expected =
      t.bytes.empty() ? 0 : *std::max_element(t.bytes.begin(), t.bytes.end());
  out << ',' << r.most_sent() << ',' << r.mean_sent() << ',' << (r.ranks > 1 ? expected : 0) << ','
      << r.c.final_bytes << ',' << r.share_bytes() << ',' << r.ratio() << ',' << t.data_messages
      << ',' << t.most_data_messages << ',' << t.count_messages << ',' << t.root_receives << ','
      << r.c.input_bytes << ',' << r.c.merge_ms << ',' << r.c.decode_ms << ',' << r.c.encode_ms
      << ',' << r.c.part_scan_ns << ',' << f.last.count(counter::spans_stored) << '\n';
}

// The measured bytes against the ones the images imply: a difference means the model of the
// projections (docs/benchmarks.md) no longer describes the compositor.
void check_bytes(const Row& r) {
  if (r.ranks == 1 || r.f.sent == r.f.traffic.bytes) return;
  std::printf("  note: the compositor sent other byte counts than its images imply:");
  for (std::size_t k = 0; k < r.f.sent.size() && k < r.f.traffic.bytes.size(); ++k)
    std::printf(" rank %zu %lld/%lld", k, static_cast<long long>(r.f.sent[k]),
                static_cast<long long>(r.f.traffic.bytes[k]));
  std::printf("\n");
}

int run(const Args& a, Communicator& comm) {
  const bool root = comm.root();
  gl::ContextOptions options = a.context;
  if (options.device < 0) options.device = comm.node_rank();  // the runtime's choice
  const gl::Context context(options);
  std::ofstream csv;
  if (root && !a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw make_error("cannot write ", a.csv);
    csv_header(csv);
  }
  Scene scene = make_scene(a);
  if (root) {
    tools::print_renderer(context);
    std::printf("scene: %s, spacing %.4g; %d ranks; medians of %d frames after one warm-up\n\n",
                scene.state.description.c_str(), scene.state.spacing, comm.size(), a.frames);
    print_header();
  }
  Bench bench(a, comm, context);
  for (tools::Split split : a.splits) {
    take_part(scene, split, comm, a.all_particles);
    const std::string split_name(name_of(tools::kSplitNames, split));
    for (Size size : a.sizes) {
      const SizeFigures figures = bench.measure(scene, size);
      if (!root) continue;
      for (const Figures& f : figures.schemes) {
        const std::string_view scheme =
            comm.size() == 1 ? "one rank" : name_of(kCompositeSchemeNames, f.scheme);
        const Row row{split_name, comm.size(), size, std::string(scheme), f, figures.composite};
        print_row(row);
        check_bytes(row);
        if (a.json) std::printf("  %s\n", f.last.json().c_str());
        if (csv) csv_row(csv, row);
      }
      print_merge(figures.composite, comm.size());
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (tools::asks_for_help(argc, argv)) return tools::print_usage(stdout, kUsage);
  MPI_Init(&argc, &argv);
  int status = 0;
  {
    voxspan::Communicator comm(int(MPI_Comm_c2f(MPI_COMM_WORLD)));
    status = tools::tool_main<Args>("bench_composite", argc, argv, kUsage, parse,
                                    [&](const Args& a) { return run(a, comm); });
  }
  // A rank that failed alone would leave the others waiting in a collective.
  if (status == 1) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Finalize();
  return status;
}
