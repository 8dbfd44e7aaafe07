// render/gl/picture_readback.h - the shaded picture read back without waiting for the GPU.
//
// A synchronous read waits for every pass of the frame to finish (22.9 ms of the solver's time
// per render step with two 1080p views on an NVIDIA H200: docs/benchmarks.md). Instead issue()
// copies the picture's buffer on the GPU into a persistently mapped buffer in host memory (the
// role a pixel-pack buffer plays for a texture), puts an EGL fence behind the copy, flushes and
// returns. The pixels are read through the PendingPicture it gives (render/pending_picture.h):
// its copy_into() waits on the fence with eglClientWaitSync, which any thread may call with no
// GL context, and copies from the mapping; release() frees the buffer for a later frame.
//
// Buffers: one per picture in flight, made when every one is held (two when the pictures are
// read before the next frame's: double buffering); none is made once the writer keeps pace.
// The GL calls (issue, the destructor) belong to the context's thread; copy_into and release to
// any thread. Where EGL has no fences (EGL_KHR_fence_sync), available() is false: read
// synchronously instead.
#pragma once

#include <memory>
#include <vector>

#include "render/gl/gpu_float_image.h"
#include "render/pending_picture.h"

namespace voxspan::gl {

class PictureReadback {
 public:
  PictureReadback();  // with the context current
  ~PictureReadback();
  PictureReadback(const PictureReadback&) = delete;
  PictureReadback& operator=(const PictureReadback&) = delete;

  bool available() const { return fences_ != nullptr; }
  // Issues the read of `image` (the shade pass's writes made visible first). The read is the
  // caller's until it calls release(). Throws voxspan::Error when no buffer or fence can be made.
  PendingPicture& issue(const GpuFloatImage& image);
  // The same for a picture packed as 8-bit sRGB in `packed` (4 bytes a pixel, its writes made
  // visible: render/gl/passes/srgb8_pack.h): a quarter of the bytes.
  PendingPicture& issue_srgb8(const gl::Buffer& packed, int width, int height);
  // Buffers made so far (the pictures once in flight together).
  std::size_t buffers() const { return slots_.size(); }

 private:
  class Slot;
  struct Fences;
  Slot& free_slot();
  PendingPicture& issue(const gl::Buffer& source, int width, int height, int pixel_bytes);

  std::unique_ptr<const Fences> fences_;  // null: EGL has none here
  std::vector<std::unique_ptr<Slot>> slots_;
};

}  // namespace voxspan::gl
