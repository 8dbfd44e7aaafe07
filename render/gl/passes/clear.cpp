#include "render/gl/passes/clear.h"

#include <algorithm>

#include "render/gl/passes/dispatch.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {
constexpr std::size_t kMaxBinding = std::size_t(1) << 30;
enum Binding : GLuint { kWords };
}  // namespace

ClearPass::ClearPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/gl/passes/clear.comp",
                               gl::defines({{"WORDS_BINDING", kWords}}))) {
  GLint alignment = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  offset_alignment_ = static_cast<std::size_t>(std::max(alignment, 1));
}

void ClearPass::run(const gl::Buffer& buffer, std::size_t offset, std::size_t bytes) const {
  if (bytes % 16 != 0 || offset % offset_alignment_ != 0 || offset + bytes > buffer.size())
    throw make_error("ClearPass: range [", offset, ", +", bytes, ") of a ", buffer.size(),
                     "-byte buffer is not 16-byte sized, aligned to ", offset_alignment_,
                     " and inside the buffer");
  for (std::size_t done = 0; done < bytes; done += kMaxBinding) {
    const std::size_t chunk = std::min(kMaxBinding, bytes - done);
    const std::size_t words = chunk / 16;
    buffer.bind_range(GL_SHADER_STORAGE_BUFFER, kWords, offset + done, chunk);
    program_.set("u_count", static_cast<unsigned>(words));
    dispatch_strided(program_, words);
  }
}

}  // namespace voxspan
