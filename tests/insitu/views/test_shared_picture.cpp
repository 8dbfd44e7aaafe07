// A view's picture handed to the outputs without a copy (insitu/views/shared_picture.h): the
// pixels move with their storage, a held picture stays as it was while the view draws the next,
// and buffers come back to the view (no allocation once warm).
#include "insitu/views/shared_picture.h"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "insitu/views/view_products.h"

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

}  // namespace
}  // namespace voxspan
