// insitu/views/sph_points.h - a particle quantity SPH-interpolated at any set of points (a
// surface view's first-hit points), with the terms and sums of insitu/views/sph_slice.h: per
// point x the sums of (m_j / rho_j) A_j W(|x - x_j|, h) and of (m_j / rho_j) W over the owned
// particles whose support reaches x, which ranks add up like the slice's.
// Costs: one pass over the owned particles in parallel (those in the cells some point reads
// are sorted into a uniform grid of cells of half the support), then per point the particles of
// the 5x5x5 cells around it; points in parallel (oneTBB). The grid holds at most kMaxCells
// cells: a sparse set of points over a large box gets larger cells (more particles a point, the
// same sums).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "insitu/views/sph_slice.h"

namespace voxspan {

struct SphPoints {
  static constexpr std::size_t kMaxCells = std::size_t(1) << 22;

  std::vector<double> sum, weight;  // per point; weight 0 where no particle reaches
  std::size_t particles_near = 0;   // owned particles in cells that some point reads

  // Working storage, kept from step to step.
  std::vector<SphTerm> near, sorted;
  std::vector<std::uint32_t> cell_start, cell_fill, cell_of;
  std::vector<std::uint8_t> cell_reached, cell_widened;
};

// Interpolates `q` at `points` into out.sum and out.weight, reusing out's storage. Throws
// voxspan::Error naming the attribute when the quantity is missing, or when h is not positive.
void interpolate_at_points(const ParticleView& particles, const SliceQuantity& q,
                           std::span<const glm::dvec3> points, SphPoints& out);

}  // namespace voxspan
