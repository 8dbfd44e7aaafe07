// render/volume.h - volume rendering and iso-surfaces of an SPH field ([FAW10], [HOK16]): what
// both renderers and the reference take and give, and the one sample lattice they share.
//
// The field at a point x is the SPH sum over the particles whose support holds it ([HOK16]
// Eq. 1-2):
//   S(x) = sum_j V_j q_j W(|x - x_j|, h_j),   w(x) = sum_j V_j W(|x - x_j|, h_j)
//   Q(x) = S / w (Shepard, [HOK16]'s CSPH), or S (a plain sum; with q = 1 the volume fraction w)
// in double on the CPU. Samples lie on every pixel's ray at the depths of one lattice,
// d_i = anchor (1 + K)^i with K = 2 tan(fov_y / 2) / height / sampling: at sampling 1 the
// spacing along the ray equals the spacing across ([FAW10] sec. 3's s_z). The anchor is the
// particle spacing, so that the samples stay put from step to step (no shimmering) and scale
// with the scene (the same picture at any scale). A sample no particle's support reaches is
// empty; with Shepard one whose weight is under `weight_floor` too (the free surface, where
// w -> 0 makes S / w noise).
//
// The samples are composited front to back (render/model/volume.glsl, shared by every
// renderer): direct volume rendering through a transfer function (colour and opacity per value;
// an opacity holds for one `opacity_length` of fluid, corrected to each sample's length), iso
// crossings between neighbouring samples (placed by linear interpolation, lit with the field's
// gradient there), or both; a ray stops when its transmittance falls under `termination`.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "render/backdrop.h"
#include "render/enum_names.h"
#include "render/float_image.h"
#include "render/shade_options.h"
#include "render/sph_kernel.h"

namespace voxspan {

enum class VolumeMode : std::uint8_t { dvr, iso, mixed };
inline constexpr EnumName<VolumeMode> kVolumeModeNames[] = {
    {"dvr", VolumeMode::dvr}, {"iso", VolumeMode::iso}, {"mixed", VolumeMode::mixed}};

// One particle as the volume renderers read it (std430: 6 floats): its smoothing length h, its
// weight m / (rho h^3) (its volume, m / rho or the rest volume, in units of h^3: dimensionless,
// so that the same scene at any scale gives the same floats) and its value q (a vector's
// magnitude; 1 for the volume fraction). V W(r, h) = weight * (h^3 W(r, h)).
struct VolumeParticle {
  float x, y, z;
  float h;
  float weight;
  float value;
};
static_assert(sizeof(VolumeParticle) == 24);

// Whether the renderers draw a particle: finite, h and weight > 0 (the others are counted as
// invalid and skipped).
inline bool drawable(const VolumeParticle& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.h) &&
         std::isfinite(p.weight) && std::isfinite(p.value) && p.h > 0 && p.weight > 0;
}

// The transfer function as a table: kTransferEntries linear RGB + opacity entries evenly over
// [lo, hi], looked up with linear interpolation, clamped at the ends.
inline constexpr int kTransferEntries = 256;
struct TransferTable {
  double lo = 0, hi = 1;
  // Whether the table spans log(q) from log(lo) to log(hi) (lo > 0), a value at or under 0
  // taking its first entry; else q from lo to hi.
  bool log = false;
  std::array<glm::vec4, kTransferEntries> rgba{};
  // Where the compositing (volume.glsl's vx_transfer, in float) finds q in the table:
  // (v - lo) * scale with v = q, or log2 q on a log scale; lo and scale as it has them.
  struct Place {
    float lo, scale;
  };
  Place place() const;
};

inline constexpr int kMaxIsoSurfaces = 4;
struct IsoSurface {
  double value = 0.5;
  glm::dvec3 color{0.85, 0.85, 0.9};  // linear RGB
  double opacity = 1;
  bool operator==(const IsoSurface&) const = default;
};

// Adaptive sampling under an error tolerance ([HOK16] sec. 4-5; render/cpu/volume_adaptive.h):
// error_tolerance 0 samples every ray at the lattice's full rate. Above 0, in DVR with Shepard,
// cells of rays sample more sparsely, or not at all (one light and transmittance for the whole
// cell), where interval bounds of the field prove that no channel of any pixel moves by more
// than error_tolerance from the full-rate picture. relax in (0, 1] subtracts that share of each
// cell's full-rate bound width from its coarser ones ([HOK16]'s E_relax, sec. 5.1): faster, no
// longer a guarantee.
struct AdaptiveOptions {
  double error_tolerance = 0;  // in [0, 1]: largest change of a pixel's channel
  double relax = 0;            // in [0, 1]
  // In (0, 1]: the share of the tolerance one rank's cells may spend when several ranks each
  // march their own particles and their segments are composited (insitu/views/
  // volume_compositor.cpp gives each 1 / ranks; render/cpu/volume_adaptive.h says why that holds).
  double share = 1;
  // [HOK16] Table 2's variants, for benchmarks (tools/bench/bench_adaptive.cpp): each part of the
  // plan may be left out. Without `greedy` each cell takes the cheapest choice whose own term
  // fits the tolerance, not the bundle's sum of terms (their "No greedy alg.": no bound left);
  // without `surface_rule` the cells at the free surface are planned as the others (their "No
  // surface"; the bounds still hold the pixels where such a cell is empty); `super_pixels` and
  // `coarse` (sparser samples along the rays) each allow one kind of choice (their "Only
  // z-Adapt": no super-pixels).
  struct Rules {
    bool greedy = true, surface_rule = true, super_pixels = true, coarse = true;
    bool operator==(const Rules&) const = default;
  };
  Rules rules{};
  bool operator==(const AdaptiveOptions&) const = default;
};

struct VolumeOptions {
  VolumeMode mode = VolumeMode::dvr;
  SphKernel kernel = SphKernel::cubic_spline;
  bool shepard = true;
  double weight_floor = 0.05;  // Shepard: w under this is empty (w is about 1 inside the fluid)
  TransferTable transfer;
  double opacity_length = 1;     // world units over which a table opacity holds (> 0)
  std::vector<IsoSurface> isos;  // up to kMaxIsoSurfaces, mode iso or mixed
  double sampling = 1;           // samples per pixel spacing along the ray (> 0)
  double anchor = 1;             // the lattice's depth 1 (world units, > 0): the particle spacing
  double termination = 1e-3;     // a ray stops when its transmittance falls under this
  // Behind the fluid: the surface views' environment (sky and ground), or nothing (transparent:
  // alpha = 1 - transmittance, for compositing elsewhere). Its sun lights the iso surfaces.
  bool background = true;
  Environment environment;
  double ambient = 0.3;  // iso surfaces' light from everywhere
  AdaptiveOptions adaptive;
  // Particle level of detail ([FAW10] sec. 4.1; render/cpu/volume_lod.h): 0 draws every
  // particle; above 0, those whose h is under this many pixel spacings at their depth are
  // merged, per world grid cell, into coarser particles at least that large. The adaptive
  // sampling and a rank's part march the merged particles as they would the given ones.
  double level_of_detail = 0;
  // The solver's walls (render/backdrop.h; null: none), the frame's size: each ray ends at its
  // pixel's walls (no sample behind them), and their colour (or the environment's, where none
  // stands) lies behind the fluid instead of the environment. Not owned.
  const Backdrop* backdrop = nullptr;
};

// Throws voxspan::Error naming the option that is out of range.
void validate(const VolumeOptions& options);

// The sample lattice: d_i = anchor (1 + k)^i, i over the integers.
struct VolumeLattice {
  double anchor = 1;
  double k = 0.01;
  double log_step = std::log1p(0.01);  // ln(1 + k)

  double half_extent = 0.01;  // ((1 + k) - 1 / (1 + k)) / 2

  VolumeLattice() = default;
  VolumeLattice(double anchor_depth, double k_step)
      : anchor(anchor_depth),
        k(k_step),
        log_step(std::log1p(k_step)),
        half_extent(0.5 * (k_step + 1 - 1 / (1 + k_step))) {}
  double depth(std::int64_t i) const { return anchor * std::exp(double(i) * log_step); }
  // The depth a sample at `depth` stands for: from the middle to the sample before to the
  // middle to the one after ((d_{i+1} - d_{i-1}) / 2: second-order accurate on the geometric
  // spacing, where d_{i+1} - d_i alone errs by k / 2 of the integral).
  double extent(double depth) const { return depth * half_extent; }
  // The first index whose depth is >= d (d > 0).
  std::int64_t first_at_or_after(double d) const {
    std::int64_t i = std::int64_t(std::ceil(std::log(d / anchor) / log_step));
    while (depth(i - 1) >= d) --i;  // rounding of the logarithm, either way
    while (depth(i) < d) ++i;
    return i;
  }
  // The last index whose depth is <= d (d > 0).
  std::int64_t last_at_or_before(double d) const {
    const std::int64_t i = first_at_or_after(d);
    return depth(i) > d ? i - 1 : i;
  }
};

// The lattice of a view: K = 2 tan(fov_y / 2) / height / sampling.
VolumeLattice volume_lattice(double tan_half_y, int height, const VolumeOptions& options);

// The sums at one point and their gradients, for the light of an iso hit.
struct FieldSums {
  double s = 0, w = 0;
  glm::dvec3 grad_s{0}, grad_w{0};
};
inline FieldSums& operator+=(FieldSums& a, const FieldSums& b) {
  a.s += b.s;
  a.w += b.w;
  a.grad_s += b.grad_s;
  a.grad_w += b.grad_w;
  return a;
}
// The field's gradient there: of S / w with Shepard (where w > 0), else of S.
inline glm::dvec3 field_gradient(const FieldSums& f, bool shepard) {
  if (!shepard || !(f.w > 0)) return f.grad_s;
  return (f.grad_s * f.w - f.s * f.grad_w) / (f.w * f.w);
}

// A deep image of a volume frame, for compositors: per pixel the runs of samples along its ray
// that some particle reaches, front to back, each one deep sample: Z and ZBack the distances
// from the eye along the unit ray where the run starts and ends, RGBA its light composited
// from transmittance 1 (premultiplied) and alpha = 1 - its transmittance. Composited over one
// another in order (OpenEXR's deep flattening), the samples give the picture without its
// background.
struct DeepSample {
  float z = 0, z_back = 0;
  glm::vec4 rgba{0.0f};
};
struct DeepImage {
  int width = 0, height = 0;
  std::vector<std::uint32_t> start;  // per pixel (x + y * width) + 1: its first sample
  std::vector<DeepSample> samples;
  std::span<const DeepSample> of(std::size_t pixel) const {
    return {samples.data() + start[pixel], samples.data() + start[pixel + 1]};
  }
};

struct VolumeFrame {
  // Linear RGBA, row 0 at the top: over the background (alpha 1), or with no background the
  // light premultiplied and alpha = 1 - transmittance.
  FloatImage picture;
  // Per pixel, the distance along the ray to the first iso hit or, failing one, to the sample
  // where the opacity reached 0.5; 0 where neither happened.
  std::vector<float> depth;
  // When asked for (VolumeRenderer::render's `deep`): the deep image; else empty.
  DeepImage deep;

  // Sized for a camera's picture, depths 0, the picture's storage kept when its size is.
  void reset(int width, int height) {
    if (picture.width != width || picture.height != height) picture = FloatImage(width, height);
    depth.assign(std::size_t(width) * std::size_t(height), 0.0f);
  }
};

// Counts of one frame.
struct VolumeCounts {
  std::int64_t particles = 0;          // given
  std::int64_t particles_invalid = 0;  // NaN or infinite position, value or weight; h, weight <= 0
  std::int64_t particles_culled = 0;   // support wholly outside the view or behind the eye
  // Level of detail (VolumeOptions::level_of_detail): given particles merged into coarser ones,
  // and those coarser ones. The frame draws particles - particles_merged + particles_coarse
  // (the invalid and culled counted among those).
  std::int64_t particles_merged = 0;
  std::int64_t particles_coarse = 0;
  std::int64_t samples = 0;  // composited (non-empty)
  std::int64_t kernel_evaluations = 0;
  std::int64_t rays_stopped = 0;  // transmittance under `termination` before the last sample
  std::int64_t iso_hits = 0;
  std::int64_t iso_hits_unlit = 0;  // past kMaxIsoHits on their ray: ambient light only
  // GL renderer on llvmpipe: frames drawn by the CPU caster because a bundle's march ran past
  // the loop iterations llvmpipe allows an invocation
  std::int64_t gl_frames_on_cpu = 0;
  // Adaptive sampling (VolumeOptions::adaptive): samples a full-rate march would composite that
  // this one skipped, and cells (a ray bundle by a run of samples) sampled sparsely, drawn as
  // one super-pixel, or held at full rate for lying at the free surface.
  std::int64_t samples_skipped = 0;
  std::int64_t cells_coarse = 0;
  std::int64_t cells_super_pixel = 0;
  std::int64_t cells_surface = 0;
  // Occlusion culling ([FAW10] sec. 5.2; CPU caster): screen tiles whose rays all stopped
  // before their last supports; supports not walked, behind those tiles or behind bundles of
  // rays that all stopped.
  std::int64_t tiles_culled = 0;
  std::int64_t supports_culled = 0;
  // Adaptive sampling's own bound: with relax 0, the most its plans let any channel of any pixel
  // move from the full-rate picture, besides the reserve for rounding and early stops (the
  // largest over the bundles of the terms spent; of a rank's own cells in an MPI job, where the
  // ranks' bounds add up). Not a count: frames' parts take the largest.
  double error_bound = 0;
  // Adaptive sampling's planning (the bounds and the choices; [HOK16] Table 2's "Adapt"), in
  // milliseconds summed over the threads: part of the march's time.
  double planning_ms = 0;
};

// Each count with the name a stats record gives it.
struct VolumeCountName {
  std::string_view name;
  std::int64_t VolumeCounts::*member;
};
inline constexpr VolumeCountName kVolumeCountNames[] = {
    {"volume.particles", &VolumeCounts::particles},
    {"volume.particles_invalid", &VolumeCounts::particles_invalid},
    {"volume.particles_culled", &VolumeCounts::particles_culled},
    {"volume.particles_merged", &VolumeCounts::particles_merged},
    {"volume.particles_coarse", &VolumeCounts::particles_coarse},
    {"volume.samples", &VolumeCounts::samples},
    {"volume.kernel_evaluations", &VolumeCounts::kernel_evaluations},
    {"volume.rays_stopped", &VolumeCounts::rays_stopped},
    {"volume.iso_hits", &VolumeCounts::iso_hits},
    {"volume.iso_hits_unlit", &VolumeCounts::iso_hits_unlit},
    {"volume.gl_frames_on_cpu", &VolumeCounts::gl_frames_on_cpu},
    {"volume.samples_skipped", &VolumeCounts::samples_skipped},
    {"volume.cells_coarse", &VolumeCounts::cells_coarse},
    {"volume.cells_super_pixel", &VolumeCounts::cells_super_pixel},
    {"volume.cells_surface", &VolumeCounts::cells_surface},
    {"volume.tiles_culled", &VolumeCounts::tiles_culled},
    {"volume.supports_culled", &VolumeCounts::supports_culled}};

inline VolumeCounts& operator+=(VolumeCounts& a, const VolumeCounts& b) {
  for (const VolumeCountName& c : kVolumeCountNames) a.*c.member += b.*c.member;
  a.error_bound = std::max(a.error_bound, b.error_bound);
  a.planning_ms += b.planning_ms;
  return a;
}

}  // namespace voxspan
