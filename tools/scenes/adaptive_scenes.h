// Scenes for adaptive volume sampling (render/cpu/volume_adaptive.h), on either renderer: Shepard
// particles of known values, their camera and their volume options; its tests' and
// tools/bench/bench_adaptive.cpp's.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/volume.h"
#include "tools/scenes/scenes.h"

namespace voxspan::test {

struct AdaptiveScene {
  std::string name;
  std::vector<VolumeParticle> particles;
  Camera camera;
  VolumeOptions options;
};

// Spheres as Shepard particles of h = 1.3 spacings whose value is value(centre).
inline std::vector<VolumeParticle> with_values(const Particles& spheres, double spacing,
                                               const std::function<double(glm::dvec3)>& value) {
  std::vector<VolumeParticle> out;
  for (const ParticleSphere& s : spheres)
    out.push_back({s.x, s.y, s.z, float(1.3 * spacing), float(1 / std::pow(1.3, 3)),
                   float(value(glm::dvec3(s.x, s.y, s.z)))});
  return out;
}

// DVR over the particle spacing, the transfer function tf(u) over values [lo, hi].
inline VolumeOptions adaptive_options(double spacing, double lo, double hi,
                                      const std::function<glm::vec4(float)>& tf) {
  VolumeOptions o;
  o.anchor = spacing;
  o.opacity_length = spacing;
  o.transfer.lo = lo;
  o.transfer.hi = hi;
  for (int k = 0; k < kTransferEntries; ++k)
    o.transfer.rgba[std::size_t(k)] = tf(float(k) / (kTransferEntries - 1));
  return o;
}

inline glm::vec4 smooth_tf(float u) { return {u, 0.6f - 0.4f * u, 1 - u, 0.03f + 0.15f * u}; }

// The synthetic scenes' block: `side`^3 particles at kCubeSpacing from the origin.
inline constexpr double kCubeSpacing = 0.05;
inline Particles cube_block(int side) {
  return lattice_block({0, 0, 0}, {side, side, side}, kCubeSpacing, kCubeSpacing);
}

// A radial concentration through a transfer function with a narrow opacity spike ([HOK16] Fig.
// 3: the cells where the spike lies stay fine, the rest need not), a cube of `side`^3 particles.
inline AdaptiveScene radial_scene(int width, int height, int side) {
  const double s = kCubeSpacing;
  const Particles block = cube_block(side);
  return {"radial, steep transfer function",
          with_values(block, s, [](glm::dvec3 x) { return glm::length(x); }),
          frame_scene(block, {-0.5, -0.6, -1}, width, height),
          adaptive_options(s, 0, 1.8, [](float u) {
            const float spike = std::exp(-std::pow((u - 0.55f) / 0.02f, 2.0f));
            return glm::vec4(u, 0.3f + 0.6f * spike, 1 - u, 0.02f + 0.6f * spike);
          })};
}

// A 3D checkerboard of concentrations 0 and 1 in cubes of 5 spacings, a cube of `side`^3
// particles.
inline AdaptiveScene checkerboard_scene(int width, int height, int side) {
  const double s = kCubeSpacing;
  const Particles block = cube_block(side);
  return {"checkerboard",
          with_values(block, s,
                      [&](glm::dvec3 x) {
                        const glm::ivec3 c(glm::floor(x / (5 * s)));
                        return double((c.x + c.y + c.z) % 2);
                      }),
          frame_scene(block, {-0.4, -0.5, -1}, width, height),
          adaptive_options(s, 0, 1, smooth_tf)};
}

// A dam break's shape (Ritter's solution) at three times, its height as the concentration, at
// `dam_spacing`; then radial_scene and checkerboard_scene. Each at width x height pixels.
inline std::vector<AdaptiveScene> adaptive_scenes(int width, int height, double dam_spacing = 0.02,
                                                  int side = 20) {
  std::vector<AdaptiveScene> out;
  DamBreak shape;
  shape.spacing = dam_spacing;
  shape.radius = dam_spacing;
  for (double t : {0.0, 0.3, 0.8}) {
    const Particles p = dam_break(shape, t);
    out.push_back({"dam break t = " + std::to_string(t).substr(0, 3),
                   with_values(p, shape.spacing, [](glm::dvec3 x) { return x.y; }),
                   frame_scene(p, {-0.3, -0.4, -1}, width, height),
                   adaptive_options(shape.spacing, 0, 0.6, smooth_tf)});
  }
  out.push_back(radial_scene(width, height, side));
  out.push_back(checkerboard_scene(width, height, side));
  return out;
}

// A deep block whose value is the particle's image-plane slope x / z (a ramp across the view,
// the same all along each ray): every bundle's full-rate bounds are as wide as its lateral
// spread, too wide for a super-pixel, and a coarser level's are no wider, so relax 1 (which
// leaves that spread out of the coarse levels' terms) chooses coarse cells, and what they change
// is the field's variation along the ray inside a cell, near nothing. The block: `side`^2
// particles across the view, `depth` along it.
inline AdaptiveScene slope_ramp(int width, int height, int side, int depth) {
  const double s = 0.05;
  const Particles block = lattice_block({0, 0, 0}, {side, side, depth}, s, s);
  const Camera camera = frame_scene(block, {0, 0, -1}, width, height);
  const ViewFrame view(camera);
  const auto slope = [&](glm::dvec3 x) {
    const glm::dvec3 v = view.to_view(x);
    return 0.5 + 0.5 * v.x / (v.z * view.tan_half_x);
  };
  const std::vector<VolumeParticle> particles = with_values(block, s, slope);
  float lo = particles.front().value, hi = lo;
  for (const VolumeParticle& p : particles) lo = std::min(lo, p.value), hi = std::max(hi, p.value);
  return {"slope ramp", particles, camera,
          adaptive_options(s, lo, hi, [](float u) { return glm::vec4(u, 0.5f, 1 - u, 0.02f); })};
}

}  // namespace voxspan::test
