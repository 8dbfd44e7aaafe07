// A GL run's pictures read back later (renderer.readback: later, render/gl/picture_readback.h)
// through the runtime: each frame is the one a run that waits for its pictures writes, of its
// own step (the particles move from step to step) with its caption, whether the writer's
// thread finished the picture or the caller asked for it (InsituPipeline::latest_views()); the
// last step's frames are there once finish() returns.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "insitu/outputs/formats/png_image.h"
#include "tests/support/temp_folder.h"
#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

constexpr int kSteps = 3;
constexpr std::array<const char*, 2> kViews = {"front", "side"};

// `exr`: an EXR output too, which takes the pictures' floats.
std::string config(const std::filesystem::path& folder, const std::string& readback,
                   bool exr = false) {
  return "output_folder: " + folder.string() + "\nrenderer: {backend: gl, readback: " + readback +
         "}" + R"(
trigger: {every_steps: 1}
views:
  - {name: front, width: 64, height: 40, caption: "{view} {step}"}
  - {name: side, width: 40, height: 40, shading: translucent, camera: {direction: [1, 0.3, -0.4]}}
outputs:
  png: {enabled: true, folder: frames, compression_level: 1}
  stats: {enabled: false}
  exr: {enabled: )" +
         (exr ? "true" : "false") + R"(, folder: exr, trigger: {every_steps: 1}}
writer: {fsync: false}
)";
}

// What a run gave the caller after each step, in the views' order.
struct Asked {
  std::vector<FloatImage> pictures;  // with `ask`, else none
  std::vector<bool> came_as_srgb8;
};

// Runs the steps over a block that moves along x.
Asked run(const std::filesystem::path& folder, const std::string& readback, bool ask,
          bool exr = false) {
  test::ParticleBlock block(0.05, "density", [](int, double) { return 1000.0; });
  Adapter a = adapter_from_config_text(config(folder, readback, exr), test::spaced(block.spacing));
  Asked asked;
  for (int step = 1; step <= kSteps; ++step) {
    for (std::size_t i = 0; i < block.xyz.size(); i += 3) block.xyz[i] += 0.02;
    const Status s = a.execute(step, 0.1 * step, block.view());
    EXPECT_TRUE(s.ok()) << s.message;
    const InsituPipeline& pipeline = dynamic_cast<const InsituPipeline&>(*a.pipeline());
    if (!ask) {  // the views' results as the outputs had them: pictures not yet read
      for (const ViewResult& v : std::span(pipeline.latest_views().data(), kViews.size()))
        asked.came_as_srgb8.push_back(v.shared_picture->came_as_srgb8());
      continue;
    }
    for (const ViewResult& v : pipeline.latest_views())
      asked.pictures.push_back(v.picture != nullptr ? *v.picture : FloatImage());
  }
  a.finish();
  return asked;
}

std::filesystem::path frame(const std::filesystem::path& folder, const char* view, int step) {
  return folder / "frames" / step_file_name(view, step, "png");
}

TEST(AsyncPictures, EachFrameIsTheOneReadAtOnceAndTheLastIsWrittenByFinish) {
  test::TempFolder dir;
  run(dir / "waited", "wait", false);    // read at once, on the solver's thread
  run(dir / "written", "later", false);  // every picture finished by the writer's jobs
  const std::vector<FloatImage> asked = run(dir / "asked", "later", true).pictures;
  ASSERT_EQ(asked.size(), kSteps * kViews.size());
  for (int step = 1; step <= kSteps; ++step)
    for (std::size_t v = 0; v < kViews.size(); ++v) {
      const FloatImage& picture = asked[std::size_t(step - 1) * kViews.size() + v];
      ASSERT_EQ(picture.rgba.size(), std::size_t(picture.width) * picture.height * 4);
      const ImageRGBA8 want = linear_to_srgb8(picture.rgba, picture.width, picture.height);
      for (const char* run : {"waited", "written", "asked"}) {
        const std::filesystem::path file = frame(dir / run, kViews[v], step);
        ASSERT_TRUE(std::filesystem::exists(file)) << file;
        EXPECT_EQ(read_png(file).pixels, want.pixels) << file;
      }
    }
  // The steps differ (the block moved): a frame of the step before would not pass.
  EXPECT_NE(read_png(frame(dir / "written", "side", kSteps)).pixels,
            read_png(frame(dir / "written", "side", kSteps - 1)).pixels);
}

// Where PNG files are all that take the pictures, the GL renderer makes them 8-bit sRGB on the
// GPU (with `later` on llvmpipe too); with an EXR output due they stay floats for it
// (ViewNeeds::linear_picture). The frames are the same pixels either way, and read at once (8-bit
// on a GPU, floats on llvmpipe).
TEST(AsyncPictures, FramesMadeAs8BitOnTheGpuAreTheFloatPicturesEncoded) {
  test::TempFolder dir;
  const Asked floats = run(dir / "floats", "later", false, /*exr=*/true);
  const Asked later = run(dir / "later", "later", false);
  const Asked waited = run(dir / "waited", "wait", false);
  EXPECT_EQ(floats.came_as_srgb8, std::vector<bool>(kSteps * kViews.size(), false));
  EXPECT_EQ(later.came_as_srgb8, std::vector<bool>(kSteps * kViews.size(), true));
  for (int step = 1; step <= kSteps; ++step)
    for (const char* view : kViews) {
      const ImageRGBA8 want = read_png(frame(dir / "floats", view, step));
      EXPECT_EQ(read_png(frame(dir / "later", view, step)).pixels, want.pixels) << view << step;
      EXPECT_EQ(read_png(frame(dir / "waited", view, step)).pixels, want.pixels) << view << step;
      EXPECT_TRUE(std::filesystem::exists(
          dir / "floats" / "exr" / step_file_name(std::string(view) + "_color", step, "exr")));
    }
}

}  // namespace
}  // namespace voxspan
