// The picture read back without waiting (render/gl/picture_readback.h): the pixels that land are
// the synchronous read's bit for bit, read on another thread, two reads in flight at once and
// read in either order; the host buffers are made once (two: double buffering) and reused; read
// as 8-bit sRGB, the float picture encoded.
#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "render/backend.h"
#include "render/gl/gpu_recorder.h"
#include "render/gl/objects.h"
#include "render/gl/picture_readback.h"
#include "render/srgb8_image.h"
#include "render/stat_names.h"
#include "tests/render/gl/shading_fixture.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// A floor at depth 5 with a raised block on the left third: light, shadow and edges to tell
// the modes apart.
SpanImage block_scene() {
  std::vector<std::vector<Span>> columns(48 * 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x)
      columns[std::size_t(x) + 48 * std::size_t(y)].push_back({x < 16 ? 4.5f : 5.0f, 6.0f});
  return test::hand_made(48, 32, columns);
}

TEST(PictureReadback, ThePixelsThatLandAreTheSynchronousReadsOnAnyThread) {
  const gl::Context& context = test::context();
  const std::unique_ptr<SurfaceRenderer> renderer =
      make_surface_renderer(RenderBackend::gl, test::shaders(), std::size_t(64) << 20);
  gl::GpuRecorder recorder(context.has_gpu_timers());
  const SpanImage spans = block_scene();
  renderer->use_spans(spans, pass::upload, recorder);
  const SurfaceOptions surfaces;
  const ShadeOptions opaque = test::test_shading(ShadeMode::opaque);
  const ShadeOptions translucent = test::test_shading(ShadeMode::translucent);
  FloatImage want_opaque, want_translucent;
  renderer->shade(surfaces, opaque, recorder, want_opaque);
  renderer->shade(surfaces, translucent, recorder, want_translucent);
  ASSERT_NE(want_opaque.rgba, want_translucent.rgba);
  for (int round = 0; round < 3; ++round) {
    FloatImage a, b, got_a, got_b;
    PendingPicture* read_a =
        renderer->shade_later(surfaces, opaque, recorder, a, ReadLater::always);
    PendingPicture* read_b =
        renderer->shade_later(surfaces, translucent, recorder, b, ReadLater::always);
    ASSERT_NE(read_a, nullptr);  // llvmpipe has EGL fences
    ASSERT_NE(read_b, nullptr);
    EXPECT_EQ(a.width, 48);  // sized for the pixels to come
    EXPECT_EQ(a.rgba.size(), want_opaque.rgba.size());
    std::thread writer([&] {
      (round % 2 == 0 ? read_b : read_a)->copy_into(round % 2 == 0 ? got_b : got_a);
      (round % 2 == 0 ? read_a : read_b)->copy_into(round % 2 == 0 ? got_a : got_b);
    });
    writer.join();
    read_a->release();
    read_b->release();
    EXPECT_EQ(got_a.rgba, want_opaque.rgba) << "round " << round;
    EXPECT_EQ(got_b.rgba, want_translucent.rgba) << "round " << round;
    EXPECT_EQ(got_a.width, 48);
    EXPECT_EQ(got_a.height, 32);
  }
  // Where it is not asked for, or on llvmpipe by default (the copy costs more than the read),
  // the picture is read at once.
  FloatImage now;
  EXPECT_EQ(renderer->shade_later(surfaces, opaque, recorder, now, ReadLater::never), nullptr);
  EXPECT_EQ(now.rgba, want_opaque.rgba);
  if (!gl::current_staging()->in_use()) {  // a software renderer
    EXPECT_EQ(renderer->shade_later(surfaces, opaque, recorder, now, ReadLater::on_gpu), nullptr);
  }
  recorder.collect();
}

TEST(PictureReadback, TwoBuffersServeReadsThatAreReleasedBeforeTheNextButOne) {
  test::context();
  gl::PictureReadback readback;
  ASSERT_TRUE(readback.available());
  GpuFloatImage image;
  image.resize(8, 4);
  std::vector<float> pixels(8 * 4 * 4);
  PendingPicture* previous = nullptr;
  for (int frame = 0; frame < 10; ++frame) {
    std::fill(pixels.begin(), pixels.end(), float(frame));
    glNamedBufferSubData(image.buffer().id(), 0, GLsizeiptr(pixels.size() * sizeof(float)),
                         pixels.data());
    PendingPicture& read = readback.issue(image);
    if (previous != nullptr) {  // the frame before, read while this one is in flight
      FloatImage got;
      previous->copy_into(got);
      previous->release();
      EXPECT_EQ(got.rgba, std::vector<float>(pixels.size(), float(frame - 1)));
    }
    previous = &read;
  }
  previous->release();
  EXPECT_EQ(readback.buffers(), 2u);
}

// Read as 8-bit sRGB (render/gl/passes/srgb8_pack.h), at once or later, the picture is the
// float one encoded on the host, bit for bit; a read is copied only as the kind it was issued.
TEST(PictureReadback, ThePictureReadAsBytesIsTheFloatOneEncoded) {
  const gl::Context& context = test::context();
  const std::unique_ptr<SurfaceRenderer> renderer =
      make_surface_renderer(RenderBackend::gl, test::shaders(), std::size_t(64) << 20);
  EXPECT_TRUE(renderer->packs_srgb8(ReadLater::always));
  gl::GpuRecorder recorder(context.has_gpu_timers());
  const SpanImage spans = block_scene();
  renderer->use_spans(spans, pass::upload, recorder);
  const SurfaceOptions surfaces;
  for (const ShadeMode mode : {ShadeMode::opaque, ShadeMode::translucent}) {
    const ShadeOptions shading = test::test_shading(mode);
    FloatImage linear;
    renderer->shade(surfaces, shading, recorder, linear);
    const ImageRGBA8 want = linear_to_srgb8(linear.rgba, linear.width, linear.height);
    ImageRGBA8 now, later;
    EXPECT_EQ(renderer->shade_srgb8_later(surfaces, shading, recorder, now, ReadLater::never),
              nullptr);
    EXPECT_EQ(now.pixels, want.pixels);
    PendingPicture* read =
        renderer->shade_srgb8_later(surfaces, shading, recorder, later, ReadLater::always);
    ASSERT_NE(read, nullptr);    // llvmpipe has EGL fences
    EXPECT_EQ(later.width, 48);  // sized for the pixels to come
    FloatImage wrong_kind;
    EXPECT_THROW(read->copy_into(wrong_kind), Error);
    read->copy_into(later);
    read->release();
    EXPECT_EQ(later.pixels, want.pixels);
    EXPECT_EQ(later.height, 32);
  }
  recorder.collect();
}

}  // namespace
}  // namespace voxspan
