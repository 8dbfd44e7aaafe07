// insitu/io/spacing_estimate.h - the particle spacing of a particle file that does not say it:
// the median distance to the nearest neighbour over an even sample of the particles (a rest
// lattice gives its spacing exactly; a disordered SPH fluid about 0.9 of it). The offline
// renderer uses it for the classification's full count, the sphere radius and the gap.
// Cost: a hash-grid pass over all positions and a 27-cell search per sampled particle.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace voxspan {

// 0 when fewer than two distinct finite positions exist.
double estimate_particle_spacing(std::span<const std::array<double, 3>> positions,
                                 std::size_t samples = 4096);

// The spacing of particles whose volumes (mass over density) a file gives: the median of
// volume^(1 / dims) over the positive ones (dims 2 for a flat run, whose masses are an area's);
// nullopt where none is.
std::optional<double> spacing_from_volumes(std::vector<double> volumes, int dims);

}  // namespace voxspan
