// insitu/views/shared_picture.h - a view's picture handed to the outputs without a copy.
//
// Outputs whose work outlives the step (a PNG or an EXR encoded on the writer's thread) used to
// copy each picture on the solver's thread: 16 bytes a pixel, 33 MB a view at 1920x1080, the part
// of the solver-thread time that grew with pixels. Instead, after each render the pipeline trades
// the view's picture for a free buffer of the view's PicturePool: the storage moves, not the
// pixels, and the buffer the view draws into next is one that held a picture of the same view
// before (no allocation once the pool is warm). A SharedPicture is a counted reference to one
// such buffer, read-only; the buffer goes back to the pool when the last reference is dropped,
// on whichever thread. Every reference must be dropped before its pool goes.
//
// A picture is finished by its first reader (get() or srgb8()): its pixels may still be on their
// way from the GPU (render/pending_picture.h) and its caption is drawn on them then, so that
// neither waits on the solver's thread when a file's job reads first (on the writer's thread).
//
// A picture comes as linear floats or, where only 8-bit readers (PNG files, the live page) take
// it, as 8-bit sRGB converted by the renderer (render/gl/passes/srgb8_pack.h). Either is read as
// both: the other kind is made once, by its first reader, and kept with the picture, so that the
// PNG frame and the live page of one float picture encode it once between them.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "render/float_image.h"
#include "render/pending_picture.h"
#include "render/srgb8_image.h"

namespace voxspan {

class PicturePool;

class SharedPicture {
 public:
  SharedPicture() = default;
  SharedPicture(const SharedPicture& other) noexcept;
  SharedPicture(SharedPicture&& other) noexcept;
  SharedPicture& operator=(SharedPicture other) noexcept;
  ~SharedPicture() { reset(); }

  void reset() noexcept;
  explicit operator bool() const { return entry_ != nullptr; }
  // The finished picture, waiting for it on the first read (any thread). Throws voxspan::Error,
  // naming the view and the step, when its pixels never came.
  // As linear floats: 8-bit precision where it came as 8-bit sRGB (srgb8_to_linear).
  const FloatImage* get() const;
  // As 8-bit sRGB (linear_to_srgb8 of the floats where it came as floats).
  const ImageRGBA8* srgb8() const;
  // Whether it came as 8-bit sRGB.
  bool came_as_srgb8() const;
  // Where the picture is, finished or not: to tell pictures apart without reading them.
  const FloatImage* target() const;
  bool refers_to(const FloatImage& image) const { return target() == &image; }
  const FloatImage& operator*() const { return *get(); }
  const FloatImage* operator->() const { return get(); }

 private:
  friend class PicturePool;
  struct Entry;
  explicit SharedPicture(Entry* entry) : entry_(entry) {}
  Entry* entry_ = nullptr;
};

// What is left to do to a picture before it may be read.
struct PictureFinish {
  PendingPicture* pending = nullptr;  // its pixels on their way; the picture's to release
  std::string_view caption;           // drawn on it once its pixels are there
  std::int64_t step = 0;              // named when the pixels never came
};

class PicturePool {
 public:
  // `expected`: buffers reserved for (the writer's queue plus what the pipeline holds); more are
  // made when that many are all held. `view`: the view named in messages.
  explicit PicturePool(std::size_t expected, std::string view = {});
  ~PicturePool();
  PicturePool(const PicturePool&) = delete;
  PicturePool& operator=(const PicturePool&) = delete;

  // Moves `picture` into a free buffer and gives `picture` that buffer's former storage (empty,
  // or a picture this view drew before: its pixels are stale, its size most likely the same).
  // `finish`: what its first reader does before reading it (nothing by default).
  SharedPicture take(FloatImage& picture, const PictureFinish& finish = {});
  // The same for a picture that came as 8-bit sRGB.
  SharedPicture take(ImageRGBA8& picture, const PictureFinish& finish = {});
  std::size_t buffers() const;
  // Makes free buffers the size and kind of `like` (captions' storage too) until `count` exist:
  // for readers that may hold a picture longer later than in the warm-up (the live page's encoder
  // on a loaded machine), so that the pool does not grow on the solver's thread then.
  void reserve(const FloatImage& like, std::size_t count);
  void reserve(const ImageRGBA8& like, std::size_t count);

 private:
  friend class SharedPicture;
  SharedPicture::Entry& free_entry();
  SharedPicture start(SharedPicture::Entry& entry, bool srgb8, const PictureFinish& finish);
  template <class Image> void reserve_entries(const Image& like, std::size_t count);
  void give_back(SharedPicture::Entry* entry) noexcept;

  const std::string view_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<SharedPicture::Entry>> entries_;
  std::vector<SharedPicture::Entry*> free_;
};

}  // namespace voxspan
