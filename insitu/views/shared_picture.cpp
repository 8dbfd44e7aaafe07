#include "insitu/views/shared_picture.h"

#include <cassert>
#include <utility>

#include "insitu/views/legend.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {
constexpr std::size_t kCaptionRoom = 128;  // a caption's storage made ahead (reserve)
}  // namespace

struct SharedPicture::Entry {
  FloatImage image;
  std::atomic<int> holders{0};
  PicturePool* pool = nullptr;
  // What take() left to do (PictureFinish), done once under the mutex by the first reader.
  std::atomic<bool> finished{true};
  std::mutex finishing;
  PendingPicture* pending = nullptr;
  std::string caption;
  std::int64_t step = 0;
  std::string failure;  // why the pixels never came; said to every reader

  void finish(const std::string& view);
  void drop_pending() noexcept {
    if (pending != nullptr) std::exchange(pending, nullptr)->release();
  }
};

void SharedPicture::Entry::finish(const std::string& view) {
  std::lock_guard lock(finishing);
  if (finished.load(std::memory_order_relaxed)) return;
  if (failure.empty()) {
    try {
      if (pending != nullptr) pending->copy_into(image);
    } catch (const std::exception& e) {
      failure = "view " + view + ", step " + std::to_string(step) +
                ": reading the picture back failed: " + e.what();
    }
    drop_pending();
  }
  if (!failure.empty()) throw Error(failure);
  if (!caption.empty()) draw_caption(image, caption);
  finished.store(true, std::memory_order_release);
}

SharedPicture::SharedPicture(const SharedPicture& other) noexcept : entry_(other.entry_) {
  if (entry_ != nullptr) entry_->holders.fetch_add(1, std::memory_order_relaxed);
}

SharedPicture::SharedPicture(SharedPicture&& other) noexcept
    : entry_(std::exchange(other.entry_, nullptr)) {}

SharedPicture& SharedPicture::operator=(SharedPicture other) noexcept {
  std::swap(entry_, other.entry_);
  return *this;
}

void SharedPicture::reset() noexcept {
  Entry* entry = std::exchange(entry_, nullptr);
  // acq_rel: the last holder's reads of the pixels happen before the view's next writes.
  if (entry != nullptr && entry->holders.fetch_sub(1, std::memory_order_acq_rel) == 1)
    entry->pool->give_back(entry);
}

const FloatImage* SharedPicture::get() const {
  if (entry_ == nullptr) return nullptr;
  if (!entry_->finished.load(std::memory_order_acquire)) entry_->finish(entry_->pool->view_);
  return &entry_->image;
}

const FloatImage* SharedPicture::target() const {
  return entry_ != nullptr ? &entry_->image : nullptr;
}

PicturePool::PicturePool(std::size_t expected, std::string view) : view_(std::move(view)) {
  entries_.reserve(expected);
  free_.reserve(expected);
}

PicturePool::~PicturePool() {
  assert(free_.size() == entries_.size() && "a SharedPicture outlived its pool");
}

SharedPicture PicturePool::take(FloatImage& picture, const PictureFinish& finish) {
  SharedPicture::Entry* entry = nullptr;
  {
    std::lock_guard lock(mutex_);
    if (!free_.empty()) {
      entry = free_.back();
      free_.pop_back();
    } else {
      entries_.push_back(std::make_unique<SharedPicture::Entry>());
      entry = entries_.back().get();
      entry->pool = this;
      // Room for every buffer to be free at once: give_back never allocates.
      free_.reserve(entries_.capacity());
    }
  }
  std::swap(entry->image, picture);
  entry->pending = finish.pending;
  entry->caption.assign(finish.caption);  // its storage kept: no allocation once long enough
  entry->step = finish.step;
  entry->failure.clear();
  entry->finished.store(finish.pending == nullptr && finish.caption.empty(),
                        std::memory_order_relaxed);
  entry->holders.store(1, std::memory_order_relaxed);
  return SharedPicture(entry);
}

void PicturePool::reserve(const FloatImage& like, std::size_t count) {
  std::lock_guard lock(mutex_);
  while (entries_.size() < count) {
    entries_.push_back(std::make_unique<SharedPicture::Entry>());
    SharedPicture::Entry* entry = entries_.back().get();
    entry->pool = this;
    entry->image = FloatImage(like.width, like.height);
    entry->caption.reserve(kCaptionRoom);
    free_.reserve(entries_.capacity());
    free_.push_back(entry);
  }
}

std::size_t PicturePool::buffers() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

void PicturePool::give_back(SharedPicture::Entry* entry) noexcept {
  entry->drop_pending();  // never read: its read-back buffer goes back to the renderer
  std::lock_guard lock(mutex_);
  free_.push_back(entry);
}

}  // namespace voxspan
