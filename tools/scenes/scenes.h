// Scenes for the voxelization's tests and benchmarks, made of particle spheres (x, y, z,
// radius): one sphere, lattice blocks, a dam break (the shape of a collapsing water column at a
// given time, filled at the solver's lattice density), stacked thin layers and a 3D
// checkerboard ([ZD15] sec. 5.4), random clouds with mixed radii. Made up, not simulated:
// the dam-break shape follows Ritter's shallow-water solution, not the solver.
#pragma once

#include <cstdint>
#include <vector>

#include "render/camera.h"
#include "voxspan/cell_states.h"

namespace voxspan::test {

using Particles = std::vector<ParticleSphere>;

Particles one_sphere(glm::dvec3 center, double radius);

// n.x * n.y * n.z spheres at lo + (i + 0.5) * spacing.
Particles lattice_block(glm::dvec3 lo, glm::ivec3 n, double spacing, double radius);

// A water column of width x height x depth, released at t = 0 into a tank along +x, at time t
// (seconds, g = 9.81). Lattice spacing `spacing`, render radius `radius`; lattice points at
// (i + 0.5) * spacing from the origin, the tank floor at y = 0 and its back wall at x = 0.
struct DamBreak {
  double width = 0.3, height = 0.6, depth = 0.3;
  double tank_length = 1.2;
  double spacing = 0.01;
  double radius = 0.01;
  // Droplets thrown ahead of the front once it moves: a fraction of the particle count.
  double spray_fraction = 0.002;
};
Particles dam_break(const DamBreak& shape, double t, std::uint32_t seed = 1);
// Spacing that gives about `particles` particles in the initial column.
double dam_break_spacing(const DamBreak& shape, double particles);

// `layers` sheets of side x side x thickness lattice spheres, stacked along z from z = 0 with
// `pitch` between the sheets' first planes: more layers than a span cap holds.
Particles stacked_layers(int layers, int side, int thickness, double spacing, double radius,
                         double pitch);

// A cube of cells^3 blocks, each block^3 lattice spheres, alternate blocks filled.
Particles checkerboard(int cells, int block, double spacing, double radius);

// n spheres uniformly in [lo, hi], radii uniform in [r0, r1].
Particles random_cloud(std::size_t n, glm::dvec3 lo, glm::dvec3 hi, double r0, double r1,
                       std::uint32_t seed);

// A camera at `eye` looking at `target`, y up.
Camera look_at(glm::dvec3 eye, glm::dvec3 target, int width, int height, double fov_y_degrees = 45);

// A camera looking at the particles' bounding box centre from `direction` (towards the
// scene), at the distance that frames the box with a margin.
Camera frame_scene(const Particles& particles, glm::dvec3 direction, int width, int height,
                   double fov_y_degrees = 45, double margin = 1.1);

}  // namespace voxspan::test
