// bench_renderers: the GPU renderer (GL: an NVIDIA GPU, or llvmpipe on a CPU) and the CPU
// renderer (render/cpu/cpu_renderer.h) on the same particles and camera in one run, per pass
// side by side with the ratio, and the exact reference's caster (render/reference/
// exact_spans.h: per pixel every candidate of its 8x8 bin, in double) on the spans alone, with
// the CPU renderer's caster on the same grid phase by phase (span_caster.h's CastPhase).
//
// The scene is bench_shading's: the WCSPH dam break at Martin & Moyce's T (--time), about
// --particles fluid particles, state cached in --state (or --ritter). Each frame runs the
// classification of the state's particles (the render step begins there), then each
// renderer from the classification to the float image in host memory (the GL one read back,
// as the runtime does). Milliseconds are medians over --frames frames after one warm-up.
// "step" = classify + frame + read-back: what one view costs a render step. With both renderers
// the PSNR of the CPU renderer's picture against the GL one's is printed per mode.
//
//   bench_renderers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]
//                   [--frames F] [--modes opaque,translucent,refractive] [--ao]
//                   [--renderers gl,cpu] [--csv FILE] [--platform auto|nvidia|device|surfaceless]
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/cpu/cpu_renderer.h"
#include "render/cpu/span_caster.h"
#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/renderer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/stat_names.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;

struct Args : tools::BenchArgs, tools::StateFlags {
  std::vector<ShadeMode> modes = {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive};
  bool ao = false;
  bool gl = true, cpu = true;
  std::string csv;
};

constexpr char kUsage[] =
    "usage: bench_renderers [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F] [--modes opaque,translucent,refractive] [--ao] [--renderers gl,cpu]\n"
    "         [--csv FILE] [--platform auto|nvidia|device|surfaceless]\n";

// The passes in the order a frame runs them; each renderer has some of them.
const char* kPasses[] = {"classify", "frame",    "upload", "bin",      "clear",
                         "splat",    "compress", "cast",   "connect",  "filter",
                         "normals",  "deep_ao",  "shade",  "readback", "step"};

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--modes")) return tools::read_names(v, kShadeModeNames, a.modes);
  if (const char* v = arg.value("--renderers")) {
    a.gl = a.cpu = false;
    for (const std::string& r : tools::comma_list(v)) {
      if (r == "gl") a.gl = true;
      else if (r == "cpu") a.cpu = true;
      else return false;
    }
    return a.gl || a.cpu;
  }
  return tools::read_bench_flag(arg, a) || tools::read_state_flag(arg, a) ||
         arg.flag("--ao", a.ao) || arg.value("--csv", a.csv);
}

bool parse(int argc, char** argv, Args& a) {
  return tools::read_args(argc, argv, a, read_flag) && a.particles > 0;
}

using Samples = std::map<std::string, std::vector<double>>;

double median_of(Samples& s, const std::string& pass) {
  auto it = s.find(pass);
  return it == s.end() || it->second.empty() ? -1 : tools::median(it->second);
}

// One renderer's frame: from the classification to the picture in host memory.
class Frame {
 public:
  virtual ~Frame() = default;
  virtual const char* name() const = 0;
  virtual void render(const Camera& camera, const Classification& c, const RenderOptions& o,
                      FrameStats& stats) = 0;
  virtual const FloatImage& picture() const = 0;  // the last frame's
};

class GlFrame final : public Frame {
 public:
  explicit GlFrame(const gl::ContextOptions& options)
      : context_(options), renderer_(shaders_), recorder_(context_.has_gpu_timers()) {
    tools::print_renderer(context_);
  }
  const char* name() const override { return "gl"; }
  void render(const Camera& camera, const Classification& c, const RenderOptions& o,
              FrameStats& stats) override {
    recorder_.record_into(stats);
    const GpuFloatImage& image =
        renderer_.render(camera, c.boundary, c.cell_states(), o, recorder_);
    {
      auto t = recorder_.device(pass::readback);
      image.download(picture_);
    }
    recorder_.collect();
  }
  const FloatImage& picture() const override { return picture_; }

 private:
  gl::Context context_;
  gl::ShaderLibrary shaders_;
  Renderer renderer_;
  gl::GpuRecorder recorder_;
  FloatImage picture_;
};

class CpuFrame final : public Frame {
 public:
  const char* name() const override { return "cpu"; }
  void render(const Camera& camera, const Classification& c, const RenderOptions& o,
              FrameStats& stats) override {
    recorder_.record_into(stats);
    const SpanImage& spans =
        renderer_.cast(camera, c.boundary, c.cell_states(), o.voxelize, recorder_);
    picture_ = &renderer_.shade(spans, o.surfaces, o.shade, recorder_);
    recorder_.collect();
  }
  const FloatImage& picture() const override { return *picture_; }

 private:
  CpuRenderer renderer_;
  Recorder recorder_;
  const FloatImage* picture_ = nullptr;
};

// The CPU renderer's cast by phase (render/cpu/span_caster.h): its caster on the same grid,
// particles and settings, the median of each phase over the frames after one warm-up.
void print_cast_phases(const PerspectiveGrid& grid, const tools::DamBreakState& s,
                       const VoxelizeOptions& o, const Args& a, std::ofstream& csv) {
  SpanCaster caster;
  SpanImage spans;
  std::array<std::vector<double>, kCastPhaseNames.size()> ms;
  for (int f = -1; f < std::max(1, a.frames); ++f) {
    const CastCounts counts =
        caster.run(grid, s.classification.boundary, s.classification.cell_states(),
                   {o.gap_bridging, o.max_spans, o.use_cell_states}, spans);
    if (f < 0) continue;  // the warm-up
    for (std::size_t p = 0; p < ms.size(); ++p) ms[p].push_back(counts.phase_ms[p]);
  }
  std::printf("CPU renderer's cast by phase, median ms:");
  for (std::size_t p = 0; p < ms.size(); ++p) {
    std::printf(" %s %.2f", kCastPhaseNames[p], tools::median(ms[p]));
    if (csv)
      csv << s.x.size() << ',' << a.width << ',' << a.height << ",spans,cpu,cast."
          << kCastPhaseNames[p] << ',' << tools::median(ms[p]) << '\n';
  }
  std::printf("\n\n");
}

RenderOptions options_for(const tools::DamBreakState& s, const Args& a) {
  RenderOptions o;
  o.voxelize.grid.alpha_degrees = a.alpha;
  o.voxelize.grid.max_layers = a.max_layers;
  o.voxelize.gap_bridging = s.spacing;
  o.surfaces.filter_radius = s.spacing;
  o.shade = tools::bench_shading(s);
  o.shade.deep_ao = a.ao;
  return o;
}

int run(const Args& a) {
  tools::DamBreakState s = tools::dam_break_state(a, a);
  s.camera.width = a.width;
  s.camera.height = a.height;
  std::vector<std::unique_ptr<Frame>> frames;
  if (a.gl) frames.push_back(std::make_unique<GlFrame>(a.context));
  if (a.cpu) frames.push_back(std::make_unique<CpuFrame>());
  const auto view = ParticleView::soa(s.x.data(), s.y.data(), s.z.data(), s.x.size());
  ClassifyOptions classify;
  classify.particle_spacing = s.spacing;
  Classifier classifier;
  std::printf("scene: %s; %dx%d, %zu boundary particles\n", s.description.c_str(), a.width,
              a.height, s.classification.boundary.size());

  RenderOptions o = options_for(s, a);
  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw make_error("cannot write ", a.csv);
    csv << "particles,width,height,mode,renderer,pass,median_ms\n";
  }
  // The exact reference's caster, on the spans alone: the plain exact ray caster.
  {
    std::vector<double> ms;
    CpuRenderer fit;
    FrameStats stats;
    Recorder recorder(stats);
    const PerspectiveGrid grid = fit.cast(s.camera, s.classification.boundary,
                                          s.classification.cell_states(), o.voxelize, recorder)
                                     .grid;
    for (int f = 0; f < std::max(1, a.frames); ++f) {
      const Stopwatch watch;
      exact_spans(grid, s.classification.boundary, s.classification.cell_states(),
                  {o.voxelize.gap_bridging, o.voxelize.max_spans});
      ms.push_back(watch.ms());
    }
    recorder.collect();
    std::printf(
        "spans alone: exact reference caster %.1f ms, CPU renderer's cast %.1f ms "
        "(one frame; medians below)\n\n",
        tools::median(ms), stats.ms("cast"));
    if (csv)
      csv << s.x.size() << ',' << a.width << ',' << a.height << ",spans,reference,cast,"
          << tools::median(ms) << '\n';
    print_cast_phases(grid, s, o.voxelize, a, csv);
  }

  std::printf("%-12s %-4s", "median ms", "");
  for (const char* p : kPasses) std::printf(" %8s", p);
  std::printf("\n");
  for (ShadeMode mode : a.modes) {
    o.shade.mode = mode;
    std::vector<Samples> samples(frames.size());
    for (int f = -1; f < a.frames; ++f)
      for (std::size_t r = 0; r < frames.size(); ++r) {
        FrameStats stats;
        const Stopwatch step;
        {
          const Stopwatch watch;
          classifier.run(view, GridView(), classify);
          stats.add_time("classify", watch.ms());
        }
        frames[r]->render(s.camera, classifier.result(), o, stats);
        stats.add_time("step", step.ms());
        if (f < 0) continue;
        for (const char* p : kPasses)
          if (stats.runs(p) > 0) samples[r][p].push_back(stats.ms(p));
      }
    for (std::size_t r = 0; r < frames.size(); ++r) {
      std::printf("%-12s %-4s", shade_mode_name(mode), frames[r]->name());
      for (const char* p : kPasses) {
        const double ms = median_of(samples[r], p);
        if (ms < 0) std::printf(" %8s", "-");
        else std::printf(" %8.1f", ms);
        if (csv && ms >= 0)
          csv << s.x.size() << ',' << a.width << ',' << a.height << ',' << shade_mode_name(mode)
              << ',' << frames[r]->name() << ',' << p << ',' << ms << '\n';
      }
      std::printf("\n");
    }
    if (frames.size() == 2) {
      const test::ImageDifference d =
          test::compare_images(frames[0]->picture(), frames[1]->picture());
      std::printf(
          "%-12s %-4s %8.2f x faster on the CPU renderer (step, gl / cpu); pictures "
          "PSNR %.1f dB, at most %d/255\n",
          "", "", median_of(samples[0], "step") / median_of(samples[1], "step"), d.psnr,
          d.max_levels);
      if (csv)
        csv << s.x.size() << ',' << a.width << ',' << a.height << ',' << shade_mode_name(mode)
            << ",gl-cpu,psnr_db," << d.psnr << '\n';
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_renderers", argc, argv, kUsage, parse, run);
}
