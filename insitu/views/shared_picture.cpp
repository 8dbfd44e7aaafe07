#include "insitu/views/shared_picture.h"

#include <cassert>
#include <utility>

namespace voxspan {

struct SharedPicture::Entry {
  FloatImage image;
  std::atomic<int> holders{0};
  PicturePool* pool = nullptr;
};

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
  return entry_ != nullptr ? &entry_->image : nullptr;
}

PicturePool::PicturePool(std::size_t expected) {
  entries_.reserve(expected);
  free_.reserve(expected);
}

PicturePool::~PicturePool() {
  assert(free_.size() == entries_.size() && "a SharedPicture outlived its pool");
}

SharedPicture PicturePool::take(FloatImage& picture) {
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
  entry->holders.store(1, std::memory_order_relaxed);
  return SharedPicture(entry);
}

std::size_t PicturePool::buffers() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

void PicturePool::give_back(SharedPicture::Entry* entry) noexcept {
  std::lock_guard lock(mutex_);
  free_.push_back(entry);
}

}  // namespace voxspan
