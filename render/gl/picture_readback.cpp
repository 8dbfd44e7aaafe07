#include "render/gl/picture_readback.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <atomic>
#include <cstring>
#include <string>

#include "render/gl/objects.h"
#include "voxspan/error.h"

namespace voxspan::gl {
namespace {

constexpr GLbitfield kMapping = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
// How long a reader waits for a fence before it calls the read failed: a GPU that has not
// finished one frame's passes in this long is not coming back.
constexpr EGLTimeKHR kWaitNs = 60'000'000'000;

}  // namespace

// The fence functions, looked up once on the context's thread: libepoxy finds an extension's
// functions through the calling thread's current display, which a reader's thread has not.
struct PictureReadback::Fences {
  EGLDisplay display = EGL_NO_DISPLAY;
  PFNEGLCREATESYNCKHRPROC create = nullptr;
  PFNEGLCLIENTWAITSYNCKHRPROC wait = nullptr;
  PFNEGLDESTROYSYNCKHRPROC destroy = nullptr;

  // Null where the current display has no fences.
  static std::unique_ptr<const Fences> of_current() {
    Fences f;
    f.display = eglGetCurrentDisplay();
    if (f.display == EGL_NO_DISPLAY) return nullptr;
    const char* extensions = eglQueryString(f.display, EGL_EXTENSIONS);
    if (extensions == nullptr || std::strstr(extensions, "EGL_KHR_fence_sync") == nullptr)
      return nullptr;
    f.create = reinterpret_cast<PFNEGLCREATESYNCKHRPROC>(eglGetProcAddress("eglCreateSyncKHR"));
    f.wait =
        reinterpret_cast<PFNEGLCLIENTWAITSYNCKHRPROC>(eglGetProcAddress("eglClientWaitSyncKHR"));
    f.destroy = reinterpret_cast<PFNEGLDESTROYSYNCKHRPROC>(eglGetProcAddress("eglDestroySyncKHR"));
    if (f.create == nullptr || f.wait == nullptr || f.destroy == nullptr) return nullptr;
    return std::make_unique<const Fences>(f);
  }
};

// One host buffer, mapped once, and the fence of the read it holds.
class PictureReadback::Slot final : public PendingPicture {
 public:
  explicit Slot(const Fences& fences) : fences_(fences) {}

  ~Slot() override {
    drop_fence();
    if (id_ == 0) return;
    glUnmapNamedBuffer(id_);
    glDeleteBuffers(1, &id_);
  }

  bool held() const { return held_.load(std::memory_order_acquire); }

  // GL thread: the copy of `source`'s first width x height pixels behind a fence; the writes
  // to it (a shader's) made visible first.
  void issue(const gl::Buffer& source, int width, int height, int pixel_bytes) {
    drop_fence();  // one left by an issue that failed
    const std::size_t bytes = std::size_t(width) * std::size_t(height) * std::size_t(pixel_bytes);
    reserve(bytes);
    width_ = width;
    height_ = height;
    pixel_bytes_ = pixel_bytes;
    if (bytes != 0)
      glCopyNamedBufferSubData(source.id(), id_, 0, 0, static_cast<GLsizeiptr>(bytes));
    fence_ = fences_.create(fences_.display, EGL_SYNC_FENCE_KHR, nullptr);
    if (fence_ == EGL_NO_SYNC_KHR)
      throw make_error("cannot make a fence for the picture's read-back (EGL error 0x", std::hex,
                       eglGetError(), ")");
    // The fence reaches the GPU now: a reader on another thread cannot flush this context.
    glFlush();
    check_error("issuing the picture's read-back");
    held_.store(true, std::memory_order_release);
  }

  void copy_into(FloatImage& out) override {
    const void* pixels = landed(16, "linear floats");
    out.width = width_;
    out.height = height_;
    out.rgba.resize(std::size_t(width_) * std::size_t(height_) * 4);
    if (!out.rgba.empty()) std::memcpy(out.rgba.data(), pixels, out.rgba.size() * sizeof(float));
  }

  void copy_into(ImageRGBA8& out) override {
    const void* pixels = landed(4, "8-bit sRGB");
    out.width = width_;
    out.height = height_;
    out.pixels.resize(std::size_t(width_) * std::size_t(height_) * 4);
    if (!out.pixels.empty()) std::memcpy(out.pixels.data(), pixels, out.pixels.size());
  }

  void release() noexcept override {
    drop_fence();
    held_.store(false, std::memory_order_release);
  }

 private:
  void reserve(std::size_t bytes) {
    if (bytes <= size_ && id_ != 0) return;
    if (id_ != 0) {
      glUnmapNamedBuffer(id_);
      glDeleteBuffers(1, &id_);
      id_ = 0;
    }
    glCreateBuffers(1, &id_);
    glNamedBufferStorage(id_, static_cast<GLsizeiptr>(bytes == 0 ? 16 : bytes), nullptr,
                         kMapping | GL_CLIENT_STORAGE_BIT);
    mapped_ =
        glMapNamedBufferRange(id_, 0, static_cast<GLsizeiptr>(bytes == 0 ? 16 : bytes), kMapping);
    check_error("a read-back buffer of " + std::to_string(bytes) + " bytes");
    if (mapped_ == nullptr) throw make_error("cannot map a read-back buffer of ", bytes, " bytes");
    size_ = bytes;
    ticket_ = MemoryTicket(static_cast<std::int64_t>(bytes));
  }

  // The mapping once the read's fence has signalled (coherent: the copy is visible then), for a
  // reader of a picture of `pixel_bytes` a pixel (`kind`, named when the read was the other).
  const void* landed(int pixel_bytes, const char* kind) const {
    if (pixel_bytes != pixel_bytes_)
      throw make_error("a picture read back at ", pixel_bytes_, " bytes a pixel copied as ", kind);
    EGLint waited = EGL_TIMEOUT_EXPIRED_KHR;
    if (fence_ != EGL_NO_SYNC_KHR) waited = fences_.wait(fences_.display, fence_, 0, kWaitNs);
    if (waited == EGL_TIMEOUT_EXPIRED_KHR)
      throw make_error("the GPU did not finish the frame within ", kWaitNs / 1'000'000'000, " s");
    if (waited != EGL_CONDITION_SATISFIED_KHR)
      throw make_error("waiting for the GPU failed (EGL error 0x", std::hex, eglGetError(), ")");
    return mapped_;
  }

  void drop_fence() noexcept {
    if (fence_ != EGL_NO_SYNC_KHR) fences_.destroy(fences_.display, fence_);
    fence_ = EGL_NO_SYNC_KHR;
  }

  const Fences& fences_;
  GLuint id_ = 0;
  std::size_t size_ = 0;
  void* mapped_ = nullptr;
  int width_ = 0, height_ = 0, pixel_bytes_ = 0;
  EGLSyncKHR fence_ = EGL_NO_SYNC_KHR;
  std::atomic<bool> held_{false};
  MemoryTicket ticket_;
};

PictureReadback::PictureReadback() : fences_(Fences::of_current()) {}

PictureReadback::~PictureReadback() = default;

PendingPicture& PictureReadback::issue(const GpuFloatImage& image) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the shade pass wrote it in a shader
  return issue(image.buffer(), image.width(), image.height(), 16);
}

PendingPicture& PictureReadback::issue_srgb8(const gl::Buffer& packed, int width, int height) {
  return issue(packed, width, height, 4);
}

PendingPicture& PictureReadback::issue(const gl::Buffer& source, int width, int height,
                                       int pixel_bytes) {
  if (!available()) throw make_error("no EGL fences here: read the picture synchronously");
  Slot& slot = free_slot();
  slot.issue(source, width, height, pixel_bytes);
  return slot;
}

PictureReadback::Slot& PictureReadback::free_slot() {
  for (const std::unique_ptr<Slot>& s : slots_)
    if (!s->held()) return *s;
  slots_.push_back(std::make_unique<Slot>(*fences_));
  return *slots_.back();
}

}  // namespace voxspan::gl
