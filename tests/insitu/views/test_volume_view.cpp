// views[i] of kind `volume` through the runtime: its keys read and written back as given, bad
// transfer functions and iso surfaces refused at start-up with their line, a quantity the
// solver does not pass failing the step by name, and the picture: the fluid tinted where it is,
// the background elsewhere, the same picture at every scale of the scene, the depth output at
// the iso surface. The renderer itself: tests/render/cpu/test_volume.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/views/volume_view.h"
#include "tests/support/error_message.h"
#include "tests/support/log_capture.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

// A block 1.0 x 0.5 x 0.5 (at spacing 0.05) with pressure rising along x.
test::ParticleBlock block(double spacing = 0.05) {
  return {spacing, "pressure", [](int i, double) { return 100.0 * i; }};
}

std::string config(const std::string& keys, const std::string& folder = "volume_view") {
  return test::one_view_config(folder,
                               "name: v, kind: volume, width: 64, height: 40,"
                               " camera: {direction: [0.2, -1, -0.5], up: [0, 0, 1]}, " +
                                   keys);
}

TEST(VolumeView, KeysAreReadAsWritten) {
  const VolumeSettings s = test::read_view<VolumeSettings>(
      "kind: volume, quantity: p, kernel: poly6, mode: mixed, shepard: false,"
      " range: [1, 2], opacity: [[0, 0], [0.5, 0.1], [1, 1]], opacity_length: 3,"
      " iso: [{value: 1.5, color: [1, 0, 0], opacity: 0.5}, {value: 1.8}], sampling: 2,"
      " smoothing_attribute: h, background: none, legend: false");
  EXPECT_EQ(s.quantity, "p");
  EXPECT_EQ(s.kernel, SphKernel::poly6);
  EXPECT_EQ(s.mode, VolumeMode::mixed);
  ASSERT_EQ(s.opacity.size(), 3u);
  EXPECT_EQ(s.opacity[1][1], 0.1);
  ASSERT_EQ(s.iso.size(), 2u);
  EXPECT_EQ(s.iso[0].color[0], 1.0);
  EXPECT_EQ(s.iso[1].opacity, 1.0);
  EXPECT_EQ(s.background, VolumeBackground::none);
}

TEST(VolumeView, BadTransferFunctionsAndIsoSurfacesAreRefusedWithTheirLine) {
  test::expect_refused_with_line(
      "volume",
      {{"opacity: [[0.5, 0], [0.2, 1]]", "must not decrease"},
       {"opacity: [[0, 0], [1, 1.5]]", "alpha in [0, 1]"},
       {"opacity: [[0, -0.1]]", "alpha in [0, 1]"},
       {"opacity: [0, 1]", "[a, b] pairs"},
       {"mode: iso", "needs at least one iso surface"},
       {"mode: iso, iso: [{value: .nan}]", "views[0].iso[0].value"},
       {"mode: iso, iso: [{value: .inf}]", "views[0].iso[0].value"},
       {"mode: iso, iso: [{color: [1, 1, 1]}]", "needs its `value`"},
       {"mode: iso, iso: [{value: 1}, {value: 2}, {value: 3}, {value: 4}, {value: 5}]",
        "at most 4"},
       {"iso: [{value: 1}]", "mode `dvr` draws no iso surfaces"},
       {"shepard: true", "volume fraction"},
       {"mode: iso, iso: [{value: 1, color: [255, 128, 0]}]", "divide them by 255"},
       {"quantity: T, units: \"\u00b0C\"", "printable ASCII only"},
       {"quantity: T, smoothing_length: 0.1, smoothing_attribute: h", "leave smoothing_length out"},
       {"adaptive: {error_tolerance: 0.01}", "applies to DVR of a Shepard"},
       {"quantity: p, shepard: false, adaptive: {error_tolerance: 0.01}",
        "applies to DVR of a Shepard"},
       {"quantity: p, mode: iso, iso: [{value: 1}], adaptive: {error_tolerance: 0.01}",
        "applies to DVR of a Shepard"},
       {"sampling: 0", "sampling"}});
  // Too many iso surfaces is that one error, not also "needs at least one".
  const std::string e = test::error_message([] {
    load_config_string(
        "views:\n  - {kind: volume, mode: iso, iso: [{value: 1}, {value: 2}, "
        "{value: 3}, {value: 4}, {value: 5}]}\n",
        "v.yaml");
  });
  EXPECT_EQ(e.find("needs at least one"), std::string::npos) << e;
  EXPECT_NE(e.find("at most 4 maps; got a list of 5"), std::string::npos) << e;
}

TEST(VolumeView, AMissingQuantityFailsTheStepByName) {
  test::expect_missing_attribute(config("quantity: temperature"), block(),
                                 "<config>:5:5: views[0].quantity", "temperature");
}

// Values that are not numbers, and an iso surface at a level the Shepard-normalised field never
// reaches (it lies between its particles' values), are said once each: the picture would
// otherwise have holes, or be empty, without a word.
TEST(VolumeView, NanValuesAndUnreachedIsoLevelsAreSaidOnce) {
  test::ParticleBlock b = block();
  for (std::size_t i = 0; i < b.values.size(); i += 7) b.values[i] = std::nan("");
  test::LogCapture log;
  Adapter a = adapter_from_config_text(
      config("quantity: pressure, mode: iso, iso: [{value: 500}, {value: 5000}]"),
      test::spaced(b.spacing));
  for (int step = 0; step < 2; ++step) EXPECT_TRUE(a.execute(step, 0, b.view()).ok());
  const std::vector<std::string> said = log.at(LogLevel::warning);
  ASSERT_EQ(said.size(), 2u) << log.all();
  EXPECT_NE(said[0].find("particles whose pressure is NaN or infinite are left out (286;"),
            std::string::npos)
      << said[0];
  EXPECT_NE(said[1].find("iso[1].value 5000 lies outside the field's values (0 to 1900)"),
            std::string::npos)
      << said[1];
}

// A smoothing length in other units than the positions is said at start-up, with what it costs.
TEST(VolumeView, ASmoothingLengthFarFromTheSpacingIsSaid) {
  test::LogCapture log;
  Adapter a = adapter_from_config_text(config("quantity: pressure, smoothing_length: 5"),
                                       test::spaced(0.05));
  const std::vector<std::string> said = log.at(LogLevel::warning);
  ASSERT_EQ(said.size(), 1u) << log.all();
  EXPECT_NE(said[0].find("view v: smoothing_length 5 is 100 particle spacings (0.05): each sample "
                         "then sums about 4200000 particles"),
            std::string::npos)
      << said[0];
}

// The centre pixel (over the block) and a corner (the sky) of the view of a block at `spacing`.
std::array<glm::vec4, 2> centre_and_corner(const std::string& keys, double spacing) {
  const test::ParticleBlock b = block(spacing);
  const FloatImage p = test::first_picture(config(keys), b);
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
  const test::ParticleBlock b = block();
  Adapter a = adapter_from_config_text(
      "output_folder: " + testing::TempDir() +
          "volume_depth\n"
          "outputs: {png: {enabled: false}, stats: {enabled: false},"
          " depth: {enabled: true, folder: depth}}\n"
          "views:\n  - {name: v, kind: volume, width: 64, height: 40, mode: iso,"
          " iso: [{value: 0.5}], camera: {eye: [0.5, 0.25, 2], target: [0.5, 0.25, 0],"
          " up: [0, 1, 0]}}\n",
      test::spaced(b.spacing));
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const ViewResult& r = test::latest_view(a);
  ASSERT_NE(r.first_hit_depth, nullptr);
  // Straight down onto the block's top (z = 0.5): the volume fraction's half-way surface lies
  // about half a spacing above the top particles' centres (z = 0.475): 1.5 from the eye.
  const float d = r.first_hit_depth->at(32, 20).r;
  EXPECT_NEAR(d, 2.0 - 0.5, 0.03) << d;
  EXPECT_EQ(r.first_hit_depth->at(1, 1).r, 0.0f);  // no fluid in the corner
}

// The GL backend's march (llvmpipe here) draws the CPU renderer's picture, to float sums.
TEST(VolumeView, TheGlBackendDrawsTheCpuPicture) {
  const test::ParticleBlock b = block();
  const std::string keys = "quantity: pressure, mode: mixed, iso: [{value: 900, opacity: 0.5}]";
  FloatImage pictures[2];
  for (int k = 0; k < 2; ++k)
    pictures[k] = test::first_picture(
        config(keys) + "renderer: {backend: " + (k == 0 ? "cpu" : "gl") + "}\n", b);
  ASSERT_EQ(pictures[0].rgba.size(), pictures[1].rgba.size());
  double d = 0;
  for (std::size_t i = 0; i < pictures[0].rgba.size(); ++i)
    d = std::max(d, double(std::abs(pictures[0].rgba[i] - pictures[1].rgba[i])));
  EXPECT_LT(d, 1e-4);
}

}  // namespace
}  // namespace voxspan
