// A view's picture handed to the outputs without a copy (insitu/views/shared_picture.h): the
// pixels move with their storage, a held picture stays as it was while the view draws the next,
// and buffers come back to the view (no allocation once warm); a picture whose pixels are on
// their way is finished by its first reader, on any thread, and a read that fails is said with
// its view and step to every reader.
#include "insitu/views/shared_picture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <vector>

#include "insitu/outputs/writer/background_writer.h"
#include "insitu/views/legend.h"
#include "insitu/views/view_products.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

FloatImage filled(int w, int h, float value) {
  FloatImage image(w, h);
  std::fill(image.rgba.begin(), image.rgba.end(), value);
  return image;
}

TEST(SharedPicture, TakeMovesThePixelsNotACopy) {
  PicturePool pool(4);
  FloatImage view = filled(8, 4, 0.5f);
  const float* pixels = view.rgba.data();
  const SharedPicture kept = pool.take(view);
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->rgba.data(), pixels);
  EXPECT_EQ(kept->width, 8);
  EXPECT_EQ(kept->height, 4);
  EXPECT_TRUE(view.rgba.empty());  // a fresh buffer: the view sizes it
}

// The buffers made ahead for lagging readers (the live page's) come sized: a view that takes
// one draws into it without allocating; asked again, the pool makes none.
TEST(SharedPicture, ReservedBuffersComeSizedAndAreMadeOnce) {
  PicturePool pool(4);
  pool.reserve(filled(8, 4, 0.0f), 3);
  EXPECT_EQ(pool.buffers(), 3u);
  pool.reserve(filled(8, 4, 0.0f), 3);
  EXPECT_EQ(pool.buffers(), 3u);
  FloatImage view = filled(8, 4, 0.5f);
  const SharedPicture first = pool.take(view), second = pool.take(view);
  EXPECT_EQ(view.rgba.size(), 8u * 4u * 4u);  // a reserved buffer, not a fresh one
  EXPECT_EQ(view.width, 8);
  EXPECT_EQ(pool.buffers(), 3u);
}

TEST(SharedPicture, ABufferComesBackToTheViewOnceReleased) {
  PicturePool pool(4);
  SharedPicture latest;
  FloatImage view = filled(8, 4, 0.0f);
  for (int step = 0; step < 100; ++step) {
    view.rgba.resize(8 * 4 * 4);  // what a view does: no allocation once its buffer is sized
    std::fill(view.rgba.begin(), view.rgba.end(), float(step));
    latest.reset();
    latest = pool.take(view);
    EXPECT_EQ(latest->rgba.front(), float(step));
  }
  EXPECT_EQ(pool.buffers(), 1u);  // the pipeline's order: release the latest, then take
}

TEST(SharedPicture, AHeldPictureStaysAsItWasWhileTheViewDrawsOn) {
  PicturePool pool(4);
  FloatImage view = filled(4, 4, 1.0f);
  const SharedPicture first = pool.take(view);
  SharedPicture copy = first;  // an output's job
  for (int step = 2; step < 6; ++step) {
    view = filled(4, 4, float(step));
    const SharedPicture next = pool.take(view);
    EXPECT_EQ(next->rgba.front(), float(step));
  }
  for (float v : copy->rgba) ASSERT_EQ(v, 1.0f);
  EXPECT_EQ(pool.buffers(), 2u);  // the held one and one cycling
}

TEST(SharedPicture, JobsOnAnotherThreadGiveTheBuffersBack) {
  PicturePool pool(8);
  FloatImage view(16, 16);
  std::vector<SharedPicture> handed;
  for (int step = 0; step < 6; ++step) {
    std::fill(view.rgba.begin(), view.rgba.end(), float(step));
    handed.push_back(pool.take(view));
    view.rgba.resize(16 * 16 * 4);
  }
  std::thread writer([moved = std::move(handed)]() mutable {
    for (std::size_t i = 0; i < moved.size(); ++i) EXPECT_EQ(moved[i]->rgba[7], float(i));
    moved.clear();
  });
  writer.join();
  const std::size_t made = pool.buffers();
  for (int step = 0; step < 50; ++step) {
    view.rgba.resize(16 * 16 * 4);
    const SharedPicture p = pool.take(view);
  }
  EXPECT_EQ(pool.buffers(), made);  // all came back: nothing new
}

TEST(KeptImage, KeepsAViewsPictureByReferenceAndAnyOtherImageAsACopy) {
  PicturePool pool(2);
  FloatImage view = filled(4, 2, 0.25f);
  const SharedPicture picture = pool.take(view);
  KeptImage kept;
  kept.keep(*picture, &picture);
  EXPECT_EQ(&kept.image(), picture.get());
  const FloatImage depth = filled(4, 2, 3.0f);
  kept.keep(depth, &picture);  // not the shared picture: copied
  EXPECT_NE(&kept.image(), &depth);
  EXPECT_EQ(kept.image().rgba, depth.rgba);
  kept.keep(*picture, nullptr);  // no reference given: copied
  EXPECT_EQ(kept.image().rgba, picture->rgba);
  EXPECT_NE(kept.image().rgba.data(), picture->rgba.data());
}

// A read-back that lands `value` everywhere (or fails), counting its copies and releases.
struct FakeRead final : PendingPicture {
  int width = 4, height = 2;
  float value = 0.75f;
  bool fails = false;
  int copies = 0, releases = 0;
  void copy_into(FloatImage& out) override {
    ++copies;
    if (fails) throw std::runtime_error("the fence was lost");
    out = FloatImage(width, height);
    std::fill(out.rgba.begin(), out.rgba.end(), value);
  }
  void copy_into(ImageRGBA8& out) override {
    ++copies;
    if (fails) throw std::runtime_error("the fence was lost");
    const std::uint8_t byte = linear_to_srgb8(value);
    out = {width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4, byte)};
    for (std::size_t i = 3; i < out.pixels.size(); i += 4) out.pixels[i] = linear_to_unorm8(value);
  }
  void release() noexcept override { ++releases; }
};

TEST(SharedPicture, PixelsOnTheirWayLandAtTheFirstReadOnAnyThreadWithTheCaption) {
  PicturePool pool(2, "main");
  FakeRead read;
  read.width = 64, read.height = 32;
  FloatImage view(64, 32);  // sized by the renderer, not yet filled
  const SharedPicture picture = pool.take(view, {&read, "step 7", 7});
  EXPECT_EQ(read.copies, 0);  // nothing waited for on the taking thread
  std::thread writer([&] { EXPECT_EQ(picture->width, 64); });
  writer.join();
  EXPECT_EQ(read.copies, 1);
  EXPECT_EQ(read.releases, 1);
  picture.get();  // finished once
  EXPECT_EQ(read.copies, 1);
  FloatImage expected(64, 32);
  std::fill(expected.rgba.begin(), expected.rgba.end(), 0.75f);
  draw_caption(expected, "step 7");
  EXPECT_NE(expected.rgba, std::vector<float>(expected.rgba.size(), 0.75f));  // text drawn
  EXPECT_EQ(picture->rgba, expected.rgba);
}

// A picture that came as 8-bit sRGB (render/gl/passes/srgb8_pack.h) with a caption is the float
// picture with its caption, encoded: the caption's bytes too (the largest difference: none).
// Each kind is made from the other once, by its first reader.
TEST(SharedPicture, APictureThatCameAs8BitIsTheFloatOneEncodedCaptionIncluded) {
  PicturePool pool(2, "main");
  FakeRead read;
  read.width = 64, read.height = 32;
  ImageRGBA8 view{64, 32, std::vector<std::uint8_t>(64 * 32 * 4)};
  const SharedPicture picture = pool.take(view, {&read, "step 7", 7});
  EXPECT_TRUE(picture.came_as_srgb8());
  FloatImage expected(64, 32);
  std::fill(expected.rgba.begin(), expected.rgba.end(), 0.75f);
  draw_caption(expected, "step 7");
  const ImageRGBA8 want = linear_to_srgb8(expected.rgba, 64, 32);
  const ImageRGBA8* bytes = picture.srgb8();
  ASSERT_NE(bytes, nullptr);
  int largest = 0;
  for (std::size_t i = 0; i < want.pixels.size(); ++i)
    largest = std::max(largest, std::abs(int(bytes->pixels[i]) - int(want.pixels[i])));
  EXPECT_EQ(largest, 0);
  // Its floats are those bytes decoded: encoded again, the same bytes.
  EXPECT_EQ(linear_to_srgb8(picture->rgba, 64, 32).pixels, want.pixels);
  EXPECT_EQ(picture.get(), picture.get());  // decoded once
  EXPECT_EQ(read.copies, 1);
  // A float picture's bytes, made once for every 8-bit reader.
  FloatImage linear = expected;
  const SharedPicture floats = pool.take(linear);
  EXPECT_FALSE(floats.came_as_srgb8());
  EXPECT_EQ(floats.srgb8()->pixels, want.pixels);
  EXPECT_EQ(floats.srgb8(), floats.srgb8());
}

TEST(SharedPicture, AReadNeverMadeGoesBackWhenThePictureIsDropped) {
  PicturePool pool(2, "main");
  FakeRead read;
  FloatImage view(4, 2);
  SharedPicture picture = pool.take(view, {&read, {}, 3});
  SharedPicture job = picture;
  picture.reset();
  EXPECT_EQ(read.releases, 0);  // a job still holds it
  job.reset();
  EXPECT_EQ(read.copies, 0);
  EXPECT_EQ(read.releases, 1);
}

TEST(SharedPicture, AFailedReadIsSaidWithItsViewAndStepToEveryReader) {
  PicturePool pool(2, "main");
  FakeRead read;
  read.fails = true;
  FloatImage view(4, 2);
  const SharedPicture picture = pool.take(view, {&read, {}, 120});
  // As an output's job meets it on the writer's thread: a counted failure with the message.
  BackgroundWriter writer(4, QueuePolicy::wait);
  for (int job = 0; job < 2; ++job)
    writer.submit("frame main_00000120.png", [picture] { (void)picture->width; });
  writer.drain();
  const WriterStats stats = writer.stats();
  EXPECT_EQ(stats.failed, 2u);
  EXPECT_NE(stats.first_error.find("view main, step 120: reading the picture back failed: the "
                                   "fence was lost"),
            std::string::npos)
      << stats.first_error;
  EXPECT_THROW(picture.get(), Error);
  EXPECT_EQ(read.copies, 1);  // tried once, said to each
  EXPECT_EQ(read.releases, 1);
}

}  // namespace
}  // namespace voxspan
