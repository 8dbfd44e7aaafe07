// Walls in a volume frame (VolumeOptions::backdrop, render/backdrop.h): a ray ends at its pixel's
// walls, and their colour (or the backdrop's environment, where none stands) lies behind the
// fluid. Adaptive sampling with walls: tests/render/cpu/test_volume_adaptive.cpp; over ranks:
// test_volume_parts.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "render/backdrop.h"
#include "render/cpu/volume_caster.h"
#include "tests/support/image_difference.h"
#include "tests/support/volume_cloud.h"

namespace voxspan {
namespace {

constexpr glm::vec3 kRed{0.8f, 0.1f, 0.1f}, kBlue{0.1f, 0.2f, 0.7f};

// The cloud's view in three bands of columns: a red wall in front of the whole block, a black
// wall at `cut` (through the block), then a blue wall behind it all; the last band's lower half
// has no wall (the blue environment).
Backdrop bands(const Camera& camera, float cut) {
  Backdrop b;
  b.width = camera.width;
  b.height = camera.height;
  b.version = 1;
  b.pixels.resize(std::size_t(b.width) * std::size_t(b.height));
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      glm::vec4& p = b.pixels[std::size_t(x) + std::size_t(y) * std::size_t(b.width)];
      if (x < b.width / 3) p = glm::vec4(kRed, 1.0f);
      else if (x < 2 * b.width / 3) p = glm::vec4(0, 0, 0, cut);
      else p = glm::vec4(kBlue, y < b.height / 2 ? 10.0f : Backdrop::kNoWall);
    }
  return b;
}

struct Frames {
  VolumeFrame plain, walled;  // without walls and background (transparent), with the walls
  VolumeCounts plain_counts, walled_counts;
};

Frames render(const test::Cloud& c, VolumeOptions o, const Backdrop& walls) {
  VolumeCaster caster;
  Frames f;
  o.background = false;
  f.plain_counts = caster.run(c.camera, c.particles, o, f.plain);
  o.backdrop = &walls;
  o.background = true;
  f.walled_counts = caster.run(c.camera, c.particles, o, f.walled);
  return f;
}

TEST(VolumeWalls, RaysEndAtTheirWallsAndShowThemBehindTheFluid) {
  const test::Cloud c = test::cloud(10, 11);
  test::each_mode(c.spacing, [&](VolumeOptions o) {
    o.termination = 0;
    const Backdrop walls = bands(c.camera, 2.3f);
    const Frames f = render(c, o, walls);
    double front = 0, behind = 0, cut_brighter = 0, cut_darker = 0;
    for (int y = 0; y < walls.height; ++y)
      for (int x = 0; x < walls.width; ++x) {
        const glm::vec4 p = f.plain.picture.at(x, y), w = f.walled.picture.at(x, y);
        EXPECT_EQ(w.a, 1.0f);
        if (x < walls.width / 3) {  // nothing in front of the red wall
          front = std::max(front, double(glm::length(glm::vec3(w) - kRed)));
        } else if (x < 2 * walls.width / 3) {  // fewer samples: less light
          for (int ch = 0; ch < 3; ++ch) {
            cut_brighter = std::max(cut_brighter, double(w[ch] - p[ch]));
            cut_darker = std::max(cut_darker, double(p[ch] - w[ch]));
          }
        } else {  // the whole ray, then blue
          const glm::vec3 expected = glm::vec3(p) + (1.0f - p.a) * kBlue;
          behind = std::max(behind, double(glm::length(glm::vec3(w) - expected)));
        }
      }
    std::printf("front %.1e, behind %.1e, cut: brighter %.1e, darker %.2f; samples %lld -> %lld\n",
                front, behind, cut_brighter, cut_darker,
                static_cast<long long>(f.plain_counts.samples),
                static_cast<long long>(f.walled_counts.samples));
    EXPECT_EQ(front, 0);
    EXPECT_LT(behind, 1e-6);
    EXPECT_LT(cut_brighter, 1e-6);
    EXPECT_GT(cut_darker, 0.05);  // the wall cuts light off
    EXPECT_LT(f.walled_counts.samples, f.plain_counts.samples * 3 / 4);
  });
}

TEST(VolumeWalls, NoWallAndNoBackgroundStaysTransparent) {
  const test::Cloud c = test::cloud(8, 5);
  VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  Backdrop none = bands(c.camera, 2.3f);
  for (glm::vec4& p : none.pixels) p = glm::vec4(kBlue, Backdrop::kNoWall);
  VolumeCaster caster;
  VolumeFrame plain, walled;
  o.background = false;
  caster.run(c.camera, c.particles, o, plain);
  o.backdrop = &none;
  caster.run(c.camera, c.particles, o, walled);
  EXPECT_EQ(test::largest_difference(plain.picture, walled.picture), 0);
}

TEST(VolumeWalls, ABackdropOfAnotherSizeIsRefused) {
  const test::Cloud c = test::cloud(4, 1);
  VolumeOptions o = test::cloud_options(VolumeMode::dvr, c.spacing);
  Backdrop small;
  small.width = 3;
  small.height = 2;
  small.pixels.resize(6);
  o.backdrop = &small;
  VolumeCaster caster;
  VolumeFrame f;
  try {
    caster.run(c.camera, c.particles, o, f);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("backdrop is 3x2, the view 56x44"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace voxspan
