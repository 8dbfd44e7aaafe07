// bench_peers: our renderers, swept over their settings, against the tools a user would run
// instead, on the same particles and camera in one run, each timed and its error measured
// against the exact reference (docs/results.md).
//
// The scene is the tools' dam break (tools/common/dambreak_state.h: the WCSPH solver at Martin &
// Moyce's T, about --particles fluid particles, spheres of the particle spacing). The methods:
//   exact     the exact reference's caster (render/reference/exact_spans.h): every candidate
//             sphere of the pixel's 8x8 bin, in double; the yardstick, and a method of its own
//   cpu, gl   our renderers, classification to picture (opaque, the runtime's defaults), and
//             one setting changed at a time: gap bridging, span cap, inner-cell skipping, and
//             for the GL one's voxelization the angle resolution, the span ends (the voxels'
//             outer faces or centres), the layer cap, the tile budget
//             (the depth filter is a look, the same for all: its cost is in the stages)
//   openvdb   ParticlesToLevelSet at voxels from the radius to a quarter of it, without and with
//             mean-value smoothing, then its level-set ray intersector
//             (tools/peers/vdb_level_set.h)
//   vtk       vtkSPHInterpolator onto a volume, vtkFlyingEdges3D, the mesh ray cast by Embree
//             (tools/peers/vtk_sph_surface.h; built where VTK's filters and Embree are found)
// Every method starts from the solver's particle arrays: our time includes the classification,
// the peers' their whole build. Every method's spans then go through one surface pipeline and
// shading, the CPU renderer's at the runtime's defaults (connect, filter of the particle spacing,
// normals, opaque and translucent shading), so that the pictures differ by the geometry alone.
// Errors, against the exact reference's spans (gap bridging of the spacing, the runtime's
// default, no cap) through the same pipeline: the distance along the unit ray to the first
// surface after the filter (median, 99th percentile, max over the pixels both hit, in particle
// radii) and before it ("raw"), silhouette pixels missed and extra, the 99th percentile of the
// length inside the fluid (thickness, radii) and the PSNR of both pictures.
// Milliseconds are medians over --frames frames after one warm-up, the frames taken in turns
// (each method one frame, then each again), so that a shared machine's load falls on all alike.
//
//   bench_peers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH] [--frames F]
//               [--methods exact,cpu,gl,openvdb,vtk] [--quick] [--check] [--csv FILE]
//               [--platform auto|nvidia|device|surfaceless]
// --quick: each family's default settings only (and the smallest sweep of the peers).
// --check (the test of this tool): fails unless the CPU renderer's default equals the exact
// reference through the pipeline (its spans are exact) and every other method sees the fluid
// (hits on half the reference's pixels at least, a finite error).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "render/cpu/cpu_renderer.h"
#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/renderer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/stat_names.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "tools/peers/vdb_level_set.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"
#ifdef VOXSPAN_HAVE_VTK_PEER
#include "tools/peers/vtk_sph_surface.h"
#endif

namespace {

using namespace voxspan;
using tools::PeerSurface;

struct Args : tools::BenchArgs, tools::StateFlags {
  std::set<std::string> methods = {"exact", "cpu", "gl", "openvdb", "vtk"};
  bool quick = false;
  bool check = false;
  std::string csv;
};

constexpr char kUsage[] =
    "usage: bench_peers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F] [--methods exact,cpu,gl,openvdb,vtk] [--quick] [--check]\n"
    "         [--csv FILE] [--platform auto|nvidia|device|surfaceless]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--methods")) {
    a.methods.clear();
    for (const std::string& m : tools::comma_list(v)) {
      if (m != "exact" && m != "cpu" && m != "gl" && m != "openvdb" && m != "vtk") return false;
      a.methods.insert(m);
    }
    return !a.methods.empty();
  }
  return tools::read_bench_flag(arg, a) || tools::read_state_flag(arg, a) ||
         arg.flag("--quick", a.quick) || arg.flag("--check", a.check) || arg.value("--csv", a.csv);
}

bool parse(int argc, char** argv, Args& a) {
  return tools::read_args(argc, argv, a, read_flag) && a.particles > 0;
}

// One configuration of one method; run() is one frame from the particle arrays.
struct Method {
  std::string family, settings;
  bool is_default = false;
  std::function<PeerSurface()> run;
};

constexpr float kNone = std::numeric_limits<float>::infinity();

// A span image as a peer's surface: first hit from `first` (0: none), the spans as distances.
PeerSurface surface_of(const SpanImage& spans, const FloatImage& first) {
  PeerSurface s;
  s.first_hit.resize(spans.pixels.size());
  s.thickness.resize(spans.pixels.size());
  s.spans.resize(spans.pixels.size());
  const ViewFrame view(spans.grid.camera());
  for (int y = 0; y < spans.height(); ++y)
    for (int x = 0; x < spans.width(); ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(y) * spans.width();
      const float d = first.rgba[4 * i];
      s.first_hit[i] = d > 0 ? d : kNone;
      s.thickness[i] = spans.pixels[i].inside;
      const float k = float(view.ray_scale(x, y));
      for (const Span& span : spans.spans_at(x, y))
        s.spans[i].insert(s.spans[i].end(), {span.entry * k, span.exit * k});
    }
  s.elements = spans.spans.size();
  return s;
}

// A surface's spans in the frame of `grid` (view depths, no cap): what our shading reads.
SpanImage span_image_of(const PeerSurface& s, const PerspectiveGrid& grid) {
  SpanImage image;
  image.grid = grid;
  image.pixels.resize(s.spans.size());
  const ViewFrame view(grid.camera());
  SpanListBuilder list(image.spans, 0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(y) * image.width();
      const double k = view.ray_scale(x, y);
      list.begin();
      for (std::size_t j = 0; j + 1 < s.spans[i].size(); j += 2)
        list.add(s.spans[i][j] / k, s.spans[i][j + 1] / k, k);
      image.pixels[i] = list.end();
    }
  return image;
}

// The stages of our frames, as FrameStats names them, in frame order.
const char* kOurStages[] = {"classify", "frame",    "upload",  "bin",     "clear",
                            "splat",    "compress", "cast",    "connect", "filter",
                            "normals",  "shade",    "readback"};

void add_stages(const FrameStats& stats, PeerSurface& s) {
  for (const char* p : kOurStages)
    if (stats.runs(p) > 0) s.ms[p] = stats.ms(p);
}

// What every method starts from.
struct Scene {
  tools::DamBreakState state;
  ParticleView view;
  ClassifyOptions classify;
  std::vector<ParticleSphere> all;  // every particle, for the runs without cell states
};

// Our frame: classification, then one renderer from it to the picture (opaque).
class OurFrame {
 public:
  virtual ~OurFrame() = default;
  PeerSurface run(const Scene& scene, const RenderOptions& o, bool cell_states) {
    FrameStats stats;
    const Stopwatch total;
    {
      const Stopwatch watch;
      classifier_.run(scene.view, GridView(), scene.classify);
      stats.add_time("classify", watch.ms());
    }
    const Classification& c = classifier_.result();
    const std::span<const ParticleSphere> spheres =
        cell_states ? std::span<const ParticleSphere>(c.boundary) : scene.all;
    render(scene.state.camera, spheres, cell_states ? c.cell_states() : CellStatesView{}, o, stats);
    const double ms = total.ms();
    PeerSurface s = surface();
    add_stages(stats, s);
    s.ms["total"] = ms;
    return s;
  }

 protected:
  virtual void render(const Camera& camera, std::span<const ParticleSphere> spheres,
                      const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) = 0;
  // The last frame's spans and their own first hit (after the recorder stopped).
  virtual PeerSurface surface() = 0;

 private:
  Classifier classifier_;
};

class CpuFrame final : public OurFrame {
  void render(const Camera& camera, std::span<const ParticleSphere> spheres,
              const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) override {
    Recorder recorder(stats);
    spans_ = &renderer_.cast(camera, spheres, cells, o.voxelize, recorder);
    renderer_.shade(*spans_, o.surfaces, o.shade, recorder);
    recorder.collect();
  }
  PeerSurface surface() override {
    CpuRenderer::first_hit(*spans_, first_);
    return surface_of(*spans_, first_);
  }
  CpuRenderer renderer_;
  const SpanImage* spans_ = nullptr;
  FloatImage first_;
};

class GlFrame final : public OurFrame {
 public:
  explicit GlFrame(const gl::ContextOptions& options)
      : context_(options), renderer_(shaders_), recorder_(context_.has_gpu_timers()) {
    tools::print_renderer(context_);
  }

 private:
  void render(const Camera& camera, std::span<const ParticleSphere> spheres,
              const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) override {
    recorder_.record_into(stats);
    const GpuFloatImage& image = renderer_.render(camera, spheres, cells, o, recorder_);
    {
      auto t = recorder_.device(pass::readback);
      image.download(picture_);
    }
    recorder_.collect();
  }
  PeerSurface surface() override {
    renderer_.voxelizer().image().download(spans_);
    CpuRenderer::first_hit(spans_, first_);
    return surface_of(spans_, first_);
  }
  gl::Context context_;
  gl::ShaderLibrary shaders_;
  Renderer renderer_;
  gl::GpuRecorder recorder_;
  FloatImage picture_, first_;
  SpanImage spans_;
};

// The same surface pipeline and shading for every method (ours, the peers', the reference's
// spans): the CPU renderer's connect, filter, normals and shade at the runtime's defaults, opaque
// and translucent. Whatever a method smooths or not, the picture is made the same way from its
// spans, so that the pictures differ by the geometry alone.
struct Seen {
  std::vector<float> first_hit;  // after the filter; +infinity: none
  FloatImage opaque, translucent;
};

Seen seen(const PeerSurface& surface, const PerspectiveGrid& grid, const RenderOptions& o) {
  static CpuRenderer renderer;
  const SpanImage spans = span_image_of(surface, grid);
  FrameStats stats;
  Recorder recorder(stats);
  Seen out;
  ShadeOptions shade = o.shade;
  shade.mode = ShadeMode::translucent;
  renderer.shade(spans, o.surfaces, shade, recorder, out.translucent);
  shade.mode = ShadeMode::opaque;
  renderer.shade(spans, o.surfaces, shade, recorder, out.opaque);
  FloatImage first;
  CpuRenderer::first_hit(spans, first, renderer.surface_depths());
  out.first_hit.resize(spans.pixels.size());
  for (std::size_t i = 0; i < out.first_hit.size(); ++i)
    out.first_hit[i] = first.rgba[4 * i] > 0 ? first.rgba[4 * i] : kNone;
  return out;
}

struct Errors {
  double median = 0, p99 = 0, max = 0;  // first hit after the filter, radii
  double raw_p99 = 0;                   // first hit of the spans themselves, radii
  std::int64_t missed = 0, extra = 0;   // silhouette pixels
  double thickness_p99 = 0;             // radii, over the pixels either hits
  double psnr_opaque = 0, psnr_translucent = 0;
};

double percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// |a - b| / radius over the pixels both hit.
std::vector<double> hit_differences(const std::vector<float>& a, const std::vector<float>& b,
                                    double radius) {
  std::vector<double> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] < kNone && b[i] < kNone) out.push_back(std::abs(double(a[i]) - b[i]) / radius);
  return out;
}

Errors errors_of(const PeerSurface& m, const Seen& m_seen, const PeerSurface& ref,
                 const Seen& ref_seen, double radius) {
  Errors e;
  std::vector<double> hit = hit_differences(m_seen.first_hit, ref_seen.first_hit, radius);
  if (!hit.empty()) {
    e.max = *std::max_element(hit.begin(), hit.end());
    e.p99 = percentile(hit, 0.99);
    e.median = percentile(hit, 0.5);
  }
  std::vector<double> raw = hit_differences(m.first_hit, ref.first_hit, radius);
  e.raw_p99 = percentile(raw, 0.99);
  std::vector<double> thick;
  for (std::size_t i = 0; i < ref.first_hit.size(); ++i) {
    const bool a = m_seen.first_hit[i] < kNone, b = ref_seen.first_hit[i] < kNone;
    e.missed += b && !a;
    e.extra += a && !b;
    if (a || b) thick.push_back(std::abs(double(m.thickness[i]) - ref.thickness[i]) / radius);
  }
  e.thickness_p99 = percentile(thick, 0.99);
  e.psnr_opaque = test::compare_images(m_seen.opaque, ref_seen.opaque).psnr;
  e.psnr_translucent = test::compare_images(m_seen.translucent, ref_seen.translucent).psnr;
  return e;
}

// Stage times of a method's frames: medians, per stage.
struct Timing {
  std::map<std::string, std::vector<double>> ms;
  std::map<std::string, double> medians() const {
    std::map<std::string, double> out;
    for (const auto& [stage, t] : ms) out[stage] = tools::median(t);
    return out;
  }
  void add(const PeerSurface& s) {
    for (const auto& [stage, t] : s.ms) ms[stage].push_back(t);
  }
};

std::string fmt(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

// Our settings: the runtime's defaults (docs/runtime.md), then one change at a time.
struct OurSetting {
  std::string text;
  bool is_default = false;
  RenderOptions options;
  bool cell_states = true;
};

RenderOptions default_options(const tools::DamBreakState& s) {
  RenderOptions o;
  o.voxelize.gap_bridging = s.spacing;
  o.surfaces.filter_radius = s.spacing;
  o.shade.mode = ShadeMode::opaque;
  o.shade.environment.up = s.up;
  o.shade.environment.rest_on_floor(s.ground, s.spacing);
  o.shade.environment.ground_tile = 12 * s.spacing;
  // absorption: auto, through the column's width (the first step's smallest side).
  o.shade.material.absorption = Material::water_absorption(s.length);
  return o;
}

std::vector<OurSetting> our_settings(const tools::DamBreakState& s, bool gl, bool quick) {
  std::vector<OurSetting> out;
  const RenderOptions base = default_options(s);
  out.push_back({"default", true, base});
  if (quick) return out;
  const auto add = [&](std::string text, auto change, bool cell_states = true) {
    OurSetting v{std::move(text), false, base, cell_states};
    change(v.options);
    out.push_back(v);
  };
  add("gap 0", [](RenderOptions& o) { o.voxelize.gap_bridging = 0; });
  add("gap 2 spacing", [&](RenderOptions& o) { o.voxelize.gap_bridging = 2 * s.spacing; });
  for (std::uint32_t cap : {1u, 4u})
    add("span cap " + std::to_string(cap), [&](RenderOptions& o) { o.voxelize.max_spans = cap; });
  add(
      "no inner cells", [](RenderOptions&) {}, false);
  if (gl) {
    for (double alpha : {28.0, 7.0, 3.5})
      add("alpha " + fmt("%g", alpha),
          [&](RenderOptions& o) { o.voxelize.grid.alpha_degrees = alpha; });
    add("span ends at voxel centres",
        [](RenderOptions& o) { o.voxelize.span_edges = SpanEdges::middle; });
    add("alpha 28, ends at centres", [](RenderOptions& o) {
      o.voxelize.grid.alpha_degrees = 28;
      o.voxelize.span_edges = SpanEdges::middle;
    });
    add("layers <= 1024", [](RenderOptions& o) { o.voxelize.grid.max_layers = 1024; });
    add("tile budget 64 MiB",
        [](RenderOptions& o) { o.voxelize.tiles.memory_budget = std::size_t(64) << 20; });
  }
  return out;
}

std::vector<Method> methods_for(const Args& a, const Scene& scene,
                                std::vector<std::unique_ptr<OurFrame>>& frames) {
  const tools::DamBreakState& s = scene.state;
  const double r = s.spacing;  // the spheres' radius: the particle spacing
  std::vector<Method> out;
  for (const char* family : {"cpu", "gl"}) {
    if (!a.methods.contains(family)) continue;
    const bool gl = std::string(family) == "gl";
    if (gl) frames.push_back(std::make_unique<GlFrame>(a.context));
    else frames.push_back(std::make_unique<CpuFrame>());
    OurFrame* frame = frames.back().get();
    for (const OurSetting& v : our_settings(s, gl, a.quick))
      out.push_back({family, v.text, v.is_default,
                     [frame, &scene, v] { return frame->run(scene, v.options, v.cell_states); }});
  }
  if (a.methods.contains("openvdb")) {
    const std::vector<double> divisions =
        a.quick ? std::vector<double>{2} : std::vector<double>{1, 2, 3, 4};
    for (double k : divisions)
      for (int smoothing : {0, 1}) {
        if (a.quick && smoothing > 0) continue;
        tools::VdbLevelSetOptions o;
        o.voxel = r / k;
        o.smoothing = smoothing;
        // Spheres of one voxel are under the default minimum radius: keep them all.
        o.min_radius_voxels = std::min(1.5, 0.5 * k);
        out.push_back({"openvdb", "voxel r/" + fmt("%g", k) + (smoothing ? ", smoothed" : ""),
                       false, [&scene, o, r] {
                         return tools::vdb_level_set_surface(
                             scene.state.x, scene.state.y, scene.state.z, r, scene.state.camera, o);
                       }});
      }
  }
#ifdef VOXSPAN_HAVE_VTK_PEER
  if (a.methods.contains("vtk")) {
    // Voxels of the spacing and half of it at the iso value 0.5 (the fluid's edge, half a
    // spacing past the outer particles' centres), and a lower iso that reaches the union's.
    const std::vector<std::pair<double, double>> settings =
        a.quick ? std::vector<std::pair<double, double>>{{0.5, 0.5}}
                : std::vector<std::pair<double, double>>{{1, 0.5}, {0.5, 0.5}, {0.5, 0.2}};
    for (const auto& [voxel, iso] : settings) {
      tools::VtkSphOptions o;
      o.voxel = voxel * s.spacing;
      o.smoothing_length = 1.3 * s.spacing;
      o.iso = iso;
      out.push_back({"vtk", "voxel " + fmt("%g", voxel) + " spacing, iso " + fmt("%g", iso), false,
                     [&scene, o] {
                       PeerSurface p =
                           tools::vtk_sph_surface(scene.state.x, scene.state.y, scene.state.z,
                                                  scene.state.spacing, scene.state.camera, o);
                       p.note.clear();  // the settings in words: the table has them
                       return p;
                     }});
    }
  }
#endif
  return out;
}

int run(const Args& a) {
  Scene scene{tools::dam_break_state(a, a), {}, {}, {}};
  tools::DamBreakState& s = scene.state;
  s.camera.width = a.width;
  s.camera.height = a.height;
  scene.view = ParticleView::soa(s.x.data(), s.y.data(), s.z.data(), s.x.size());
  scene.classify.particle_spacing = s.spacing;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    scene.all.push_back({s.x[i], s.y[i], s.z[i], float(s.spacing)});
  const double radius = s.spacing;
  std::printf("scene: %s; %dx%d, %zu particles, %zu boundary; radius r = %g\n",
              s.description.c_str(), a.width, a.height, s.x.size(),
              s.classification.boundary.size(), radius);

  // The reference, in the frame the CPU renderer fits (the GPU's: same near, same far).
  CpuRenderer fit;
  FrameStats fit_stats;
  Recorder fit_recorder(fit_stats);
  const PerspectiveGrid grid =
      fit.cast(s.camera, s.classification.boundary, s.classification.cell_states(),
               default_options(s).voxelize, fit_recorder)
          .grid;
  Classifier classifier;
  // With the runtime's gap bridging (the particle spacing): closing the gaps shorter than it is
  // the model's choice, not an error; without it the spans would differ by their gaps alone.
  const Method exact{
      "exact", "gap = spacing, no cap", false, [&] {
        const Stopwatch total;
        classifier.run(scene.view, GridView(), scene.classify);
        const Classification& c = classifier.result();
        const SpanImage spans = exact_spans(grid, c.boundary, c.cell_states(), {s.spacing, 0});
        const double ms = total.ms();
        FloatImage first;
        CpuRenderer::first_hit(spans, first);
        PeerSurface out = surface_of(spans, first);
        out.ms["total"] = ms;
        return out;
      }};
  const PeerSurface ref = exact.run();  // the warm-up of the exact method, and the yardstick
  const RenderOptions shading = default_options(s);
  const Seen ref_seen = seen(ref, grid, shading);

  std::vector<std::unique_ptr<OurFrame>> frames;
  std::vector<Method> methods;
  if (a.methods.contains("exact")) methods.push_back(exact);
  for (Method& m : methods_for(a, scene, frames)) methods.push_back(std::move(m));

  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw make_error("cannot write ", a.csv);
    csv << "particles,width,height,family,settings,default,total_ms,first_hit_median_r,"
           "first_hit_p99_r,first_hit_max_r,raw_first_hit_p99_r,missed,extra,thickness_p99_r,"
           "psnr_opaque_db,psnr_translucent_db,elements,stages,note\n";
  }
  std::printf("\n%-8s %-26s %8s %7s %7s %7s %7s %6s %6s %7s %6s %6s  %s\n", "method", "settings",
              "ms", "hit med", "hit p99", "hit max", "raw p99", "missed", "extra", "thick99",
              "PSNR o", "PSNR t", "stages (ms)");
  std::int64_t ref_hits = 0;
  for (float d : ref_seen.first_hit) ref_hits += d < kNone;
  // Errors from each method's warm-up frame (its surfaces are the same every frame), then the
  // timed frames taken in turns, method after method, so that the shared machine's load drifts
  // alike over all of them.
  int failed = 0;
  std::vector<Errors> errors;
  std::vector<PeerSurface> firsts;
  for (const Method& m : methods) {
    PeerSurface out = m.family == "exact" ? ref : m.run();
    errors.push_back(errors_of(out, seen(out, grid, shading), ref, ref_seen, radius));
    out.first_hit.clear(), out.thickness.clear(), out.spans.clear();
    firsts.push_back(std::move(out));
  }
  std::vector<Timing> timing(methods.size());
  for (int f = 0; f < a.frames; ++f)
    for (std::size_t i = 0; i < methods.size(); ++i) timing[i].add(methods[i].run());
  for (std::size_t i = 0; i < methods.size(); ++i) {
    const Method& m = methods[i];
    const Errors& e = errors[i];
    const PeerSurface& out = firsts[i];
    const std::map<std::string, double> ms = timing[i].medians();
    if (a.check) {
      const bool same = e.p99 < 1e-4 && e.missed == 0 && e.extra == 0 &&
                        std::isinf(e.psnr_opaque) && std::isinf(e.psnr_translucent);
      const bool sees = 2 * e.missed < ref_hits && std::isfinite(e.p99) && e.p99 < 10;
      if ((m.family == "cpu" && m.is_default && !same) || !sees) {
        std::fprintf(stderr, "bench_peers: check failed: %s %s (%s)\n", m.family.c_str(),
                     m.settings.c_str(), sees ? "not equal to the reference" : "misses the fluid");
        ++failed;
      }
    }
    std::string stages;
    for (const auto& [stage, t] : ms)
      if (stage != "total") stages += stage + " " + fmt("%.1f", t) + " ";
    std::printf("%-8s %-26s %8.1f %7.3f %7.3f %7.3f %7.3f %6lld %6lld %7.3f %6.1f %6.1f  %s%s\n",
                m.family.c_str(), (m.settings + (m.is_default ? " *" : "")).c_str(), ms.at("total"),
                e.median, e.p99, e.max, e.raw_p99, static_cast<long long>(e.missed),
                static_cast<long long>(e.extra), e.thickness_p99, e.psnr_opaque, e.psnr_translucent,
                stages.c_str(), out.note.empty() ? "" : ("[" + out.note + "]").c_str());
    if (csv)
      csv << s.x.size() << ',' << a.width << ',' << a.height << ',' << m.family << ",\""
          << m.settings << "\"," << int(m.is_default) << ',' << ms.at("total") << ',' << e.median
          << ',' << e.p99 << ',' << e.max << ',' << e.raw_p99 << ',' << e.missed << ',' << e.extra
          << ',' << e.thickness_p99 << ',' << e.psnr_opaque << ',' << e.psnr_translucent << ','
          << out.elements << ",\"" << stages << "\",\"" << out.note << "\"\n";
  }
  std::printf("\n* the runtime's default settings; r = the particle radius\n");
  return failed == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_peers", argc, argv, kUsage, parse, run);
}
