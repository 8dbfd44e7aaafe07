// views[i] of kind `slice` through the runtime: its keys read and refused as documented, the
// picture coloured where the plane meets the fluid and dark where it does not, a quantity the
// solver does not pass failing the step by name, and a plane that misses the fluid drawing
// an empty picture. The interpolation itself: test_sph_slice.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "insitu/views/slice_view.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;

// A block 1.0 x 0.5 x 0.5 with density rising along x.
struct Block {
  std::vector<double> xyz, density;
  Block() {
    for (int k = 0; k < 10; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 20; ++i) {
          for (int a : {i, j, k}) xyz.push_back((a + 0.5) * kSpacing);
          density.push_back(1000 + 10 * xyz[xyz.size() - 3]);
        }
  }
  ParticleView view() const {
    return ParticleView::aos(xyz.data(), density.size()).with_scalar("density", density.data());
  }
};

std::string config(const std::string& slice) {
  return "output_folder: " + testing::TempDir() +
         "slice_view\n"
         "outputs: {png: {enabled: false}, stats: {enabled: false}}\n"
         "trigger: {every_steps: 1}\n"
         "views:\n  - {name: s, kind: slice, width: 64, height: 32, " +
         slice + "}\n";
}

const FloatImage& picture_of(const Adapter& a) {
  const auto& pipeline = dynamic_cast<const InsituPipeline&>(*a.pipeline());
  return *pipeline.latest_views()[0].picture;
}

AdapterOptions options() {
  AdapterOptions o;
  o.classify.particle_spacing = kSpacing;
  return o;
}

TEST(SliceView, KeysAreReadAsWritten) {
  const Config c = load_config_string(
      "views:\n  - {kind: slice, quantity: p, kernel: quintic, shepard: true, range: [1, 2],"
      " color_map: coolwarm, plane: {origin: [1, 2, 3], normal: [0, 0, 2]}, isolines: 0}\n");
  const auto& s = dynamic_cast<const SliceSettings&>(*c.views[0].settings);
  EXPECT_EQ(s.quantity, "p");
  EXPECT_EQ(s.kernel, SphKernel::quintic);
  EXPECT_TRUE(s.shepard);
  ASSERT_TRUE(s.range);
  EXPECT_EQ((*s.range)[1], 2.0);
  EXPECT_EQ(s.color_map, ColorMap::coolwarm);
  EXPECT_EQ(s.plane.normal[2], 2.0);
  EXPECT_EQ(load_config_string(to_yaml(c)).views[0], c.views[0]);
}

TEST(SliceView, BadKeysAreRefusedWithTheirLine) {
  for (const auto& [yaml, words] : std::vector<std::pair<std::string, std::string>>{
           {"color_map: rainbow, quantity: p", "color_map"},
           {"range: [2, 1], quantity: p", "range"},
           {"plane: {normal: [0, 0, 0]}, quantity: p", "must not be zero"},
           {"kernel: gauss, quantity: p", "kernel"},
           {"width: 10", "needs `quantity`"}}) {
    try {
      load_config_string("views:\n  - {kind: slice, " + yaml + "}\n", "s.yaml");
      ADD_FAILURE() << yaml << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("s.yaml:2:"), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  }
}

TEST(SliceView, ColoursThePlaneWhereItMeetsTheFluid) {
  const Block b;
  Adapter a = adapter_from_config_text(
      config("quantity: density, shepard: true, plane: {normal: [0, -1, 0]}, isolines: 0"),
      options());
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const FloatImage& p = picture_of(a);
  // The plane through the box's centre seen from -y (its normal's side), fitted: +x to the
  // right. The left of the picture is the low density end (viridis: dark blue), the right the
  // high end (yellow-green); the colour bar is further right.
  const glm::vec4 left = p.at(6, 9), right = p.at(50, 9);  // between the legend's labels
  EXPECT_GT(left.b, left.g);
  EXPECT_GT(right.g, right.b);
  EXPECT_GT(right.r + right.g, left.r + left.g);
}

TEST(SliceView, AMissingQuantityFailsTheStepByName) {
  const Block b;
  Adapter a = adapter_from_config_text(config("quantity: pressure"), options());
  const Status s = a.execute(0, 0, b.view());
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("\"pressure\""), std::string::npos) << s.message;
}

TEST(SliceView, APlaneThatMissesTheFluidDrawsAnEmptyPicture) {
  const Block b;
  Adapter a = adapter_from_config_text(
      config("quantity: density, plane: {origin: [0, 0, 9], normal: [0, 0, 1]}"), options());
  ASSERT_TRUE(a.execute(0, 0, b.view()).ok());
  const FloatImage& p = picture_of(a);
  for (int x : {0, 10, 30}) EXPECT_LT(p.at(x, 16).g, 0.05f) << x;
}

}  // namespace
}  // namespace voxspan
