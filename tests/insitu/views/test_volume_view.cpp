// views[i] of kind `volume` through the runtime: its keys read and written back as given, bad
// transfer functions and iso surfaces refused at start-up with their line, a quantity the
// solver does not pass failing the step by name, and the picture: the fluid tinted where it is,
// the background elsewhere, the same picture at every scale of the scene, the depth output at
// the iso surface. The renderer itself: tests/render/cpu/test_volume.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "insitu/views/volume_view.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

// A block 1.0 x 0.5 x 0.5 of spacing `spacing`, with pressure rising along x.
struct Block {
  double spacing;
  std::vector<double> xyz, pressure;
  explicit Block(double s = 0.05) : spacing(s) {
    for (int k = 0; k < 10; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 20; ++i) {
          for (int a : {i, j, k}) xyz.push_back((a + 0.5) * spacing);
          pressure.push_back(100 * i);
        }
  }
  ParticleView view() const {
    return ParticleView::aos(xyz.data(), pressure.size()).with_scalar("pressure", pressure.data());
  }
};

std::string config(const std::string& keys, const std::string& folder = "volume_view") {
  return "output_folder: " + testing::TempDir() + folder +
         "\n"
         "outputs: {png: {enabled: false}, stats: {enabled: false}}\n"
         "trigger: {every_steps: 1}\n"
         "views:\n  - {name: v, kind: volume, width: 64, height: 40,"
         " camera: {direction: [0.2, -1, -0.5], up: [0, 0, 1]}, " +
         keys + "}\n";
}

const ViewResult& result_of(const Adapter& a) {
  const auto& pipeline = dynamic_cast<const InsituPipeline&>(*a.pipeline());
  return pipeline.latest_views()[0];
}

AdapterOptions options(double spacing) {
  AdapterOptions o;
  o.classify.particle_spacing = spacing;
  return o;
}

TEST(VolumeView, KeysAreReadAsWritten) {
  const Config c = load_config_string(
      "views:\n  - {kind: volume, quantity: p, kernel: poly6, mode: mixed, shepard: false,"
      " range: [1, 2], opacity: [[0, 0], [0.5, 0.1], [1, 1]], opacity_length: 3,"
      " iso: [{value: 1.5, color: [1, 0, 0], opacity: 0.5}, {value: 1.8}], sampling: 2,"
      " smoothing_attribute: h, background: none, legend: false}\n");
  const auto& s = dynamic_cast<const VolumeSettings&>(*c.views[0].settings);
  EXPECT_EQ(s.quantity, "p");
  EXPECT_EQ(s.kernel, SphKernel::poly6);
  EXPECT_EQ(s.mode, VolumeMode::mixed);
  ASSERT_EQ(s.opacity.size(), 3u);
  EXPECT_EQ(s.opacity[1][1], 0.1);
  ASSERT_EQ(s.iso.size(), 2u);
  EXPECT_EQ(s.iso[0].color[0], 1.0);
  EXPECT_EQ(s.iso[1].opacity, 1.0);
  EXPECT_EQ(s.background, VolumeBackground::none);
  EXPECT_EQ(load_config_string(to_yaml(c)).views[0], c.views[0]);
}

TEST(VolumeView, BadTransferFunctionsAndIsoSurfacesAreRefusedWithTheirLine) {
  for (const auto& [yaml, words] : std::vector<std::pair<std::string, std::string>>{
           {"opacity: [[0.5, 0], [0.2, 1]]", "must not decrease"},
           {"opacity: [[0, 0], [1, 1.5]]", "alpha in [0, 1]"},
           {"opacity: [[0, -0.1]]", "alpha in [0, 1]"},
           {"opacity: [0, 1]", "[a, b] pairs"},
           {"mode: iso", "needs at least one iso surface"},
           {"mode: iso, iso: [{value: .nan}]", "views[0].iso[0].value"},
           {"mode: iso, iso: [{value: .inf}]", "views[0].iso[0].value"},
           {"mode: iso, iso: [{color: [1, 1, 1]}]", "needs its `value`"},
           {"iso: [{value: 1}, {value: 2}, {value: 3}, {value: 4}, {value: 5}]", "at most 4"},
           {"shepard: true", "volume fraction"},
           {"sampling: 0", "sampling"}}) {
    try {
      load_config_string("views:\n  - {kind: volume, " + yaml + "}\n", "v.yaml");
      ADD_FAILURE() << yaml << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("v.yaml:2:"), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << yaml << ": " << what;
    }
  }
}

TEST(VolumeView, AMissingQuantityFailsTheStepByName) {
  const Block b;
  Adapter a = adapter_from_config_text(config("quantity: temperature"), options(b.spacing));
  const Status s = a.execute(0, 0, b.view());
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("views[0].quantity \"temperature\""), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("(it passes: pressure)"), std::string::npos) << s.message;
}

// The centre pixel (over the block) and a corner (the sky) of the view of a block at `spacing`.
std::array<glm::vec4, 2> centre_and_corner(const std::string& keys, double spacing) {
  const Block b(spacing);
  Adapter a = adapter_from_config_text(config(keys), options(spacing));
  EXPECT_TRUE(a.execute(0, 0, b.view()).ok());
  const FloatImage& p = *result_of(a).picture;
  return {p.at(32, 20), p.at(1, 1)};
}

// (Below about 1e-8 the runtime's automatic framing loses the fluid, whatever the view kind:
// the next issue's.)
TEST(VolumeView, TheFluidIsTintedWhereItIsAndTheSameAtEveryScale) {
  const std::string keys = "quantity: pressure, legend: false, opacity: [[0, 0.3], [1, 0.3]]";
  const auto [centre, corner] = centre_and_corner(keys, 0.05);
  // The sky in the corner (bluish), the tinted fluid in the centre: not the sky's colour.
  EXPECT_GT(corner.b, corner.r);
  EXPECT_GT(std::abs(centre.g - corner.g) + std::abs(centre.r - corner.r), 0.1f);
  for (double spacing : {5e-6, 5e6, 5e18}) {
    const auto [c, k] = centre_and_corner(keys, spacing);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(c[ch], centre[ch], 1e-4) << spacing;
      EXPECT_NEAR(k[ch], corner[ch], 1e-4) << spacing;
    }
  }
}

TEST(VolumeView, TheDepthOutputIsTheFirstIsoHit) {
  const Block b;
  Adapter a = adapter_from_config_text(
      "output_folder: " + testing::TempDir() +
          "volume_depth\n"
          "outputs: {png: {enabled: false}, stats: {enabled: false},"
          " depth: {enabled: true, folder: depth}}\n"
          "views:\n  - {name: v, kind: volume, width: 64, height: 40, mode: iso,"
          " iso: [{value: 0.5}], camera: {eye: [0.5, 0.25, 2], target: [0.5, 0.25, 0],"
          " up: [0, 1, 0]}}\n",
      options(b.spacing));
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const ViewResult& r = result_of(a);
  ASSERT_NE(r.first_hit_depth, nullptr);
  // Straight down onto the block's top (z = 0.5): the volume fraction's half-way surface lies
  // about half a spacing above the top particles' centres (z = 0.475): 1.5 from the eye.
  const float d = r.first_hit_depth->at(32, 20).r;
  EXPECT_NEAR(d, 2.0 - 0.5, 0.03) << d;
  EXPECT_EQ(r.first_hit_depth->at(1, 1).r, 0.0f);  // no fluid in the corner
}

}  // namespace
}  // namespace voxspan
