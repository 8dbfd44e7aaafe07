#include "insitu/views/shared_picture.h"

#include <cassert>
#include <type_traits>
#include <utility>

#include "insitu/views/legend.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {
constexpr std::size_t kCaptionRoom = 128;  // a caption's storage made ahead (reserve)

void convert(const ImageRGBA8& from, FloatImage& to) { srgb8_to_linear(from, to); }
void convert(const FloatImage& from, ImageRGBA8& to) { linear_to_srgb8(from, to); }
}  // namespace

struct SharedPicture::Entry {
  // The picture of either kind: its storage, and whether it holds this picture yet.
  template <class Image> struct Held {
    Image image;
    std::atomic<bool> there{false};
  };
  Held<FloatImage> linear;
  Held<ImageRGBA8> srgb8;
  bool came_as_srgb8 = false;
  std::atomic<int> holders{0};
  PicturePool* pool = nullptr;
  // What take() left to do (PictureFinish), done once under the mutex by the first reader; the
  // kind it did not come as is made under it too.
  std::atomic<bool> finished{true};
  std::mutex finishing;
  PendingPicture* pending = nullptr;
  std::string caption;
  std::int64_t step = 0;
  std::string failure;  // why the pixels never came; said to every reader

  void finish(const std::string& view);
  template <class Image> void finish_as(Held<Image>& held);
  template <class Image, class From> const Image& converted(Held<Image>& to, const From& from);
  void drop_pending() noexcept {
    if (pending != nullptr) std::exchange(pending, nullptr)->release();
  }
};

void SharedPicture::Entry::finish(const std::string& view) {
  std::lock_guard lock(finishing);
  if (finished.load(std::memory_order_relaxed)) return;
  if (failure.empty()) {
    try {
      if (came_as_srgb8) finish_as(srgb8);
      else finish_as(linear);
    } catch (const std::exception& e) {
      failure = "view " + view + ", step " + std::to_string(step) +
                ": reading the picture back failed: " + e.what();
    }
    drop_pending();
  }
  if (!failure.empty()) throw Error(failure);
  finished.store(true, std::memory_order_release);
}

// The pixels copied in where they are on their way, the caption drawn (under `finishing`).
template <class Image> void SharedPicture::Entry::finish_as(Held<Image>& held) {
  if (pending != nullptr) pending->copy_into(held.image);
  if (!caption.empty()) draw_caption(held.image, caption);
  held.there.store(true, std::memory_order_release);
}

// The kind it did not come as, made once from the finished one.
template <class Image, class From>
const Image& SharedPicture::Entry::converted(Held<Image>& to, const From& from) {
  if (!to.there.load(std::memory_order_acquire)) {
    std::lock_guard lock(finishing);
    if (!to.there.load(std::memory_order_relaxed)) {
      convert(from, to.image);
      to.there.store(true, std::memory_order_release);
    }
  }
  return to.image;
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
  return &entry_->converted(entry_->linear, entry_->srgb8.image);
}

const ImageRGBA8* SharedPicture::srgb8() const {
  if (entry_ == nullptr) return nullptr;
  if (!entry_->finished.load(std::memory_order_acquire)) entry_->finish(entry_->pool->view_);
  return &entry_->converted(entry_->srgb8, entry_->linear.image);
}

bool SharedPicture::came_as_srgb8() const { return entry_ != nullptr && entry_->came_as_srgb8; }

const FloatImage* SharedPicture::target() const {
  return entry_ != nullptr ? &entry_->linear.image : nullptr;
}

PicturePool::PicturePool(std::size_t expected, std::string view) : view_(std::move(view)) {
  entries_.reserve(expected);
  free_.reserve(expected);
}

PicturePool::~PicturePool() {
  assert(free_.size() == entries_.size() && "a SharedPicture outlived its pool");
}

SharedPicture::Entry& PicturePool::free_entry() {
  std::lock_guard lock(mutex_);
  if (!free_.empty()) {
    SharedPicture::Entry* entry = free_.back();
    free_.pop_back();
    return *entry;
  }
  entries_.push_back(std::make_unique<SharedPicture::Entry>());
  SharedPicture::Entry& entry = *entries_.back();
  entry.pool = this;
  // Room for every buffer to be free at once: give_back never allocates.
  free_.reserve(entries_.capacity());
  return entry;
}

SharedPicture PicturePool::take(FloatImage& picture, const PictureFinish& finish) {
  SharedPicture::Entry& entry = free_entry();
  std::swap(entry.linear.image, picture);
  return start(entry, false, finish);
}

SharedPicture PicturePool::take(ImageRGBA8& picture, const PictureFinish& finish) {
  SharedPicture::Entry& entry = free_entry();
  std::swap(entry.srgb8.image, picture);
  return start(entry, true, finish);
}

// The entry holding a picture just traded in, of the kind `srgb8` says, to be finished so.
SharedPicture PicturePool::start(SharedPicture::Entry& entry, bool srgb8,
                                 const PictureFinish& finish) {
  const bool finished = finish.pending == nullptr && finish.caption.empty();
  entry.came_as_srgb8 = srgb8;
  entry.linear.there.store(!srgb8 && finished, std::memory_order_relaxed);
  entry.srgb8.there.store(srgb8 && finished, std::memory_order_relaxed);
  entry.pending = finish.pending;
  entry.caption.assign(finish.caption);  // its storage kept: no allocation once long enough
  entry.step = finish.step;
  entry.failure.clear();
  entry.finished.store(finished, std::memory_order_relaxed);
  entry.holders.store(1, std::memory_order_relaxed);
  return SharedPicture(&entry);
}

void PicturePool::reserve(const FloatImage& like, std::size_t count) {
  reserve_entries(like, count);
}

void PicturePool::reserve(const ImageRGBA8& like, std::size_t count) {
  reserve_entries(like, count);
}

template <class Image> void PicturePool::reserve_entries(const Image& like, std::size_t count) {
  std::lock_guard lock(mutex_);
  while (entries_.size() < count) {
    entries_.push_back(std::make_unique<SharedPicture::Entry>());
    SharedPicture::Entry* entry = entries_.back().get();
    entry->pool = this;
    if constexpr (std::is_same_v<Image, ImageRGBA8>)
      entry->srgb8.image = {like.width, like.height, std::vector<std::uint8_t>(like.pixels.size())};
    else entry->linear.image = FloatImage(like.width, like.height);
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
