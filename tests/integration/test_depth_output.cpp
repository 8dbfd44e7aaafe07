// outputs.depth through the shared library as a solver links it: each view's first-entry
// distance as an OpenEXR image (channel Z, 32-bit float), read back with OpenEXR's own
// reader, against the distance to the nearest sphere computed exactly, ray by ray, on the CPU
// (the camera model of docs/runtime.md, "Depth images").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "output_files.h"
#include "tests/support/deep_exr_reader.h"
#include "tests/support/depth_exr_reader.h"
#include "tests/support/temp_folder.h"
#include "tools/scenes/lattice.h"
#include "voxspan/adapter.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

// The distance along the unit ray from `eye` to the nearest sphere; 0 when it meets none.
double first_hit(const std::array<double, 3>& eye, const std::array<double, 3>& dir,
                 const std::vector<ParticleSphere>& spheres) {
  double best = 0;
  for (const ParticleSphere& s : spheres) {
    const double ox = eye[0] - s.x, oy = eye[1] - s.y, oz = eye[2] - s.z;
    const double b = ox * dir[0] + oy * dir[1] + oz * dir[2];
    const double c = ox * ox + oy * oy + oz * oz - double(s.radius) * s.radius;
    const double disc = b * b - c;
    if (disc < 0) continue;
    const double t = -b - std::sqrt(disc);
    if (t > 0 && (best == 0 || t < best)) best = t;
  }
  return best;
}

std::array<double, 3> normalized(std::array<double, 3> v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

TEST(DepthOutput, FirstEntryDistanceOfEveryPixelAsOpenExr) {
  test::TempFolder dir;
  // A block of 12^3 particles, 1 cm apart, seen from a manual camera off its corner.
  const test::LatticeScene block = test::make_lattice_block(12, 0.01, 0.007f);
  const int width = 80, height = 60;
  const std::array<double, 3> eye{0.35, -0.2, 0.25}, target{0.06, 0.06, 0.06}, up{0, 0, 1};
  const std::string yaml = "output_folder: " + dir.path().string() + R"(
trigger: {every_steps: 1}
views:
  - name: corner
    width: 80
    height: 60
    shading: opaque
    filter_radius: 0
    camera: {eye: [0.35, -0.2, 0.25], target: [0.06, 0.06, 0.06], up: [0, 0, 1], fov: 24}
outputs:
  png: {enabled: false}
  stats: {enabled: false}
  depth: {enabled: true, trigger: {every_steps: 1}}
writer: {fsync: false}
)";
  std::vector<double> x, y, z;
  std::vector<float> r;
  for (const ParticleSphere& p : block.all) {
    x.push_back(p.x), y.push_back(p.y), z.push_back(p.z), r.push_back(p.radius);
  }
  {
    AdapterOptions options;
    options.classify.particle_spacing = block.spacing;
    Adapter adapter = adapter_from_config_text(yaml, options, "depth.yaml");
    const auto particles =
        ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_radii(r.data());
    ASSERT_TRUE(adapter.execute(3, 0.0, particles).ok());
    adapter.finish();
    EXPECT_NE(adapter.summary().find("1 depth images"), std::string::npos) << adapter.summary();
  }
  EXPECT_TRUE(test::temporaries_under(dir.path()).empty());
  const test::DepthExr d = test::read_depth_exr(dir / "depth" / "corner_00000003.exr");
  ASSERT_EQ(d.width, width);
  ASSERT_EQ(d.height, height);
  EXPECT_EQ(d.channels, std::vector<std::string>{"Z"});

  // The exact first hit of every pixel's ray through its centre, row 0 at the top.
  const auto forward = normalized({target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]});
  const auto right = normalized(cross(forward, up));
  const auto true_up = cross(right, forward);
  const double tan_y = std::tan(12.0 * M_PI / 180), tan_x = tan_y * width / height;
  int both = 0, agree = 0, hits = 0;
  double worst = 0;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      const double u = (2 * (px + 0.5) / width - 1) * tan_x,
                   v = (1 - 2 * (py + 0.5) / height) * tan_y;
      const auto ray = normalized({forward[0] + u * right[0] + v * true_up[0],
                                   forward[1] + u * right[1] + v * true_up[1],
                                   forward[2] + u * right[2] + v * true_up[2]});
      const double exact = first_hit(eye, ray, block.all);
      const float got = d.z[std::size_t(px) + std::size_t(py) * width];
      hits += exact > 0;
      agree += (exact > 0) == (got > 0);
      if (exact > 0 && got > 0) {
        ++both;
        worst = std::max(worst, std::abs(got - exact) / exact);
      }
    }
  std::printf(
      "depth image: %d pixels hit exactly, %d in both, hit masks agree on %.2f %%, worst "
      "relative distance error %.4f %%\n",
      hits, both, 100.0 * agree / (width * height), 100 * worst);
  ASSERT_GT(hits, width * height / 5) << "the block fills too little of the view";
  // Silhouette pixels may differ (a sphere grazed within a voxel); the rest agree.
  EXPECT_GE(double(agree) / (width * height), 0.98);
  // A depth layer here is 0.17 % of the depth (pixel angle 24/60 degrees times tan 14 degrees,
  // docs/design.md "Voxelization"); an entry lies within a layer of the exact one. Two layers:
  EXPECT_LE(worst, 0.0035) << both << " pixels hit in both";
}

// outputs.exr beside outputs.depth in one run on `backend`: the deep image's first sample of
// every pixel is the depth image's distance, its samples in order, each span's exit behind its
// entry; the colour companion is the picture (alpha 1).
void check_deep_exr_output(const std::string& backend) {
  SCOPED_TRACE("renderer " + backend);
  test::TempFolder dir;
  const test::LatticeScene block = test::make_lattice_block(12, 0.01, 0.007f);
  const std::string yaml =
      "output_folder: " + dir.path().string() + "\nrenderer: {backend: " + backend + "}" + R"(
trigger: {every_steps: 1}
views:
  - name: corner
    width: 80
    height: 60
    shading: translucent
    camera: {eye: [0.35, -0.2, 0.25], target: [0.06, 0.06, 0.06], up: [0, 0, 1], fov: 24}
outputs:
  png: {enabled: false}
  stats: {enabled: false}
  depth: {enabled: true, trigger: {every_steps: 1}}
  exr: {enabled: true, trigger: {every_steps: 1}}
writer: {fsync: false}
)";
  std::vector<double> x, y, z;
  for (const ParticleSphere& p : block.all) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  {
    AdapterOptions options;
    options.classify.particle_spacing = block.spacing;
    Adapter adapter = adapter_from_config_text(yaml, options, "exr.yaml");
    ASSERT_TRUE(
        adapter.execute(4, 0.0, ParticleView::soa(x.data(), y.data(), z.data(), x.size())).ok());
    adapter.finish();
    EXPECT_NE(adapter.summary().find("1 deep EXR images"), std::string::npos) << adapter.summary();
  }
  EXPECT_TRUE(test::temporaries_under(dir.path()).empty());
  const test::DepthExr flat = test::read_depth_exr(dir / "depth" / "corner_00000004.exr");
  const test::DeepExr deep = test::read_deep_exr(dir / "exr" / "corner_00000004.exr");
  ASSERT_EQ(deep.width, 80);
  ASSERT_EQ(deep.height, 60);
  int hits = 0;
  for (std::size_t p = 0; p < deep.z.size(); ++p) {
    ASSERT_EQ(deep.z[p].empty(), flat.z[p] == 0) << "pixel " << p;
    if (deep.z[p].empty()) continue;
    ++hits;
    EXPECT_NEAR(deep.z[p][0], flat.z[p], 1e-6 * flat.z[p]) << "pixel " << p;
    for (std::size_t k = 0; k < deep.z[p].size(); ++k) {
      EXPECT_LT(deep.z[p][k], deep.z_back[p][k]) << "pixel " << p << " sample " << k;
      if (k > 0) {
        EXPECT_GE(deep.z[p][k], deep.z_back[p][k - 1]) << "pixel " << p;
      }
    }
  }
  EXPECT_GT(hits, 80 * 60 / 5);
  Imf::InputFile color((dir / "exr" / "corner_color_00000004.exr").c_str());
  std::vector<float> alpha(80 * 60, 0.0f);
  Imf::FrameBuffer frame;
  frame.insert("A", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(alpha.data()), sizeof(float),
                               sizeof(float) * 80));
  color.setFrameBuffer(frame);
  color.readPixels(0, 59);
  for (float a : alpha) ASSERT_EQ(a, 1.0f);
}

TEST(DeepExrOutput, EveryViewsSpansAndItsPictureAsOpenExrOnBothRenderers) {
  check_deep_exr_output("cpu");
  check_deep_exr_output("gl");
}

}  // namespace
}  // namespace voxspan
