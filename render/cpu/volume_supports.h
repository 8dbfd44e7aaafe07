// render/cpu/volume_supports.h - the CPU volume caster's particles as supports in view space
// (render/cpu/volume_caster.h's project, sort and bin phases, [FAW10] sec. 3) and what one
// support adds to a ray's samples and at an iso hit (the SPH sums of [FAW10] sec. 4).
//
// Reads VolumeParticles and the frame's view; writes per particle its Support (view-space
// centre, pixel rectangle, first and last samples), their order nearest first, and per screen
// tile the supports that touch it in that order. Cost: one parallel pass over the particles, a
// parallel sort of those in view, a counting sort into tiles (render/cpu/screen_bins.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/cpu/screen_bins.h"
#include "render/perspective_grid.h"
#include "render/sph_kernel.h"
#include "render/volume.h"

namespace voxspan::volume_cast {

// A particle's support in view space, as the march reads it.
struct Support {
  glm::dvec3 c;            // centre
  double radius = 0;       // R = kernel support * h
  double inv_h = 0;        // 1 / h
  double vq = 0, v = 0;    // weight q and weight: the kernel's shape times these is the sum
  std::int64_t first = 0;  // the first sample at or after its nearest depth (and the near clip)
  std::int64_t last = -1;  // the last sample at or before its farthest depth
  PixelRect rect;
};

// The frame's samples: depth(i) for i in [base, base + depth.size()).
struct Samples {
  VolumeLattice lattice;
  double near = 0;  // the near clip: no sample before it
  std::int64_t base = 0;
  std::vector<double> depths;
  double depth(std::int64_t i) const { return depths[std::size_t(i - base)]; }
};

// Project: each valid particle's support in view space (`support`: the kernel's support in
// units of h), culled where it meets no pixel centre or no sample; `counts` gets the invalid and
// the culled. `out` holds one entry per particle, an empty rectangle for those left out.
void project(const PerspectiveGrid& view_grid, const Samples& s,
             std::span<const VolumeParticle> particles, double support, VolumeCounts& counts,
             std::vector<Support>& out);

// Sort: the supports in view (a pixel rectangle), nearest first sample first, ties by input
// order, copied into `sorted` in that order: the march then reads each tile's in rising
// addresses (`keys`: scratch).
void sort_supports(const std::vector<Support>& supports, std::int64_t base,
                   std::vector<std::uint64_t>& keys, std::vector<Support>& sorted);

// Bin: per tile the positions of the sorted supports whose rectangles touch it, in order.
void bin_supports(const Tiles& screen, const std::vector<Support>& sorted, Bins& bins,
                  std::vector<std::uint32_t>& lists);

// The kernel of support s at the n samples of depths z[k] on the ray of |d|^2 = a whose depth
// nearest s's centre is zc, at distance^2 m2 from it (|z d - c|^2 = a (z - zc)^2 + m2, which
// keeps its precision at any distance), added to sum[k] (V q W) and weight[k] (V W). No branch:
// it vectorizes, with AVX2 where the processor has it (the same IEEE operations either way, so
// the same sums).
template <SphKernel K>
__attribute__((target_clones("avx2", "default"))) void add_kernel(
    const double* __restrict z, std::int64_t n, double zc, double a, double m2, const Support& s,
    double* __restrict sum, double* __restrict weight) {
  const double inv_h = s.inv_h, vq = s.vq, v = s.v;
  for (std::int64_t k = 0; k < n; ++k) {
    const double t = z[k] - zc;
    const double shape = kernel_shape<K>(std::sqrt(a * t * t + m2) * inv_h);
    sum[k] += vq * shape;
    weight[k] += v * shape;
  }
}

// Support s's part of the field's sums and their gradients at view point x (an iso hit's).
template <SphKernel K> void add_field_sums(glm::dvec3 x, const Support& s, FieldSums& a) {
  const glm::dvec3 d = x - s.c;
  const double dist = std::sqrt(glm::dot(d, d));
  const double q = dist * s.inv_h;
  const double shape = kernel_shape<K>(q);
  if (shape == 0 && q >= kernel_support(K)) return;
  const glm::dvec3 g = dist > 0 ? (kernel_slope<K>(q) * s.inv_h / dist) * d : glm::dvec3(0);
  a.s += s.vq * shape;
  a.w += s.v * shape;
  a.grad_s += s.vq * g;
  a.grad_w += s.v * g;
}

}  // namespace voxspan::volume_cast
