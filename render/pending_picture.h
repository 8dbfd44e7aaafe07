// render/pending_picture.h - a picture on its way from the GPU to host memory: the read is
// issued with the frame and lands while the solver goes on (render/gl/picture_readback.h).
// Whoever needs the pixels first waits for them, on any thread, without a GL call: the writer's
// thread for a file, the solver's only when it asks for the picture itself.
#pragma once

#include "render/float_image.h"
#include "render/srgb8_image.h"

namespace voxspan {

class PendingPicture {
 public:
  virtual ~PendingPicture() = default;
  // Waits until the pixels have landed, then copies them into `out` (resized to the picture:
  // no allocation when it held a picture this size). Throws voxspan::Error when the read failed.
  virtual void copy_into(FloatImage& out) = 0;
  // The same for a picture read as 8-bit sRGB (render/gl/passes/srgb8_pack.h). Each read is
  // copied into the kind it was issued as; the other throws voxspan::Error.
  virtual void copy_into(ImageRGBA8& out) = 0;
  // Done with it, read or not: the renderer may reuse its memory. Any thread, once.
  virtual void release() noexcept = 0;
};

}  // namespace voxspan
