// bench_peers: our renderers, swept over their settings, against the tools a user would run
// instead, on the same particles and camera in one run, each timed and its error measured
// against the exact reference (docs/results.md).
//
// The scene is the tools' dam break (tools/dambreak_state.h: the WCSPH solver at Martin &
// Moyce's T, about --particles fluid particles, spheres of the particle spacing). The methods:
//   exact     the exact reference's caster (render/reference/exact_spans.h): every candidate
//             sphere of the pixel's 8x8 bin, in double; the yardstick, and a method of its own
//   cpu, gl   our renderers, classification to picture (opaque), over a sweep of settings:
//             filter radius, gap bridging, span cap, inner-cell skipping, and for the GL one's
//             voxelization the angle resolution, the layer cap and the tile budget
//   openvdb   ParticlesToLevelSet at voxels from the radius to a quarter of it, without and with
//             mean-value smoothing, then its level-set ray intersector (tools/peers/vdb_level_set.h)
//   vtk       vtkSPHInterpolator onto a volume, vtkFlyingEdges3D, the mesh ray cast by Embree
//             (tools/peers/vtk_sph_surface.h; built where VTK's filters and Embree are found)
// Every method starts from the solver's particle arrays: our time includes the classification,
// the peers' their whole build. Errors, against the exact spans of the union of the spheres:
// first-hit distance along the unit ray (median, 99th percentile, max over the pixels both hit,
// in particle radii), silhouette pixels missed and extra, the 99th percentile of the length
// inside the fluid (thickness, radii), and the PSNR of one shading of the first-hit surface,
// the same for every method (normals from the first-hit depths, one light), against the
// reference's. Our surfaces are the ones the picture shows: after the depth filter.
// Milliseconds are medians over --frames frames after one warm-up.
//
//   bench_peers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH] [--frames F]
//               [--methods exact,cpu,gl,openvdb,vtk] [--quick] [--csv FILE]
//               [--platform auto|nvidia|device|surfaceless]
// --quick: each family's default settings only (and the smallest sweep of the peers).
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

#include "dambreak_state.h"
#include "peers/vdb_level_set.h"
#include "render/cpu/cpu_renderer.h"
#include "render/gl/context.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/renderer.h"
#include "tool_args.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"
#ifdef VOXSPAN_HAVE_VTK_PEER
#include "peers/vtk_sph_surface.h"
#endif

namespace {

using namespace voxspan;
using tools::PeerSurface;

struct Args : tools::BenchArgs {
  std::string state = "build/dambreak_state.bin";
  bool ritter = !tools::have_solver();
  std::set<std::string> methods = {"exact", "cpu", "gl", "openvdb", "vtk"};
  bool quick = false;
  std::string csv;
};

constexpr char kUsage[] =
    "usage: bench_peers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F] [--methods exact,cpu,gl,openvdb,vtk] [--quick] [--csv FILE]\n"
    "         [--platform auto|nvidia|device|surfaceless]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--methods")) {
    a.methods.clear();
    for (const std::string& m : tools::comma_list(v)) {
      if (m != "exact" && m != "cpu" && m != "gl" && m != "openvdb" && m != "vtk") return false;
      a.methods.insert(m);
    }
    return !a.methods.empty();
  }
  return tools::read_bench_flag(arg, a) || arg.value("--state", a.state) ||
         arg.flag("--ritter", a.ritter) || arg.flag("--quick", a.quick) ||
         arg.value("--csv", a.csv);
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

// A span image as a peer's surface: first hit from `first` (0: none), thickness from the spans.
PeerSurface surface_of(const SpanImage& spans, const FloatImage& first) {
  PeerSurface s;
  s.first_hit.resize(spans.pixels.size());
  s.thickness.resize(spans.pixels.size());
  for (std::size_t i = 0; i < spans.pixels.size(); ++i) {
    const float d = first.rgba[4 * i];
    s.first_hit[i] = d > 0 ? d : kNone;
    s.thickness[i] = spans.pixels[i].inside;
  }
  s.elements = spans.spans.size();
  return s;
}

// The stages of our frames, as FrameStats names them, in frame order.
const char* kOurStages[] = {"classify", "frame",   "upload",  "bin",    "clear",    "splat",
                            "compress", "cast",    "connect", "filter", "normals",  "shade",
                            "readback"};

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
    render(scene.state.camera, spheres, cell_states ? c.cell_states() : CellStatesView{}, o,
           stats);
    const double ms = total.ms();
    PeerSurface s = surface();
    add_stages(stats, s);
    s.ms["total"] = ms;
    return s;
  }

 protected:
  virtual void render(const Camera& camera, std::span<const ParticleSphere> spheres,
                      const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) = 0;
  // The last frame's surface (after the timer stopped).
  virtual PeerSurface surface() = 0;

 private:
  Classifier classifier_;
};

class CpuFrame final : public OurFrame {
  void render(const Camera& camera, std::span<const ParticleSphere> spheres,
              const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) override {
    gl::PassTimer timer(false);
    spans_ = &renderer_.cast(camera, spheres, cells, o.voxelize, timer, stats);
    renderer_.shade(*spans_, o.surfaces, o.shade, timer, stats);
    timer.collect(stats);
  }
  PeerSurface surface() override {
    CpuRenderer::first_hit(*spans_, first_, renderer_.surface_depths());
    return surface_of(*spans_, first_);
  }
  CpuRenderer renderer_;
  const SpanImage* spans_ = nullptr;
  FloatImage first_;
};

class GlFrame final : public OurFrame {
 public:
  explicit GlFrame(const gl::ContextOptions& options)
      : context_(options), renderer_(shaders_), timer_(context_.has_gpu_timers()) {
    tools::print_renderer(context_);
  }

 private:
  void render(const Camera& camera, std::span<const ParticleSphere> spheres,
              const CellStatesView& cells, const RenderOptions& o, FrameStats& stats) override {
    const GpuFloatImage& image = renderer_.render(camera, spheres, cells, o, timer_, stats);
    {
      auto t = timer_.gpu("readback");
      image.download(picture_);
    }
    timer_.collect(stats);
  }
  PeerSurface surface() override {
    const GpuSpanImage& gpu = renderer_.voxelizer().image();
    gpu.download(spans_);
    const std::vector<glm::vec2> depths =
        renderer_.surfaces().filtered() ? renderer_.surfaces().download_depths(gpu)
                                        : std::vector<glm::vec2>{};
    CpuRenderer::first_hit(spans_, first_, depths);
    return surface_of(spans_, first_);
  }
  gl::Context context_;
  gl::ShaderLibrary shaders_;
  Renderer renderer_;
  gl::PassTimer timer_;
  FloatImage picture_, first_;
  SpanImage spans_;
};

// One shading of a first-hit surface for every method: normals from the world points of the
// neighbouring pixels (on each axis the side nearer in depth, so that silhouettes do not bend
// them), a key light from above the camera's left, a grey background.
FloatImage shade_first_hit(const std::vector<float>& d, const Camera& camera) {
  const ViewFrame view(camera);
  const int w = camera.width, h = camera.height;
  FloatImage image(w, h);
  const glm::dvec3 light = glm::normalize(-0.4 * view.right + 0.7 * view.up - 0.6 * view.forward);
  const auto hit = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && d[std::size_t(x) + std::size_t(y) * w] < kNone;
  };
  const auto point = [&](int x, int y) {
    return view.eye + double(d[std::size_t(x) + std::size_t(y) * w]) *
                          glm::normalize(view.world_ray(x, y));
  };
  const auto tangent = [&](int x, int y, int dx, int dy) {
    const glm::dvec3 p = point(x, y);
    const bool a = hit(x + dx, y + dy), b = hit(x - dx, y - dy);
    if (!a && !b) return glm::dvec3(0);
    if (a && b) {
      const glm::dvec3 pa = point(x + dx, y + dy) - p, pb = p - point(x - dx, y - dy);
      return glm::length(pa) < glm::length(pb) ? pa : pb;
    }
    return a ? point(x + dx, y + dy) - p : p - point(x - dx, y - dy);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 c(0.35f);
      if (hit(x, y)) {
        glm::dvec3 n = glm::cross(tangent(x, y, 0, -1), tangent(x, y, 1, 0));
        double lit = 0.5;
        if (glm::length(n) > 0) {
          n = glm::normalize(n);
          if (glm::dot(n, view.world_ray(x, y)) > 0) n = -n;
          lit = 0.15 + 0.85 * std::max(0.0, glm::dot(n, light));
        }
        c = glm::vec3(0.25f, 0.55f, 0.9f) * float(lit);
      }
      image.set(x, y, glm::vec4(c, 1.0f));
    }
  return image;
}

struct Errors {
  double median = 0, p99 = 0, max = 0;  // first hit, radii
  std::int64_t missed = 0, extra = 0;   // silhouette pixels
  double thickness_p99 = -1;            // radii; < 0: the method gives none
  double psnr = 0;
};

double percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

Errors errors_of(const PeerSurface& m, const PeerSurface& ref, const FloatImage& ref_picture,
                 double radius, const Camera& camera) {
  Errors e;
  std::vector<double> hit, thick;
  for (std::size_t i = 0; i < ref.first_hit.size(); ++i) {
    const bool a = m.first_hit[i] < kNone, b = ref.first_hit[i] < kNone;
    if (a && b) hit.push_back(std::abs(double(m.first_hit[i]) - ref.first_hit[i]) / radius);
    e.missed += b && !a;
    e.extra += a && !b;
    if (!m.thickness.empty() && (a || b))
      thick.push_back(std::abs(double(m.thickness[i]) - ref.thickness[i]) / radius);
  }
  if (!hit.empty()) {
    e.max = *std::max_element(hit.begin(), hit.end());
    e.p99 = percentile(hit, 0.99);
    e.median = percentile(hit, 0.5);
  }
  if (!m.thickness.empty()) e.thickness_p99 = percentile(thick, 0.99);
  e.psnr = test::compare_images(shade_first_hit(m.first_hit, camera), ref_picture).psnr;
  return e;
}

// Runs a method one warm-up and `frames` timed frames; the stage times are medians.
PeerSurface timed(const Method& m, int frames) {
  PeerSurface last = m.run();
  std::map<std::string, std::vector<double>> ms;
  for (int f = 0; f < frames; ++f) {
    last = m.run();
    for (const auto& [stage, t] : last.ms) ms[stage].push_back(t);
  }
  for (auto& [stage, t] : ms) last.ms[stage] = tools::median(t);
  return last;
}

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
  for (double f : {0.0, 0.5, 2.0})
    add("filter " + fmt("%g", f) + " spacing",
        [&](RenderOptions& o) { o.surfaces.filter_radius = f * s.spacing; });
  add("gap 0", [](RenderOptions& o) { o.voxelize.gap_bridging = 0; });
  add("gap 2 spacing", [&](RenderOptions& o) { o.voxelize.gap_bridging = 2 * s.spacing; });
  for (std::uint32_t cap : {1u, 4u})
    add("span cap " + std::to_string(cap), [&](RenderOptions& o) { o.voxelize.max_spans = cap; });
  add("no inner cells", [](RenderOptions&) {}, false);
  add("filter 0, no inner cells", [](RenderOptions& o) { o.surfaces.filter_radius = 0; }, false);
  if (gl) {
    for (double alpha : {28.0, 7.0, 3.5})
      add("alpha " + fmt("%g", alpha),
          [&](RenderOptions& o) { o.voxelize.grid.alpha_degrees = alpha; });
    for (double alpha : {28.0, 7.0})
      add("alpha " + fmt("%g", alpha) + ", filter 0", [&](RenderOptions& o) {
        o.voxelize.grid.alpha_degrees = alpha;
        o.surfaces.filter_radius = 0;
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
      out.push_back({family, v.text, v.is_default, [frame, &scene, v] {
                       return frame->run(scene, v.options, v.cell_states);
                     }});
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
        out.push_back({"openvdb",
                       "voxel r/" + fmt("%g", k) + (smoothing ? ", smoothed" : ""), false,
                       [&scene, o, r] {
                         return tools::vdb_level_set_surface(scene.state.x, scene.state.y,
                                                             scene.state.z, r, scene.state.camera,
                                                             o);
                       }});
      }
  }
#ifdef VOXSPAN_HAVE_VTK_PEER
  if (a.methods.contains("vtk")) {
    const std::vector<double> voxels =
        a.quick ? std::vector<double>{0.5} : std::vector<double>{1, 0.5, 0.33};
    for (double v : voxels) {
      tools::VtkSphOptions o;
      o.voxel = v * s.spacing;
      o.smoothing_length = 1.3 * s.spacing;
      out.push_back({"vtk", "voxel " + fmt("%.2g", v) + " spacing, h 1.3 spacing", false,
                     [&scene, o] {
                       return tools::vtk_sph_surface(scene.state.x, scene.state.y, scene.state.z,
                                                     scene.state.spacing, scene.state.camera, o);
                     }});
    }
  }
#endif
  return out;
}

int run(const Args& a) {
  Scene scene{tools::dam_break_state(a.ritter, a.particles, a.time, a.state), {}, {}, {}};
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
  gl::PassTimer fit_timer(false);
  const PerspectiveGrid grid = fit.cast(s.camera, s.classification.boundary,
                                        s.classification.cell_states(),
                                        default_options(s).voxelize, fit_timer, fit_stats)
                                   .grid;
  Classifier classifier;
  const Method exact{"exact", "gap 0, no cap", false, [&] {
                       const Stopwatch total;
                       classifier.run(scene.view, GridView(), scene.classify);
                       const Classification& c = classifier.result();
                       const SpanImage spans =
                           exact_spans(grid, c.boundary, c.cell_states(), {0.0, 0});
                       const double ms = total.ms();
                       FloatImage first;
                       CpuRenderer::first_hit(spans, first);
                       PeerSurface out = surface_of(spans, first);
                       out.ms["total"] = ms;
                       return out;
                     }};
  const PeerSurface ref = timed(exact, a.frames);
  const FloatImage ref_picture = shade_first_hit(ref.first_hit, s.camera);

  std::vector<std::unique_ptr<OurFrame>> frames;
  std::vector<Method> methods;
  if (a.methods.contains("exact")) methods.push_back(exact);
  for (Method& m : methods_for(a, scene, frames)) methods.push_back(std::move(m));

  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw make_error("cannot write ", a.csv);
    csv << "particles,width,height,family,settings,default,total_ms,first_hit_median_r,"
           "first_hit_p99_r,first_hit_max_r,missed,extra,thickness_p99_r,psnr_db,elements,"
           "stages,note\n";
  }
  std::printf("\n%-8s %-34s %9s %8s %8s %8s %7s %7s %8s %7s  %s\n", "method", "settings",
              "ms", "hit med", "hit p99", "hit max", "missed", "extra", "thick99", "PSNR",
              "stages (ms)");
  for (const Method& m : methods) {
    const PeerSurface out = m.family == "exact" ? ref : timed(m, a.frames);
    const Errors e = errors_of(out, ref, ref_picture, radius, s.camera);
    std::string stages;
    for (const auto& [stage, ms] : out.ms)
      if (stage != "total") stages += stage + " " + fmt("%.1f", ms) + " ";
    std::printf("%-8s %-34s %9.1f %8.3f %8.3f %8.3f %7lld %7lld %8.3f %7.1f  %s%s\n",
                m.family.c_str(), (m.settings + (m.is_default ? " *" : "")).c_str(),
                out.ms.at("total"), e.median, e.p99, e.max, static_cast<long long>(e.missed),
                static_cast<long long>(e.extra), e.thickness_p99, e.psnr, stages.c_str(),
                out.note.empty() ? "" : ("[" + out.note + "]").c_str());
    std::fflush(stdout);
    if (csv)
      csv << s.x.size() << ',' << a.width << ',' << a.height << ',' << m.family << ",\""
          << m.settings << "\"," << int(m.is_default) << ',' << out.ms.at("total") << ','
          << e.median << ',' << e.p99 << ',' << e.max << ',' << e.missed << ',' << e.extra << ','
          << e.thickness_p99 << ',' << e.psnr << ',' << out.elements << ",\"" << stages << "\",\""
          << out.note << "\"\n";
  }
  std::printf("\n* the runtime's default settings; r = the particle radius\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_peers", argc, argv, kUsage, parse, run);
}
