// bench_shading: times a whole frame, voxelization then the passes after it ([ZD15] sec.
// 3.3-3.6: connect, filter, normals, deep AO, shade) per shading mode, on the dam break, and
// measures how close the shaded pictures come to the exact reference per angle resolution.
//
// Timing (default): the WCSPH dam break of examples/dambreak at Martin & Moyce's T (--time),
// about --particles fluid particles, state cached in --state; or --ritter: the Ritter-profile
// test scene (with --all-particles every particle is voxelized, no cell states: the way to
// reach millions of voxelized particles). Milliseconds per pass are medians over --frames
// frames after one warm-up (glFinish + wall clock on llvmpipe, GPU recorder queries on NVIDIA);
// "frame" is the whole frame from particles to the float image, no read-back, no disk.
//
// Accuracy (--accuracy FILE.csv): the voxelization's accuracy scenes (tools/scenes/
// accuracy_scenes.h) at 160x120, filter off, for each angle resolution of --alphas: PSNR of the
// GPU's picture against the exact reference with the same (Sobel) normals and with exact sphere
// normals, per mode; printed and written as CSV for tools/plots/plot_psnr.py. The shading is the
// tests' (test::test_shading); --bounces sets refraction's bounces (default: ShadeOptions').
//
//   bench_shading [--particles N] [--time T] [--state FILE] [--ritter] [--all-particles]
//                 [--size WxH] [--alpha DEG] [--max-layers L] [--budget-mib M] [--frames F]
//                 [--modes opaque,translucent,refractive] [--ao] [--accuracy FILE.csv]
//                 [--alphas 14,7,3.5,2,1] [--bounces N] [--json]
//                 [--platform auto|nvidia|device|surfaceless]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "render/gl/context.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/renderer.h"
#include "render/gl/shader_library.h"
#include "render/reference/exact_spans.h"
#include "render/reference/reference_shading.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/accuracy_scenes.h"
#include "tools/scenes/image_compare.h"
#include "voxspan/error.h"

namespace {

using namespace voxspan;

struct Args : tools::BenchArgs, tools::StateFlags {
  double budget_mib = 512;
  std::vector<ShadeMode> modes = {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive};
  bool ao = false;
  std::string accuracy;
  std::vector<double> alphas = {14, 7, 3.5, 2, 1};
  int bounces = -1;  // refraction's bounces in the accuracy figures; < 0: the default
};

const char* kPasses[] = {"frame",   "upload", "bin",     "clear",   "splat", "compress",
                         "connect", "filter", "normals", "deep_ao", "shade"};

constexpr char kUsage[] =
    "usage: bench_shading [--particles N] [--time T] [--state FILE] [--ritter]\n"
    "         [--all-particles] [--size WxH] [--alpha DEG] [--max-layers L]\n"
    "         [--budget-mib M] [--frames F] [--modes opaque,translucent,refractive]\n"
    "         [--ao] [--accuracy FILE.csv] [--alphas 14,7,3.5,2,1] [--bounces N] [--json]\n"
    "         [--platform auto|nvidia|device|surfaceless]\n";

// --modes opaque,translucent,refractive: false for another name.
bool read_modes(const std::string& list, std::vector<ShadeMode>& modes) {
  modes.clear();
  for (const std::string& m : tools::comma_list(list)) {
    if (m == "opaque") modes.push_back(ShadeMode::opaque);
    else if (m == "translucent") modes.push_back(ShadeMode::translucent);
    else if (m == "refractive") modes.push_back(ShadeMode::refractive);
    else return false;
  }
  return true;
}

// The flags beyond the scene's.
bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--modes")) return read_modes(v, a.modes);
  if (const char* v = arg.value("--alphas")) {
    a.alphas.clear();
    for (const std::string& alpha : tools::comma_list(v))
      a.alphas.push_back(std::atof(alpha.c_str()));
    return true;
  }
  return tools::read_bench_flag(arg, a) || tools::read_state_flag(arg, a) ||
         arg.value("--budget-mib", a.budget_mib) || arg.flag("--ao", a.ao) ||
         arg.value("--accuracy", a.accuracy) || arg.value("--bounces", a.bounces);
}

bool parse(int argc, char** argv, Args& a) {
  return tools::read_args(argc, argv, a, read_flag) && a.particles > 0 && !a.modes.empty();
}

void time_modes(const Args& a, const gl::Context& context, Renderer& renderer) {
  tools::DamBreakState s = tools::dam_break_state(a, a);
  const Classification& c = s.classification;
  std::vector<ParticleSphere> all;
  if (a.all_particles)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      all.push_back({s.x[i], s.y[i], s.z[i], float(s.spacing)});
  const std::vector<ParticleSphere>& particles = a.all_particles ? all : c.boundary;
  const CellStatesView cells = a.all_particles ? CellStatesView{} : c.cell_states();
  s.camera.width = a.width;
  s.camera.height = a.height;
  std::printf("scene: %s; %zu voxelized (%s)\n", s.description.c_str(), particles.size(),
              a.all_particles ? "all particles" : "boundary particles, cell states");

  RenderOptions o;
  o.voxelize.grid.alpha_degrees = a.alpha;
  o.voxelize.grid.max_layers = a.max_layers;
  o.voxelize.gap_bridging = s.spacing;
  o.voxelize.tiles.memory_budget = static_cast<std::size_t>(a.budget_mib * (1 << 20));
  o.surfaces.filter_radius = 1.5 * s.spacing;
  o.shade = tools::bench_shading(s);
  o.shade.deep_ao = a.ao;

  bool first = true;
  for (ShadeMode mode : a.modes) {
    o.shade.mode = mode;
    std::map<std::string, std::vector<double>> samples;
    FrameStats last;
    for (int f = -1; f < a.frames; ++f) {
      gl::reset_memory_peak();
      FrameStats stats;
      gl::GpuRecorder recorder(stats, context.has_gpu_timers());
      renderer.render(s.camera, particles, cells, o, recorder);
      recorder.collect();
      if (f < 0) continue;
      for (const char* p : kPasses) samples[p].push_back(stats.ms(p));
      samples["total"].push_back(stats.total_ms());
      last = stats;
    }
    if (first) {
      std::printf(
          "grid: %dx%d x %lld layers (alpha %.2f deg), %lld spans stored, filter %lld "
          "iterations\n\n%-22s",
          a.width, a.height, static_cast<long long>(last.count("grid.layers")),
          last.figure("grid.alpha_degrees"), static_cast<long long>(last.count("spans.stored")),
          static_cast<long long>(last.count("filter.iterations")), "mode (median ms)");
      for (const char* p : kPasses) std::printf(" %8s", p);
      std::printf(" %8s %8s\n", "total", "peak MiB");
      first = false;
    }
    char label[64];
    std::snprintf(label, sizeof label, "%s%s", shade_mode_name(mode), a.ao ? " + deep AO" : "");
    std::printf("%-22s", label);
    for (const char* p : kPasses) std::printf(" %8.1f", tools::median(samples[p]));
    std::printf(" %8.1f %8.0f\n", tools::median(samples["total"]),
                double(last.gpu_peak_bytes) / (1 << 20));
    if (mode == ShadeMode::refractive)
      std::printf(
          "  refraction: %lld march dispatches, %lld rays unfinished, %.1f column events "
          "per pixel, %lld at most\n",
          static_cast<long long>(last.count("refract.dispatches")),
          static_cast<long long>(last.count("refract.unfinished")),
          double(last.count("refract.events")) / (double(a.width) * a.height),
          static_cast<long long>(last.count("refract.most_events")));
    if (a.json) std::printf("  %s\n", last.json().c_str());
  }
}

void accuracy(const Args& a, const gl::Context& context, Renderer& renderer) {
  std::ofstream csv(a.accuracy);
  if (!csv) throw make_error("cannot write ", a.accuracy);
  csv << "scene,alpha,layers,mode,psnr_same_normals,psnr_sphere_normals\n";
  std::printf(
      "\nPSNR (dB) against the exact reference, same normals / sphere normals, 160x120, filter "
      "off\n");
  std::printf("%-18s %6s %6s %14s %14s %14s\n", "scene", "alpha", "layers", "opaque", "translucent",
              "refractive");
  for (const test::AccuracyScene& scene : test::accuracy_scenes(160, 120)) {
    for (double alpha : a.alphas) {
      VoxelizeOptions vo = scene.options;
      vo.grid.alpha_degrees = alpha;
      FrameStats stats;
      gl::GpuRecorder recorder(stats, context.has_gpu_timers());
      const GpuSpanImage& gpu =
          renderer.voxelizer().run(scene.camera, scene.particles, {}, vo, recorder);
      const SpanImage spans = gpu.download();
      std::vector<SpanNormals> exact_normals;
      const SpanImage exact = exact_spans(spans.grid, scene.particles, {},
                                          {vo.gap_bridging, vo.max_spans}, &exact_normals);
      const std::vector<glm::uvec2> sobel = reference_normals(exact, reference_links(exact));
      const std::vector<glm::uvec2> sphere = encode_exact_normals(exact_normals, sobel);
      std::printf("%-18s %6.2f %6d", scene.name.c_str(), alpha, spans.grid.layers());
      for (ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent, ShadeMode::refractive}) {
        ShadeOptions shade = test::test_shading(mode, scene.ground_tile);
        if (a.bounces >= 0) shade.bounces = a.bounces;
        const FloatImage image = renderer.shade(gpu, {}, shade, recorder).download();
        const double same =
            test::compare_images(image, reference_shading(exact, shade, &sobel)).psnr;
        const double exact_n =
            test::compare_images(image, reference_shading(exact, shade, &sphere)).psnr;
        std::printf(" %6.1f / %5.1f", same, exact_n);
        csv << '"' << scene.name << "\"," << alpha << ',' << spans.grid.layers() << ','
            << shade_mode_name(mode) << ',' << same << ',' << exact_n << '\n';
      }
      std::printf("\n");
      recorder.collect();
    }
  }
  std::printf("wrote %s\n", a.accuracy.c_str());
}

int run(const Args& a) {
  gl::Context context(a.context);
  tools::print_renderer(context);
  gl::ShaderLibrary shaders;
  Renderer renderer(shaders);
  if (!a.accuracy.empty()) accuracy(a, context, renderer);
  else time_modes(a, context, renderer);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_shading", argc, argv, kUsage, parse, run);
}
