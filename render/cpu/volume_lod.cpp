#include "render/cpu/volume_lod.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace voxspan {
namespace {

// A cell's key: the exponent of its size (biased) in the top 10 bits, then its index along x, y
// and z from the scene's first cell of that size, 18 bits each.
constexpr int kAxisBits = 18;
constexpr int kExponentBias = 512;
constexpr std::uint64_t kKept = ~std::uint64_t(0);

// The smallest corner of the drawable particles' positions.
glm::dvec3 lowest_corner(std::span<const VolumeParticle> particles) {
  const glm::dvec3 none(std::numeric_limits<double>::infinity());
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, particles.size(), 16384), none,
      [&](const tbb::blocked_range<std::size_t>& range, glm::dvec3 lo) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          if (drawable(particles[i]))
            lo = glm::min(lo, glm::dvec3(particles[i].x, particles[i].y, particles[i].z));
        return lo;
      },
      [](glm::dvec3 a, glm::dvec3 b) { return glm::min(a, b); });
}

// The key of particle p's cell, or kKept where it is kept as it is.
std::uint64_t key_of(const ViewFrame& frame, const VolumeParticle& p, double spacing_at_1,
                     glm::dvec3 lowest) {
  if (!drawable(p)) return kKept;
  const glm::dvec3 x(p.x, p.y, p.z);
  const double needed = spacing_at_1 * frame.to_view(x).z;  // the smallest h drawn as it is
  if (!(needed > 0) || !(double(p.h) < needed)) return kKept;
  int exponent = 0;
  std::frexp(needed, &exponent);  // needed <= 2^exponent < 2 needed
  const double size = std::ldexp(1.0, exponent);
  const glm::dvec3 i = glm::floor(x / size) - glm::floor(lowest / size);
  const double axis_cells = double(1 << kAxisBits);
  if (!(i.x < axis_cells && i.y < axis_cells && i.z < axis_cells) || exponent + kExponentBias < 0 ||
      exponent + kExponentBias >= 1 << (64 - 3 * kAxisBits))
    return kKept;
  return std::uint64_t(exponent + kExponentBias) << (3 * kAxisBits) |
         std::uint64_t(i.x) << (2 * kAxisBits) | std::uint64_t(i.y) << kAxisBits |
         std::uint64_t(i.z);
}

double cell_size(std::uint64_t key) {
  return std::ldexp(1.0, int(key >> (3 * kAxisBits)) - kExponentBias);
}

// One coarser particle of `run`'s particles (one cell, in input order).
VolumeParticle merged(std::span<const VolumeLod::Cell> run,
                      std::span<const VolumeParticle> particles) {
  double v = 0, vq = 0, h_max = 0;
  glm::dvec3 vx(0);
  for (const VolumeLod::Cell& c : run) {
    const VolumeParticle& p = particles[c.index];
    const double h = p.h, vj = double(p.weight) * h * h * h;
    v += vj;
    vq += vj * double(p.value);
    vx += vj * glm::dvec3(p.x, p.y, p.z);
    h_max = std::max(h_max, h);
  }
  const double h = std::max(cell_size(run.front().key), h_max);
  const glm::dvec3 x = vx / v;
  return {float(x.x), float(x.y), float(x.z), float(h), float(v / (h * h * h)), float(vq / v)};
}

}  // namespace

std::span<const VolumeParticle> VolumeLod::run(const ViewFrame& frame,
                                               std::span<const VolumeParticle> particles,
                                               double level, LodCounts& counts) {
  // Rows of pixels are 2 tan(fov_y / 2) / height apart at depth 1.
  const double spacing_at_1 = level * 2 * frame.tan_half_y / frame.height;
  const glm::dvec3 lowest = lowest_corner(particles);
  cells_.resize(particles.size());
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, particles.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
          cells_[i] = {key_of(frame, particles[i], spacing_at_1, lowest), std::uint32_t(i)};
      });
  counts = {};
  if (std::none_of(cells_.begin(), cells_.end(), [](const Cell& c) { return c.key != kKept; }))
    return particles;
  drawn_.clear();
  std::size_t merging = 0;
  for (const Cell& c : cells_) {
    if (c.key == kKept) drawn_.push_back(particles[c.index]);
    else cells_[merging++] = c;
  }
  cells_.resize(merging);
  tbb::parallel_sort(cells_.begin(), cells_.end(), [](const Cell& a, const Cell& b) {
    return a.key < b.key || (a.key == b.key && a.index < b.index);
  });
  counts.merged = std::int64_t(merging);
  for (std::size_t b = 0; b < cells_.size();) {
    std::size_t e = b + 1;
    while (e < cells_.size() && cells_[e].key == cells_[b].key) ++e;
    drawn_.push_back(merged(std::span(cells_).subspan(b, e - b), particles));
    ++counts.coarse;
    b = e;
  }
  return drawn_;
}

}  // namespace voxspan
