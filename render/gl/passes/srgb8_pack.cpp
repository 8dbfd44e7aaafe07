#include "render/gl/passes/srgb8_pack.h"

#include <algorithm>
#include <vector>

#include "render/gl/passes/dispatch.h"
#include "render/srgb8_image.h"

namespace voxspan {
namespace {

enum Binding : GLuint { kPicture, kTable, kPacked };

// The table's bytes in uints (four entries each, the first in the low byte), as the shader
// reads them; zero-padded to whole words.
gl::Buffer table_buffer() {
  const std::span<const std::uint8_t> table = srgb8_table();
  std::vector<std::uint8_t> words((table.size() + 3) / 4 * 4, 0);
  std::copy(table.begin(), table.end(), words.begin());
  return gl::Buffer(words.size(), words.data());
}

}  // namespace

Srgb8PackPass::Srgb8PackPass(const gl::ShaderLibrary& shaders)
    : program_(shaders.compute("render/gl/passes/srgb8_pack.comp",
                               gl::defines({{"PICTURE_BINDING", kPicture},
                                            {"TABLE_BINDING", kTable},
                                            {"PACKED_BINDING", kPacked},
                                            {"TABLE_BITS", kSrgb8TableBits}}))),
      table_(table_buffer()) {}

void Srgb8PackPass::run(const GpuFloatImage& image, gl::Buffer& out) const {
  const std::size_t pixels = std::size_t(image.width()) * std::size_t(image.height());
  out.reserve(std::max<std::size_t>(4, pixels * 4));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the shade pass wrote the picture
  gl::bind_storage({{image.buffer(), kPicture}, {table_, kTable}, {out, kPacked}});
  dispatch_threads(program_, pixels);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace voxspan
