// bench_volume: the volume views' renderer on the CPU (render/cpu/volume_caster.h) on the dam
// break, per phase, with what it did (samples, kernel evaluations, rays stopped early, iso hits),
// and with --convergence its error against the converged integral (render/reference/
// volume_reference.h: the sampling doubled until the picture changes under 1e-4, or 8 times)
// per sampling setting beside its time; --csv writes the rows for
// tools/plots/plot_volume_accuracy.py; --gl also times the GL renderer's march (its whole frame:
// the CPU's project, sort and bin, the upload, the march, the read-back) and its largest channel
// difference from the CPU picture. --tolerances adds, per DVR row, adaptive sampling at each
// tolerance (VolumeOptions::adaptive, --relax): its time and speed-up over the full-rate frame
// (the two timed in turn, the median of the pairs' ratios),
// its largest change from it and the share of channels past the tolerance, the share of samples
// skipped (and with --convergence its error against the converged integral). --lod adds, per
// row, particle level of detail at each level (VolumeOptions::level_of_detail, [FAW10] Fig. 8):
// the particles drawn, the time and speed-up (paired as the tolerances'), and the largest and
// 99th-percentile channel error against the frame of every particle (and the converged one).
//
// The scene is bench_renderers': the WCSPH dam break at Martin & Moyce's T (--time), about
// --particles fluid particles, state cached in --state (or --ritter, the Ritter-profile scene).
// The field: the volume fraction (--quantity fraction, the view's default) or the height above
// the floor (--quantity height), h = 1.3 spacings, the view's default transfer function (viridis
// and its default opacity points, or with --opacity one opacity per spacing for every value: 0.9
// is an opaque fluid, where occlusion culling pays: `culled` counts the screen tiles whose rays
// all stopped and the supports behind them not walked; --no-tile-culling turns it off), iso
// surfaces at 0.5 (fraction) or the middle
// of the range. Milliseconds are medians over --frames frames after one warm-up.
//
//   bench_volume [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH] [--frames F]
//                [--modes dvr,iso,mixed] [--sampling S,...] [--quantity fraction|height]
//                [--convergence] [--check] [--csv FILE] [--gl [--platform P]]
//                [--tolerances E,... [--relax R]] [--opacity A] [--no-tile-culling]
//                [--lod L,...]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "insitu/views/volume_view.h"
#include "render/cpu/volume_caster.h"
#include "render/gl/volume_renderer.h"
#include "render/reference/volume_reference.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/dambreak_volume.h"
#include "tools/common/tool_args.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;

struct Args : tools::BenchArgs, tools::StateFlags {
  std::vector<VolumeMode> modes = {VolumeMode::dvr, VolumeMode::iso, VolumeMode::mixed};
  std::vector<double> samplings = {1};
  bool height_field = false;  // the field: height above the floor, else the volume fraction
  bool convergence = false, check = false;
  bool gl = false;  // also the GL renderer's march (render/gl/volume_renderer.h)
  std::string csv;  // each row also as CSV (tools/plots/plot_volume_accuracy.py charts it)
  std::vector<double> tolerances;  // adaptive sampling's, DVR rows
  std::vector<double> levels;      // --lod: VolumeOptions::level_of_detail, rows per frame
  double relax = 0;
  double opacity = -1;  // --opacity: every value's opacity per spacing (< 0: the view's default)
  bool no_tile_culling = false;  // VolumeCaster::set_tile_culling(false): rays stop one by one
};

constexpr char kUsage[] =
    "usage: bench_volume [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F] [--modes dvr,iso,mixed] [--sampling S,...]\n"
    "         [--quantity fraction|height] [--convergence] [--check] [--csv FILE]\n"
    "         [--gl [--platform auto|nvidia|device|surfaceless]]\n"
    "         [--tolerances E,... [--relax R]] [--opacity A] [--no-tile-culling]\n"
    "         [--lod L,...]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  if (const char* v = arg.value("--modes")) return tools::read_names(v, kVolumeModeNames, a.modes);
  if (const char* v = arg.value("--sampling")) {
    a.samplings.clear();
    for (const std::string& s : tools::comma_list(v)) a.samplings.push_back(std::atof(s.c_str()));
    return !a.samplings.empty() &&
           std::all_of(a.samplings.begin(), a.samplings.end(), [](double s) { return s > 0; });
  }
  if (const char* v = arg.value("--tolerances")) {
    for (const std::string& e : tools::comma_list(v)) a.tolerances.push_back(std::atof(e.c_str()));
    return std::all_of(a.tolerances.begin(), a.tolerances.end(),
                       [](double e) { return e > 0 && e <= 1; });
  }
  if (const char* v = arg.value("--lod")) {
    for (const std::string& l : tools::comma_list(v)) a.levels.push_back(std::atof(l.c_str()));
    return std::all_of(a.levels.begin(), a.levels.end(), [](double l) { return l > 0; });
  }
  if (const char* v = arg.value("--opacity")) {
    a.opacity = std::atof(v);
    return a.opacity >= 0 && a.opacity <= 1;
  }
  if (const char* v = arg.value("--relax")) {
    a.relax = std::atof(v);
    return a.relax >= 0 && a.relax <= 1;
  }
  if (const char* v = arg.value("--quantity")) {
    a.height_field = std::string(v) == "height";
    return a.height_field || std::string(v) == "fraction";
  }
  return tools::read_state_flag(arg, a) || arg.value("--csv", a.csv) ||
         arg.flag("--convergence", a.convergence) || arg.flag("--gl", a.gl) ||
         arg.flag("--check", a.check) || arg.flag("--no-tile-culling", a.no_tile_culling) ||
         tools::read_bench_flag(arg, a);
}

bool parse(int argc, char** argv, Args& a) { return tools::read_args(argc, argv, a, read_flag); }

// The largest and the 99th-percentile channel error of `a` against `b`.
std::array<double, 2> errors(const FloatImage& a, const FloatImage& b) {
  std::vector<double> e(a.rgba.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = std::abs(double(a.rgba[i]) - b.rgba[i]);
  std::sort(e.begin(), e.end());
  return {e.empty() ? 0 : e.back(), e.empty() ? 0 : e[e.size() * 99 / 100]};
}

// Of the 8x8-pixel bundles where the fluid reaches half opacity somewhere, the share whose
// full-rate picture varies by at most `spread` in every channel. With relax 0 a cell may take one
// value for its bundle (a super-pixel) only where its own light varies by at most twice the
// tolerance, so in the rays' first cells this bounds what the guarantee can skip.
double flat_bundles(const VolumeFrame& f, double spread) {
  const FloatImage& p = f.picture;
  int fluid = 0, flat = 0;
  for (int y0 = 0; y0 < p.height; y0 += 8)
    for (int x0 = 0; x0 < p.width; x0 += 8) {
      std::array<float, 3> lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
      bool any = false;
      for (int y = y0; y < std::min(y0 + 8, p.height); ++y)
        for (int x = x0; x < std::min(x0 + 8, p.width); ++x) {
          const std::size_t i = std::size_t(x) + std::size_t(y) * std::size_t(p.width);
          any = any || f.depth[i] > 0;
          for (std::size_t c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], p.rgba[4 * i + c]);
            hi[c] = std::max(hi[c], p.rgba[4 * i + c]);
          }
        }
      if (!any) continue;
      ++fluid;
      flat += hi[0] - lo[0] <= spread && hi[1] - lo[1] <= spread && hi[2] - lo[2] <= spread;
    }
  return fluid == 0 ? 0 : 100.0 * flat / fluid;
}

// Two frames timed in turn, frame by frame, after one warm-up pair: the second's median
// milliseconds and the median of the pairs' ratios (its speed-up over the first; the machine's
// load drifts between rows).
struct Paired {
  double ms = 0, speed_up = 0;
};
template <class Base, class Variant>
Paired paired_frames(int frames, Base&& base, Variant&& variant) {
  std::vector<double> ms, ratios;
  for (int f = -1; f < frames; ++f) {
    const Stopwatch base_watch;
    base();
    const double base_ms = base_watch.ms();
    const Stopwatch watch;
    variant();
    if (f < 0) continue;  // the warm-up
    ms.push_back(watch.ms());
    ratios.push_back(base_ms / ms.back());
  }
  return {tools::median(ms), tools::median(ratios)};
}

// Per tolerance: adaptive sampling's frame against the full-rate one (`exact`), paired.
void adaptive_rows(const Args& a, const Camera& camera,
                   const std::vector<VolumeParticle>& particles, VolumeOptions o,
                   const VolumeFrame& exact, const VolumeFrame* converged, VolumeCaster& caster) {
  for (double tolerance : a.tolerances) {
    VolumeFrame frame, full_rate;
    VolumeCounts c;
    VolumeOptions exact_options = o;
    exact_options.adaptive = {};
    o.adaptive = {tolerance, a.relax};
    const Paired timed = paired_frames(
        a.frames, [&] { caster.run(camera, particles, exact_options, full_rate); },
        [&] { c = caster.run(camera, particles, o, frame); });
    std::size_t over = 0;
    double largest = 0;
    for (std::size_t i = 0; i < frame.picture.rgba.size(); ++i) {
      const double d = std::abs(double(frame.picture.rgba[i]) - exact.picture.rgba[i]);
      largest = std::max(largest, d);
      over += d > tolerance + 1e-6 ? 1 : 0;
    }
    std::printf(
        "  tolerance %-6g relax %g: %8.1f ms, speed-up %5.2f (paired) | vs full rate: largest "
        "%.2e, "
        "%.4f %% of channels past | skipped %5.1f %% of samples, %lld coarse and %lld "
        "super-pixel cells, %lld at the surface | fluid bundles flat within 2x: %.1f %%",
        tolerance, a.relax, timed.ms, timed.speed_up, largest,
        100.0 * double(over) / double(frame.picture.rgba.size()),
        100.0 * double(c.samples_skipped) / double(c.samples + c.samples_skipped),
        static_cast<long long>(c.cells_coarse), static_cast<long long>(c.cells_super_pixel),
        static_cast<long long>(c.cells_surface), flat_bundles(exact, 2 * tolerance));
    if (converged != nullptr) {
      const std::array<double, 2> e = errors(frame.picture, converged->picture);
      std::printf(" | vs converged: max %.2e p99 %.2e", e[0], e[1]);
    }
    std::printf("\n");
  }
}

// The frame of `o` at twice the width and height, each 2x2 block of pixels averaged: what a
// pixel's area shows rather than its centre, which particles under a pixel alias.
FloatImage supersampled(const Camera& camera, const std::vector<VolumeParticle>& particles,
                        const VolumeOptions& o, VolumeCaster& caster) {
  Camera fine = camera;
  fine.width *= 2;
  fine.height *= 2;
  VolumeFrame f;
  caster.run(fine, particles, o, f);
  FloatImage out(camera.width, camera.height);
  const auto at = [&](int x, int y) {
    return glm::make_vec4(
        &f.picture.rgba[4 * (std::size_t(x) + std::size_t(y) * std::size_t(fine.width))]);
  };
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      out.set(x, y,
              0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                       at(2 * x + 1, 2 * y + 1)));
  return out;
}

// Per level (VolumeOptions::level_of_detail, [FAW10] Fig. 8): the frame of the merged particles
// against the one of all of them (`all`), paired: the particles drawn, its time (and its project
// phase's, the merging included), and its largest and 99th-percentile channel error against
// `all`, against all of them 2x2 supersampled (`all`'s own error there first) and against the
// converged integral.
void lod_rows(const Args& a, const Camera& camera, const std::vector<VolumeParticle>& particles,
              VolumeOptions o, const VolumeFrame& all, const VolumeFrame* converged,
              VolumeCaster& caster) {
  if (a.levels.empty()) return;
  const FloatImage fine = supersampled(camera, particles, o, caster);
  const std::array<double, 2> e_all = errors(all.picture, fine);
  std::printf("  every particle vs 2x2 supersampled: max %.2e p99 %.2e\n", e_all[0], e_all[1]);
  const VolumeOptions all_options = o;
  for (double level : a.levels) {
    VolumeFrame frame, every;
    VolumeCounts c;
    o.level_of_detail = level;
    std::vector<double> project_ms;
    const Paired timed = paired_frames(
        a.frames, [&] { caster.run(camera, particles, all_options, every); },
        [&] {
          std::array<double, kVolumeCastPhaseNames.size()> phase{};
          c = caster.run(camera, particles, o, frame, &phase);
          project_ms.push_back(phase[std::size_t(VolumeCastPhase::project)]);
        });
    const std::array<double, 2> e = errors(frame.picture, all.picture);
    std::printf(
        "  level of detail %-4g: %9lld particles drawn (%lld merged into %lld) | %8.1f ms "
        "(project %.1f), speed-up %5.2f (paired) | vs all: max %.2e p99 %.2e",
        level, static_cast<long long>(c.particles - c.particles_merged + c.particles_coarse),
        static_cast<long long>(c.particles_merged), static_cast<long long>(c.particles_coarse),
        timed.ms, tools::median(project_ms), timed.speed_up, e[0], e[1]);
    const std::array<double, 2> e_fine = errors(frame.picture, fine);
    std::printf(" | vs 2x2 supersampled: max %.2e p99 %.2e", e_fine[0], e_fine[1]);
    if (converged != nullptr) {
      const std::array<double, 2> ec = errors(frame.picture, converged->picture);
      std::printf(" | vs converged: max %.2e p99 %.2e", ec[0], ec[1]);
    }
    std::printf("\n");
  }
}

int run(const Args& a) {
  tools::DamBreakState s = tools::dam_break_state(a, a);
  s.camera.width = a.width;
  s.camera.height = a.height;
  const std::vector<VolumeParticle> particles = tools::dam_break_particles(s, a.height_field);
  std::printf("scene: %s; %dx%d, %zu particles, field %s\n", s.description.c_str(), a.width,
              a.height, particles.size(), a.height_field ? "height (Shepard)" : "volume fraction");
  std::printf("%-5s %8s | %8s %8s %8s %8s %8s | %10s %12s %9s %9s %15s", "mode", "sampling",
              "project", "sort", "bin", "march", "total", "samples", "evaluations", "stopped",
              "iso hits", "culled");
  if (a.convergence) std::printf(" | %9s %9s %5s", "max err", "p99 err", "dbl");
  if (a.check) std::printf(" | %9s", "vs ref");
  if (a.gl) std::printf(" | %8s %9s", "GL ms", "GL vs CPU");
  std::printf("\n");
  std::FILE* csv = a.csv.empty() ? nullptr : std::fopen(a.csv.c_str(), "w");
  if (!a.csv.empty() && csv == nullptr) throw make_error("cannot write ", a.csv);
  if (csv != nullptr)
    std::fprintf(csv, "scene,particles,width,height,mode,sampling,ms,samples,max_err,p99_err\n");
  VolumeCaster caster;
  caster.set_tile_culling(!a.no_tile_culling);
  std::optional<gl::Context> context;
  std::optional<gl::ShaderLibrary> shaders;
  std::unique_ptr<VolumeRenderer> gl_renderer;
  if (a.gl) {
    context.emplace(a.context);
    tools::print_renderer(*context);
    shaders.emplace();
    gl_renderer = make_gl_volume_renderer(*shaders);
  }
  for (VolumeMode mode : a.modes) {
    // The converged integral, once per mode: the sampling doubled from 1 until the picture
    // changes under 1e-4 (or 8 doublings).
    VolumeFrame converged;
    int doublings = 0;
    if (a.convergence) {
      VolumeOptions exact =
          tools::dam_break_volume_options(s, particles, a.height_field, a.opacity, mode, 1);
      exact.termination = 0;
      converged = converged_volume(s.camera, particles, exact, 1e-4, 8, &doublings);
    }
    for (double sampling : a.samplings) {
      const VolumeOptions o =
          tools::dam_break_volume_options(s, particles, a.height_field, a.opacity, mode, sampling);
      std::array<std::vector<double>, kVolumeCastPhaseNames.size() + 1> ms;
      VolumeFrame frame;
      VolumeCounts counts;
      for (int f = -1; f < a.frames; ++f) {
        std::array<double, kVolumeCastPhaseNames.size()> phase{};
        const Stopwatch watch;
        counts = caster.run(s.camera, particles, o, frame, &phase);
        const double total = watch.ms();
        if (f < 0) continue;  // the warm-up
        for (std::size_t p = 0; p < phase.size(); ++p) ms[p].push_back(phase[p]);
        ms.back().push_back(total);
      }
      std::printf("%-5s %8g |", name_of(kVolumeModeNames, mode).data(), sampling);
      for (const std::vector<double>& m : ms) std::printf(" %8.1f", tools::median(m));
      std::printf(
          " | %10lld %12lld %9lld %9lld %5lld/%9lld", static_cast<long long>(counts.samples),
          static_cast<long long>(counts.kernel_evaluations),
          static_cast<long long>(counts.rays_stopped), static_cast<long long>(counts.iso_hits),
          static_cast<long long>(counts.tiles_culled),
          static_cast<long long>(counts.supports_culled));
      std::array<double, 2> e{0, 0};
      if (a.convergence) {
        e = errors(frame.picture, converged.picture);
        std::printf(" | %9.2e %9.2e %5d", e[0], e[1], doublings);
      }
      if (a.check) {
        VolumeFrame reference;
        volume_reference(s.camera, particles, o, reference);
        std::printf(" | %9.2e", errors(frame.picture, reference.picture)[0]);
      }
      if (gl_renderer) {
        std::vector<double> gl_ms;
        VolumeFrame on_gl;
        Recorder recorder;
        std::int64_t on_cpu = 0;
        for (int f = -1; f < a.frames; ++f) {
          const Stopwatch watch;
          on_cpu += gl_renderer->render(s.camera, particles, o, recorder, on_gl).gl_frames_on_cpu;
          if (f >= 0) gl_ms.push_back(watch.ms());
        }
        // A frame past a software renderer's loop budget is the CPU caster's (docs/design.md).
        std::printf(" | %8.1f %9.2e%s", tools::median(gl_ms),
                    errors(on_gl.picture, frame.picture)[0], on_cpu > 0 ? " on CPU" : "");
      }
      std::printf("\n");
      if (mode == VolumeMode::dvr)
        adaptive_rows(a, s.camera, particles, o, frame, a.convergence ? &converged : nullptr,
                      caster);
      lod_rows(a, s.camera, particles, o, frame, a.convergence ? &converged : nullptr, caster);
      if (csv != nullptr)
        std::fprintf(csv, "%s,%zu,%d,%d,%s,%g,%.2f,%lld,%.4g,%.4g\n",
                     a.ritter ? "ritter" : "solver", particles.size(), a.width, a.height,
                     name_of(kVolumeModeNames, mode).data(), sampling, tools::median(ms.back()),
                     static_cast<long long>(counts.samples), e[0], e[1]);
    }
  }
  if (csv != nullptr) std::fclose(csv);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_volume", argc, argv, kUsage, parse, run);
}
