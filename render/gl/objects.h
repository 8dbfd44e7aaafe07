// render/gl/objects.h - small RAII owners of GL objects: Buffer, Program, Texture3D,
// TimerQuery. Each owns one GL name, is move-only, and uses direct state access (GL 4.5),
// so no binding leaks between passes. Call only with a current context.
// Buffers and textures count their bytes in one process-wide tally (memory_usage()), so the
// per-step stats can report the GPU memory allocated now and at its peak.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

namespace voxspan::gl {

// Shared move-only ownership of one GL name; Deleter frees it.
template <class Deleter> class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      o.id_ = 0;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint get() const { return id_; }
  void reset() {
    if (id_ != 0) Deleter{}(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct DeleteBuffer {
  void operator()(GLuint id) const { glDeleteBuffers(1, &id); }
};
struct DeleteProgram {
  void operator()(GLuint id) const { glDeleteProgram(id); }
};
struct DeleteTexture {
  void operator()(GLuint id) const { glDeleteTextures(1, &id); }
};
struct DeleteQuery {
  void operator()(GLuint id) const { glDeleteQueries(1, &id); }
};

// Bytes held by live Buffers and Texture3Ds (all contexts of the process), and the most held at
// once since the last reset_memory_peak().
struct MemoryUsage {
  std::int64_t current_bytes = 0;
  std::int64_t peak_bytes = 0;
};
MemoryUsage memory_usage();
void reset_memory_peak();

// Move-only share of the tally: adds its bytes when made, removes them when destroyed.
class MemoryTicket {
 public:
  MemoryTicket() = default;
  explicit MemoryTicket(std::int64_t bytes);
  ~MemoryTicket();
  MemoryTicket(MemoryTicket&& o) noexcept : bytes_(o.bytes_) { o.bytes_ = 0; }
  MemoryTicket& operator=(MemoryTicket&& o) noexcept;
  MemoryTicket(const MemoryTicket&) = delete;
  MemoryTicket& operator=(const MemoryTicket&) = delete;

 private:
  std::int64_t bytes_ = 0;
};

// An immutable-storage buffer. Growing means a new buffer: reserve() reallocates only when the
// request exceeds the capacity, so steady-state steps allocate nothing.
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(std::size_t bytes, const void* data = nullptr);

  GLuint id() const { return handle_.get(); }
  std::size_t size() const { return size_; }

  // Ensures at least `bytes` of storage (contents are lost when it grows). Returns true if it
  // reallocated.
  bool reserve(std::size_t bytes);
  // reserve(), and also reallocates to exactly `bytes` when the capacity is more than twice
  // that, so a buffer sized by a memory budget gives memory back when the budget shrinks.
  bool fit(std::size_t bytes);
  void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
  void download(void* out, std::size_t bytes, std::size_t offset = 0) const;
  // Zero-fills [offset, offset+bytes) with glClearNamedBufferSubData: fine for small buffers;
  // large bit grids are cleared by a compute shader (GPU-NOTES: 50x faster on NVIDIA).
  void clear(std::size_t offset = 0, std::size_t bytes = SIZE_MAX);

  // N values from `first`, on the stack: a tally read back every frame allocates nothing.
  template <class T, std::size_t N> std::array<T, N> read_array(std::size_t first = 0) const {
    std::array<T, N> out{};
    download(out.data(), N * sizeof(T), first * sizeof(T));
    return out;
  }

  template <class T> std::vector<T> read(std::size_t count, std::size_t first = 0) const {
    std::vector<T> out;
    read(out, count, first);
    return out;
  }
  // Into `out`, whose memory is kept: a read every frame allocates only when it grows.
  template <class T>
  void read(std::vector<T>& out, std::size_t count, std::size_t first = 0) const {
    out.resize(count);
    if (count != 0) download(out.data(), count * sizeof(T), first * sizeof(T));
  }

  // Copies `bytes` from `from` at `from_offset` to this buffer at `offset`, on the GPU.
  void copy_from(const Buffer& from, std::size_t bytes, std::size_t from_offset = 0,
                 std::size_t offset = 0);

  // Binds the whole buffer (or a range) to an indexed target (GL_SHADER_STORAGE_BUFFER...).
  // NVIDIA breaks on single bindings of 2 GiB or more (GPU-NOTES): bind ranges below that.
  void bind(GLenum target, GLuint index) const;
  void bind_range(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const;

 private:
  Handle<DeleteBuffer> handle_;
  std::size_t size_ = 0;
  MemoryTicket ticket_;
};

// Where the host reads the GPU's buffers on a GPU: a persistently mapped buffer in host memory
// that only copies write, read after a fence. Reading a pass's own buffer instead
// (glGetNamedBufferSubData) made NVIDIA move it to host memory, and say so, 2 425 times in a
// 49 s run. One per context (render/gl/context.h makes it current with its context); a
// software renderer reads directly (its buffers are host memory already: a copy would only
// cost), unless `through_staging` asks otherwise (the tests, to run this path there).
class ReadbackStaging {
 public:
  explicit ReadbackStaging(bool use);
  ~ReadbackStaging();
  ReadbackStaging(const ReadbackStaging&) = delete;
  ReadbackStaging& operator=(const ReadbackStaging&) = delete;

  bool in_use() const { return use_; }
  void set_in_use(bool use) { use_ = use; }
  // `bytes` of `from` at `offset` into `out`, once the GPU has written them.
  void read(GLuint from, std::size_t offset, std::size_t bytes, void* out);
  // Its GL buffer is gone with its context: the destructor makes no GL call.
  void forget() { id_ = 0; }

 private:
  bool use_;
  GLuint id_ = 0;
  std::size_t size_ = 0;
  void* mapped_ = nullptr;
  MemoryTicket ticket_{0};
};

// The calling thread's current context's staging (null: read directly).
void set_current_staging(ReadbackStaging* staging);
ReadbackStaging* current_staging();

// One buffer bound whole to a shader-storage binding, for bind_storage().
struct StorageBinding {
  const Buffer& buffer;
  GLuint index;
};

// Binds each buffer whole at its GL_SHADER_STORAGE_BUFFER index, so a pass lists its buffers once.
void bind_storage(std::initializer_list<StorageBinding> bindings);

// A linked compute program. Uniforms are set by name with direct state access.
class Program {
 public:
  Program() = default;
  // Compiles and links; throws voxspan::Error with the driver's log on failure. `name` is the
  // shader's file name, for the message.
  static Program compute(std::string_view name, const std::string& source);

  GLuint id() const { return handle_.get(); }
  const std::string& name() const { return name_; }
  void use() const { glUseProgram(id()); }
  // Uses the program and dispatches; work-group counts must be within the GL limits.
  void dispatch(GLuint x, GLuint y = 1, GLuint z = 1) const;

  // Location of a uniform, -1 if the compiler removed it (setting -1 is a GL no-op).
  GLint uniform(const char* name) const;
  void set(const char* name, int v) const { glProgramUniform1i(id(), uniform(name), v); }
  void set(const char* name, unsigned v) const { glProgramUniform1ui(id(), uniform(name), v); }
  void set(const char* name, float v) const { glProgramUniform1f(id(), uniform(name), v); }
  void set(const char* name, double v) const { glProgramUniform1d(id(), uniform(name), v); }
  void set(const char* name, glm::dvec2 v) const;
  void set(const char* name, glm::vec2 v) const;
  void set(const char* name, glm::vec3 v) const;
  void set(const char* name, glm::vec4 v) const;
  void set(const char* name, glm::ivec2 v) const;
  void set(const char* name, glm::ivec3 v) const;
  void set(const char* name, glm::ivec4 v) const;
  void set(const char* name, glm::uvec2 v) const;
  void set(const char* name, glm::uvec3 v) const;
  void set(const char* name, const glm::mat4& v) const;

  // Work-group size declared by the shader (local_size_x/y/z), queried once at link time.
  glm::uvec3 work_group_size() const { return work_group_size_; }

 private:
  // Looked up by the caller's string without making a std::string: setting uniforms every
  // frame allocates nothing once each name has been seen.
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  Handle<DeleteProgram> handle_;
  std::string name_;
  glm::uvec3 work_group_size_{0};
  mutable std::unordered_map<std::string, GLint, NameHash, std::equal_to<>> locations_;
};

// An immutable 3D texture (e.g. the per-cell states of the simulation grid as R8UI).
class Texture3D {
 public:
  Texture3D() = default;
  Texture3D(GLenum internal_format, glm::ivec3 size);
  GLuint id() const { return handle_.get(); }
  glm::ivec3 size() const { return size_; }
  void upload(GLenum format, GLenum type, const void* data);
  void bind_unit(GLuint unit) const { glBindTextureUnit(unit, id()); }

 private:
  Handle<DeleteTexture> handle_;
  glm::ivec3 size_{0};
  MemoryTicket ticket_;
};

// A GL_TIME_ELAPSED query. Only meaningful where Context::has_gpu_timers() is true.
class TimerQuery {
 public:
  TimerQuery();
  void begin() const { glBeginQuery(GL_TIME_ELAPSED, handle_.get()); }
  void end() const { glEndQuery(GL_TIME_ELAPSED); }
  // Waits for the result.
  double milliseconds() const;

 private:
  Handle<DeleteQuery> handle_;
};

// Throws voxspan::Error naming `what` if GL has recorded an error since the last check.
void check_error(std::string_view what);

}  // namespace voxspan::gl
