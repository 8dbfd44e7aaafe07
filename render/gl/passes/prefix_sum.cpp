#include "render/gl/passes/prefix_sum.h"

#include <string>

#include "render/gl/passes/dispatch.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr const char* kShader = "render/gl/passes/prefix_sum.comp";
constexpr unsigned kPerThread = 16;    // values each scan thread sums
constexpr std::size_t kMaxLevels = 3;  // 4096^3 values: more than a uint can count
constexpr GLbitfield kBarriers = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

enum Binding : GLuint { kValues, kSums };

std::string shader_defines() {
  return gl::defines(
      {{"VALUES_BINDING", kValues}, {"SUMS_BINDING", kSums}, {"PREFIX_PER_THREAD", kPerThread}});
}

}  // namespace

PrefixSumPass::PrefixSumPass(const gl::ShaderLibrary& shaders)
    : scan_(shaders.compute(kShader, shader_defines())),
      add_(shaders.compute(kShader, shader_defines() + "#define PREFIX_ADD 1")),
      block_(scan_.work_group_size().x * kPerThread),
      level_sums_(kMaxLevels) {}

void PrefixSumPass::run(gl::Buffer& values, std::size_t count) {
  if (values.size() < (count + 1) * 4)
    throw make_error("PrefixSumPass: ", count, " values and their total need ", (count + 1) * 4,
                     " bytes, the buffer has ", values.size());
  scan_level(values, count, 0);
}

// Scans values[0, count) in place and writes the total to values[count].
void PrefixSumPass::scan_level(gl::Buffer& values, std::size_t count, std::size_t level) {
  const std::size_t blocks = (count + block_ - 1) / block_;
  if (blocks > kMaxGroups || level >= kMaxLevels)
    throw make_error("PrefixSumPass: ", count, " values exceed what one scan handles");
  values.bind(GL_SHADER_STORAGE_BUFFER, kValues);
  scan_.set("u_count", static_cast<unsigned>(count));
  if (blocks <= 1) {
    // One block: its total is the grand total, written straight after the values.
    values.bind(GL_SHADER_STORAGE_BUFFER, kSums);
    scan_.set("u_sum_base", static_cast<unsigned>(count));
    scan_.dispatch(1);
    glMemoryBarrier(kBarriers);
    return;
  }
  gl::Buffer& sums = level_sums_[level];
  sums.reserve((blocks + 1) * 4);
  sums.bind(GL_SHADER_STORAGE_BUFFER, kSums);
  scan_.set("u_sum_base", 0u);
  scan_.dispatch(static_cast<GLuint>(blocks));
  glMemoryBarrier(kBarriers);
  scan_level(sums, blocks, level + 1);
  // Level buffers may have been rebound by the recursion.
  values.bind(GL_SHADER_STORAGE_BUFFER, kValues);
  sums.bind(GL_SHADER_STORAGE_BUFFER, kSums);
  add_.set("u_count", static_cast<unsigned>(count));
  dispatch_strided(add_, count);
  values.copy_from(sums, 4, blocks * 4, count * 4);
  glMemoryBarrier(kBarriers);
}

}  // namespace voxspan
