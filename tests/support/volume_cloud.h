// A random block of particles with values varying in space, its camera and volume options
// (the volume renderers' tests, tests only).
#pragma once

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "render/cpu/volume_caster.h"
#include "render/sph_kernel.h"
#include "render/volume.h"
#include "tools/scenes/scenes.h"

namespace voxspan::test {

// A random block with values varying in space: the renderer's picture against the reference's.
struct Cloud {
  std::vector<VolumeParticle> particles;
  Camera camera;
  double spacing = 0.1;
};

inline Cloud cloud(int side, std::uint32_t seed) {
  Cloud c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) {
        const glm::dvec3 p =
            (glm::dvec3(i, j, k) + glm::dvec3(jitter(rng), jitter(rng), jitter(rng))) * c.spacing;
        const double value = std::sin(3 * p.x) + p.y * p.y + 0.5 * p.z;
        c.particles.push_back({float(p.x), float(p.y), float(p.z), float(1.3 * c.spacing),
                               float(1 / std::pow(1.3, 3)), float(value)});
      }
  const double mid = 0.5 * (side - 1) * c.spacing;
  c.camera = test::look_at({mid + 0.4, mid + 0.5, mid + 2.2}, {mid, mid, mid}, 56, 44, 40);
  return c;
}

inline VolumeOptions cloud_options(VolumeMode mode, double spacing) {
  VolumeOptions o;
  o.mode = mode;
  o.anchor = spacing;
  o.opacity_length = spacing;
  TransferTable t;
  t.lo = -0.5;
  t.hi = 2.0;
  for (int k = 0; k < kTransferEntries; ++k) {
    const float u = float(k) / (kTransferEntries - 1);
    t.rgba[std::size_t(k)] = glm::vec4(u, 0.5f - 0.4f * u, 1 - u, 0.05f + 0.2f * u * u);
  }
  o.transfer = t;
  if (mode != VolumeMode::dvr) o.isos = {{0.6, {0.9, 0.8, 0.3}, 0.7}, {1.2, {0.3, 0.9, 0.4}, 1}};
  return o;
}

// fn(options) for every mode, with and without Shepard normalisation, under a trace naming them.
template <class F> void each_mode(double spacing, F fn) {
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::iso, VolumeMode::mixed})
    for (bool shepard : {true, false}) {
      SCOPED_TRACE(std::string(name_of(kVolumeModeNames, mode)) + (shepard ? " shepard" : ""));
      VolumeOptions o = cloud_options(mode, spacing);
      o.shepard = shepard;
      fn(o);
    }
}

// fn(options, name) in mixed mode for every SPH kernel, under a trace naming it.
template <class F> void each_kernel(double spacing, F fn) {
  for (const auto& [name, kernel] : kSphKernelNames) {
    SCOPED_TRACE(name);
    VolumeOptions o = cloud_options(VolumeMode::mixed, spacing);
    o.kernel = kernel;
    fn(o, name);
  }
}

// The CPU caster's picture of `c` under `o` on 1, 2 and 7 threads: the same bit for bit.
inline void expect_same_on_any_threads(const Cloud& c, const VolumeOptions& o) {
  std::vector<float> first;
  for (int threads : {1, 2, 7}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    VolumeCaster caster;
    VolumeFrame frame;
    caster.run(c.camera, c.particles, o, frame);
    if (first.empty()) first = frame.picture.rgba;
    else EXPECT_EQ(frame.picture.rgba, first) << threads << " threads";
  }
}

}  // namespace voxspan::test
