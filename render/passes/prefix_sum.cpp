#include "render/passes/prefix_sum.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {
namespace {
constexpr std::size_t kBlock = 4096;  // values per work group (prefix_sum.comp)
constexpr GLuint kMaxGroups = 65535;
constexpr std::size_t kMaxLevels = 3;  // 4096^3 values: more than a uint can count
constexpr GLbitfield kBarriers = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;
}  // namespace

PrefixSumPass::PrefixSumPass(const gl::ShaderLibrary& shaders)
    : scan_(shaders.compute("render/passes/prefix_sum.comp")),
      add_(shaders.compute("render/passes/prefix_sum.comp", "#define PREFIX_ADD 1")),
      level_sums_(kMaxLevels) {}

void PrefixSumPass::run(gl::Buffer& values, std::size_t count) {
  if (values.size() < (count + 1) * 4)
    throw make_error("PrefixSumPass: ", count, " values and their total need ", (count + 1) * 4,
                     " bytes, the buffer has ", values.size());
  scan_level(values, count, 0);
}

// Scans values[0, count) in place and writes the total to values[count].
void PrefixSumPass::scan_level(gl::Buffer& values, std::size_t count, std::size_t level) {
  const std::size_t blocks = (count + kBlock - 1) / kBlock;
  if (blocks > kMaxGroups || level >= kMaxLevels)
    throw make_error("PrefixSumPass: ", count, " values exceed what one scan handles");
  values.bind(GL_SHADER_STORAGE_BUFFER, 0);
  scan_.set("u_count", static_cast<unsigned>(count));
  if (blocks <= 1) {
    // One block: its total is the grand total, written straight after the values.
    values.bind(GL_SHADER_STORAGE_BUFFER, 1);
    scan_.set("u_sum_base", static_cast<unsigned>(count));
    scan_.dispatch(1);
    glMemoryBarrier(kBarriers);
    return;
  }
  gl::Buffer& sums = level_sums_[level];
  sums.reserve((blocks + 1) * 4);
  sums.bind(GL_SHADER_STORAGE_BUFFER, 1);
  scan_.set("u_sum_base", 0u);
  scan_.dispatch(static_cast<GLuint>(blocks));
  glMemoryBarrier(kBarriers);
  scan_level(sums, blocks, level + 1);
  // Level buffers may have been rebound by the recursion.
  values.bind(GL_SHADER_STORAGE_BUFFER, 0);
  sums.bind(GL_SHADER_STORAGE_BUFFER, 1);
  add_.set("u_count", static_cast<unsigned>(count));
  add_.dispatch(static_cast<GLuint>(std::min<std::size_t>(kMaxGroups, (count + 255) / 256)));
  values.copy_from(sums, 4, blocks * 4, count * 4);
  glMemoryBarrier(kBarriers);
}

}  // namespace voxspan
