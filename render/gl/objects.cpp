#include "render/gl/objects.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "voxspan/error.h"

namespace voxspan::gl {
namespace {

GLuint create_buffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return id;
}

const char* gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return "GL error";
  }
}

// The driver's compile log of a shader or link log of a program: `get_iv` and `get_log` are
// glGetShaderiv and glGetShaderInfoLog, or the Program pair.
template <class GetIv, class GetLog> std::string info_log(GLuint id, GetIv get_iv, GetLog get_log) {
  GLint length = 0;
  get_iv(id, GL_INFO_LOG_LENGTH, &length);
  std::string info(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  get_log(id, length, nullptr, info.data());
  return info.c_str();  // up to the terminating NUL the driver wrote
}

std::atomic<std::int64_t> g_memory_current{0};
std::atomic<std::int64_t> g_memory_peak{0};

// Bytes per texel of the formats we allocate; 4 for anything else (an estimate, for stats).
std::int64_t texel_bytes(GLenum internal_format) {
  switch (internal_format) {
    case GL_R8UI:
    case GL_R8: return 1;
    case GL_R16UI:
    case GL_R16F:
    case GL_RG8: return 2;
    case GL_RGBA16F:
    case GL_RG32F:
    case GL_RG32UI: return 8;
    case GL_RGBA32F:
    case GL_RGBA32UI: return 16;
    default: return 4;
  }
}

}  // namespace

MemoryUsage memory_usage() { return {g_memory_current.load(), g_memory_peak.load()}; }

void reset_memory_peak() { g_memory_peak.store(g_memory_current.load()); }

MemoryTicket::MemoryTicket(std::int64_t bytes) : bytes_(bytes) {
  const std::int64_t now = g_memory_current.fetch_add(bytes) + bytes;
  std::int64_t peak = g_memory_peak.load();
  while (now > peak && !g_memory_peak.compare_exchange_weak(peak, now)) {}
}

MemoryTicket::~MemoryTicket() { g_memory_current.fetch_sub(bytes_); }

MemoryTicket& MemoryTicket::operator=(MemoryTicket&& o) noexcept {
  if (this != &o) {
    g_memory_current.fetch_sub(bytes_);
    bytes_ = o.bytes_;
    o.bytes_ = 0;
  }
  return *this;
}

void check_error(std::string_view what) {
  GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {}
  throw make_error(what, ": ", gl_error_name(e));
}

// --- Buffer -----------------------------------------------------------------------------------

Buffer::Buffer(std::size_t bytes, const void* data) : handle_(create_buffer()), size_(bytes) {
  // GL refuses zero-sized storage; keep one word so an empty buffer is still bindable.
  glNamedBufferStorage(id(), static_cast<GLsizeiptr>(bytes == 0 ? 4 : bytes), data,
                       GL_DYNAMIC_STORAGE_BIT);
  check_error("allocating a GL buffer of " + std::to_string(bytes) + " bytes");
  ticket_ = MemoryTicket(static_cast<std::int64_t>(bytes == 0 ? 4 : bytes));
}

bool Buffer::reserve(std::size_t bytes) {
  if (handle_.get() != 0 && bytes <= size_) return false;
  // Grow by half again so a slowly growing count does not reallocate every step.
  std::size_t grown = size_ + size_ / 2;
  *this = Buffer(bytes > grown ? bytes : grown);
  return true;
}

bool Buffer::fit(std::size_t bytes) {
  if (handle_.get() != 0 && size_ / 2 > bytes) {
    *this = Buffer();  // release first: the point is to hold less
    *this = Buffer(bytes);
    return true;
  }
  return reserve(bytes);
}

void Buffer::upload(const void* data, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_)
    throw make_error("Buffer::upload: ", bytes, " bytes at ", offset, " exceed the buffer's ",
                     size_);
  glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::download(void* out, std::size_t bytes, std::size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > size_)
    throw make_error("Buffer::download: ", bytes, " bytes at ", offset, " exceed the buffer's ",
                     size_);
  if (ReadbackStaging* staging = current_staging(); staging != nullptr && staging->in_use())
    staging->read(id(), offset, bytes, out);
  else
    glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                            out);
}

void Buffer::clear(std::size_t offset, std::size_t bytes) {
  if (offset >= size_) return;
  if (bytes > size_ - offset) bytes = size_ - offset;
  glClearNamedBufferSubData(id(), GL_R32UI, static_cast<GLintptr>(offset),
                            static_cast<GLsizeiptr>(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT,
                            nullptr);
}

void Buffer::copy_from(const Buffer& from, std::size_t bytes, std::size_t from_offset,
                       std::size_t offset) {
  if (bytes == 0) return;
  if (from_offset + bytes > from.size() || offset + bytes > size_)
    throw make_error("Buffer::copy_from: ", bytes, " bytes from ", from_offset, " of a ",
                     from.size(), "-byte buffer to ", offset, " of a ", size_,
                     "-byte buffer is out of range");
  glCopyNamedBufferSubData(from.id(), id(), static_cast<GLintptr>(from_offset),
                           static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes));
}

void Buffer::bind(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }

void Buffer::bind_range(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const {
  glBindBufferRange(target, index, id(), static_cast<GLintptr>(offset),
                    static_cast<GLsizeiptr>(bytes));
}

void bind_storage(std::initializer_list<StorageBinding> bindings) {
  for (const StorageBinding& b : bindings) b.buffer.bind(GL_SHADER_STORAGE_BUFFER, b.index);
}

// --- ReadbackStaging --------------------------------------------------------------------------

namespace {
thread_local ReadbackStaging* t_staging = nullptr;
}  // namespace

void set_current_staging(ReadbackStaging* staging) { t_staging = staging; }
ReadbackStaging* current_staging() { return t_staging; }

ReadbackStaging::ReadbackStaging(bool use) : use_(use) {}

ReadbackStaging::~ReadbackStaging() {
  if (id_ == 0) return;
  glUnmapNamedBuffer(id_);
  glDeleteBuffers(1, &id_);
}

void ReadbackStaging::read(GLuint from, std::size_t offset, std::size_t bytes, void* out) {
  constexpr GLbitfield kMap = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  if (bytes > size_) {
    if (id_ != 0) {
      glUnmapNamedBuffer(id_);
      glDeleteBuffers(1, &id_);
    }
    const std::size_t grown = std::max(bytes, size_ + size_ / 2);
    glCreateBuffers(1, &id_);
    glNamedBufferStorage(id_, static_cast<GLsizeiptr>(grown), nullptr,
                         kMap | GL_CLIENT_STORAGE_BIT);
    mapped_ = glMapNamedBufferRange(id_, 0, static_cast<GLsizeiptr>(grown), kMap);
    check_error("a read-back buffer of " + std::to_string(grown) + " bytes");
    if (mapped_ == nullptr) throw make_error("cannot map a read-back buffer of ", grown, " bytes");
    size_ = grown;
    ticket_ = MemoryTicket(static_cast<std::int64_t>(grown));
  }
  glCopyNamedBufferSubData(from, id_, static_cast<GLintptr>(offset), 0,
                           static_cast<GLsizeiptr>(bytes));
  // Coherent mapping: the copy is visible to the host once a fence after it has signalled.
  GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  GLenum waited = GL_TIMEOUT_EXPIRED;
  while (waited == GL_TIMEOUT_EXPIRED)
    waited = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
  glDeleteSync(fence);
  if (waited == GL_WAIT_FAILED) throw make_error("waiting for a GPU read-back failed");
  std::memcpy(out, mapped_, bytes);
}

// --- Program ----------------------------------------------------------------------------------

Program Program::compute(std::string_view name, const std::string& source) {
  GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    throw make_error("compiling ", name, " failed:\n", log);
  }
  Program program;
  program.handle_ = Handle<DeleteProgram>(glCreateProgram());
  program.name_ = std::string(name);
  glAttachShader(program.id(), shader);
  glLinkProgram(program.id());
  glDeleteShader(shader);  // freed with the program
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok)
    throw make_error("linking ", name, " failed:\n",
                     info_log(program.id(), glGetProgramiv, glGetProgramInfoLog));
  GLint size[3] = {0, 0, 0};
  glGetProgramiv(program.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
  program.work_group_size_ = glm::uvec3(size[0], size[1], size[2]);
  return program;
}

void Program::dispatch(GLuint x, GLuint y, GLuint z) const {
  if (x == 0 || y == 0 || z == 0) return;
  use();
  glDispatchCompute(x, y, z);
}

GLint Program::uniform(const char* name) const {
  auto it = locations_.find(std::string_view(name));
  if (it != locations_.end()) return it->second;
  GLint loc = glGetUniformLocation(id(), name);
  locations_.emplace(name, loc);
  return loc;
}

void Program::set(const char* n, glm::dvec2 v) const {
  glProgramUniform2dv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::vec2 v) const {
  glProgramUniform2fv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::vec3 v) const {
  glProgramUniform3fv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::vec4 v) const {
  glProgramUniform4fv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::ivec2 v) const {
  glProgramUniform2iv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::ivec3 v) const {
  glProgramUniform3iv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::ivec4 v) const {
  glProgramUniform4iv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::uvec2 v) const {
  glProgramUniform2uiv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, glm::uvec3 v) const {
  glProgramUniform3uiv(id(), uniform(n), 1, glm::value_ptr(v));
}
void Program::set(const char* n, const glm::mat4& v) const {
  glProgramUniformMatrix4fv(id(), uniform(n), 1, GL_FALSE, glm::value_ptr(v));
}

// --- Texture3D --------------------------------------------------------------------------------

Texture3D::Texture3D(GLenum internal_format, glm::ivec3 size) : size_(size) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_3D, 1, &id);
  handle_ = Handle<DeleteTexture>(id);
  glTextureStorage3D(id, 1, internal_format, size.x, size.y, size.z);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  check_error("allocating a 3D texture");
  ticket_ = MemoryTicket(texel_bytes(internal_format) * size.x * size.y * size.z);
}

void Texture3D::upload(GLenum format, GLenum type, const void* data) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(id(), 0, 0, 0, 0, size_.x, size_.y, size_.z, format, type, data);
}

// --- TimerQuery -------------------------------------------------------------------------------

TimerQuery::TimerQuery() {
  GLuint id = 0;
  glCreateQueries(GL_TIME_ELAPSED, 1, &id);
  handle_ = Handle<DeleteQuery>(id);
}

double TimerQuery::milliseconds() const {
  GLuint64 ns = 0;
  glGetQueryObjectui64v(handle_.get(), GL_QUERY_RESULT, &ns);
  return static_cast<double>(ns) * 1e-6;
}

}  // namespace voxspan::gl
