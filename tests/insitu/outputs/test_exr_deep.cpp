// outputs.exr's deep image (insitu/outputs/formats/exr_image.h), read back with OpenEXR's own deep
// reader: per pixel as many samples as the span image stores, Z and ZBack the spans' entry
// and exit depths times the pixel ray's length (distances along the unit ray), to float
// precision; pixels without spans have no samples. And its RGBA companion, and a slice view's
// raw values with their world mapping.
#include <gtest/gtest.h>

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include <cmath>
#include <fstream>
#include <vector>

#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>

#include "insitu/outputs/formats/exr_image.h"
#include "insitu/runtime/pipeline.h"
#include "tests/support/deep_exr_reader.h"
#include "tests/support/temp_folder.h"
#include "tests/support/view_tests.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

// 7 x 5 pixels, pixel (x, y) holding (x + y) % 3 spans at depths that differ from pixel to pixel.
SpanImage test_spans() {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.width = 7;
  camera.height = 5;
  SpanImage image;
  image.grid = PerspectiveGrid::over(camera, 0.5, 10, GridOptions{});
  image.pixels.resize(35);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      PixelSpans& p = image.pixels[std::size_t(x) + 7 * std::size_t(y)];
      p.offset = std::uint32_t(image.spans.size());
      p.count = p.total = std::uint32_t((x + y) % 3);
      for (std::uint32_t k = 0; k < p.count; ++k) {
        const float entry = 1.0f + 0.37f * float(x) + 0.11f * float(y) + 2.0f * float(k);
        image.spans.push_back({entry, entry + 0.5f + 0.01f * float(x)});
      }
    }
  return image;
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A run with outputs.exr on every step into `folder`, and one view, `view` (its flow map's
// inside).
std::string exr_run(const std::filesystem::path& folder, const std::string& view) {
  return "output_folder: " + folder.string() +
         "\noutputs: {png: {enabled: false}, stats: {enabled: false},"
         " exr: {enabled: true, trigger: {every_steps: 1}}}\n"
         "writer: {fsync: false}\nviews:\n  - {" +
         view + "}\n";
}

// A flat EXR file's R, G, B, A channels, interleaved per pixel (-1 where it has none).
std::vector<float> read_rgba(const std::filesystem::path& path, int width, int height) {
  Imf::InputFile file(path.c_str());
  std::vector<float> rgba(4 * std::size_t(width) * std::size_t(height), -1.0f);
  Imf::FrameBuffer frame;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgba.data() + c),
                                      4 * sizeof(float), 4 * sizeof(float) * std::size_t(width)));
  file.setFrameBuffer(frame);
  file.readPixels(0, height - 1);
  return rgba;
}

TEST(DeepExr, ReadBackGivesTheSpansAsDistancesAlongTheUnitRay) {
  test::TempFolder dir;
  const SpanImage spans = test_spans();
  write(dir / "deep.exr", encode_deep_exr(spans));

  const test::DeepExr d = test::read_deep_exr(dir / "deep.exr");
  EXPECT_EQ(d.type, Imf::DEEPSCANLINE);
  ASSERT_EQ(d.width, 7);
  ASSERT_EQ(d.height, 5);
  EXPECT_TRUE(d.has_z);
  EXPECT_TRUE(d.has_z_back);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) {
      const std::size_t p = std::size_t(x) + 7 * std::size_t(y);
      ASSERT_EQ(d.z[p].size(), spans.pixels[p].count) << x << "," << y;
      const double scale = spans.grid.view().ray_scale(x, y);
      for (std::uint32_t k = 0; k < spans.pixels[p].count; ++k) {
        const Span& s = spans.spans[spans.pixels[p].offset + k];
        EXPECT_FLOAT_EQ(d.z[p][k], float(s.entry * scale)) << x << "," << y << " span " << k;
        EXPECT_FLOAT_EQ(d.z_back[p][k], float(s.exit * scale)) << x << "," << y << " span " << k;
      }
    }
}

TEST(DeepExr, TheColourCompanionHoldsThePictureAsRgbaFloats) {
  test::TempFolder dir;
  FloatImage picture(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) picture.set(x, y, {0.1f * x, 0.2f * y, 0.5f, 1.0f});
  write(dir / "color.exr", encode_exr_rgba(picture));
  EXPECT_EQ(read_rgba(dir / "color.exr", 3, 2), picture.rgba);
}

// A slice view with outputs.exr on: its raw values as float channels and the plane's
// pixel-to-world mapping in the header, as the runtime wrote them.
TEST(SliceExr, HoldsTheRawValuesAndThePixelToWorldMapping) {
  test::TempFolder dir;
  const test::ParticleBlock block(0.05, "density", [](int, double x) { return 1000 + 10 * x; });
  Adapter a = adapter_from_config_text(
      exr_run(dir.path(),
              "name: s, kind: slice, width: 40, height: 20, quantity: density,"
              " shepard: true, plane: {normal: [0, -1, 0]}"),
      test::spaced(block.spacing));
  ASSERT_TRUE(a.execute(3, 0, block.view()).ok());
  const auto& pipeline = dynamic_cast<const InsituPipeline&>(*a.pipeline());
  ASSERT_NE(pipeline.latest_views()[0].field, nullptr);
  const FieldImage field = *pipeline.latest_views()[0].field;
  a.finish();
  std::filesystem::path file;
  for (const auto& e : std::filesystem::directory_iterator(dir / "exr"))
    if (e.path().filename().string().find("_color") == std::string::npos) file = e.path();
  ASSERT_FALSE(file.empty());
  Imf::InputFile in(file.c_str());
  const Imf::Header& h = in.header();
  const Imath::V3d origin = h.typedAttribute<Imf::V3dAttribute>("voxspan:origin").value();
  const Imath::V3d u = h.typedAttribute<Imf::V3dAttribute>("voxspan:u").value();
  const Imath::V3d v = h.typedAttribute<Imf::V3dAttribute>("voxspan:v").value();
  const double width = h.typedAttribute<Imf::DoubleAttribute>("voxspan:width").value();
  EXPECT_EQ(h.typedAttribute<Imf::StringAttribute>("voxspan:quantity").value(), "density");
  EXPECT_NE(h.findTypedAttribute<Imf::StringAttribute>("voxspan:pixel_to_world"), nullptr);
  // The block's centre, seen from -y: +x to the right, z up.
  EXPECT_NEAR(origin.x, 0.5, 1e-6);  // the box of the float spheres
  EXPECT_NEAR(origin.y, 0.25, 1e-6);
  EXPECT_NEAR(u.x, 1, 1e-12);
  EXPECT_NEAR(v.z, 1, 1e-12);
  EXPECT_EQ(width, field.width);
  std::vector<float> value(40 * 20), weight(40 * 20);
  Imf::FrameBuffer frame;
  frame.insert("value", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(value.data()), sizeof(float),
                                   sizeof(float) * 40));
  frame.insert("weight", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(weight.data()),
                                    sizeof(float), sizeof(float) * 40));
  in.setFrameBuffer(frame);
  in.readPixels(0, 19);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 40; ++i) {
      const glm::vec4 f = field.values.at(i, j);
      ASSERT_EQ(value[std::size_t(i + 40 * j)], f.r) << i << " " << j;
      ASSERT_EQ(weight[std::size_t(i + 40 * j)], f.g) << i << " " << j;
    }
  // Inside the block the value is the density at the pixel's world x (Shepard: exact for a
  // linear field away from the edges, to the lattice's symmetry).
  const int i = 20, j = 10;
  const double x = origin.x + ((i + 0.5) / 40 - 0.5) * width * u.x;
  EXPECT_NEAR(value[std::size_t(i + 40 * j)], 1000 + 10 * x, 1e-3);
}

// A volume view with outputs.exr on and no background: the flat picture (premultiplied, alpha =
// 1 - transmittance) and the deep image, one sample per run of fluid along each ray, which
// flattens (over, front to back) into the picture. In one process and on 1 rank alike: the
// MPI job's are in tests/mpi.
TEST(VolumeExr, TheDeepImageFlattensIntoTheFlatPicture) {
  test::TempFolder dir;
  test::ParticleBlock block(0.05, "p", [](int i, double) { return 100.0 * i; });
  block.xyz.insert(block.xyz.end(), {0.5, 0.25, 1.2});  // a drop above: two runs on some rays
  block.values.push_back(1000);
  Adapter a = adapter_from_config_text(
      exr_run(dir.path(),
              "name: v, kind: volume, width: 48, height: 40, quantity: p,"
              " mode: mixed, iso: [{value: 900, opacity: 0.5}], background: none,"
              " legend: false, caption: '', camera: {direction: [0.2, 0.3, -1], up: [0, 1, 0]}"),
      test::spaced(block.spacing));
  ASSERT_TRUE(a.execute(2, 0, block.view()).ok());
  a.finish();
  const test::DeepExr deep = test::read_deep_exr(dir / "exr" / "v_00000002.exr");
  ASSERT_TRUE(deep.has_z && deep.has_z_back && deep.has_rgba);
  const std::vector<float> flat = read_rgba(dir / "exr" / "v_color_00000002.exr", 48, 40);
  double worst = 0;
  std::size_t samples = 0, two_runs = 0;
  for (std::size_t px = 0; px < deep.z.size(); ++px) {
    float composite[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < deep.z[px].size(); ++k) {
      EXPECT_LT(deep.z[px][k], deep.z_back[px][k]);
      if (k > 0) {
        EXPECT_GE(deep.z[px][k], deep.z_back[px][k - 1]);
      }
      const float sample[4] = {deep.r[px][k], deep.g[px][k], deep.b[px][k], deep.a[px][k]};
      const float behind = 1 - composite[3];
      for (int c = 0; c < 4; ++c) composite[c] += behind * sample[c];
      ++samples;
    }
    two_runs += deep.z[px].size() > 1;
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, double(std::abs(composite[c] - flat[4 * px + std::size_t(c)])));
  }
  EXPECT_GT(samples, 400u);
  EXPECT_GT(two_runs, 0u);
  EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace voxspan
