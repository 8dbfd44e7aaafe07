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
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include "render/float_image.h"

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
  const FloatImage* get() const;
  const FloatImage& operator*() const { return *get(); }
  const FloatImage* operator->() const { return get(); }

 private:
  friend class PicturePool;
  struct Entry;
  explicit SharedPicture(Entry* entry) : entry_(entry) {}
  Entry* entry_ = nullptr;
};

class PicturePool {
 public:
  // `expected`: buffers reserved for (the writer's queue plus what the pipeline holds); more are
  // made when that many are all held.
  explicit PicturePool(std::size_t expected);
  ~PicturePool();
  PicturePool(const PicturePool&) = delete;
  PicturePool& operator=(const PicturePool&) = delete;

  // Moves `picture` into a free buffer and gives `picture` that buffer's former storage (empty,
  // or a picture this view drew before: its pixels are stale, its size most likely the same).
  SharedPicture take(FloatImage& picture);
  std::size_t buffers() const;

 private:
  friend class SharedPicture;
  void give_back(SharedPicture::Entry* entry) noexcept;

  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<SharedPicture::Entry>> entries_;
  std::vector<SharedPicture::Entry*> free_;
};

}  // namespace voxspan
