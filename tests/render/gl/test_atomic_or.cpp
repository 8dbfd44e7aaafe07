// Many GPU threads set overlapping bit ranges with atomicOr (the splat's write pattern); the
// readback must equal the CPU's bit for bit. Also the compute-shader clear.
#include <cstdint>
#include <random>
#include <vector>

#include "render/gl/objects.h"
#include "render/gl/passes/clear.h"
#include "tests/render/gl/gl_fixture.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

struct Range {
  std::uint32_t first, count;
};

std::vector<std::uint32_t> cpu_bits(const std::vector<Range>& ranges, std::size_t words) {
  std::vector<std::uint32_t> bits(words, 0);
  for (const Range& r : ranges)
    for (std::uint32_t b = r.first; b < r.first + r.count; ++b) bits[b >> 5] |= 1u << (b & 31);
  return bits;
}

std::vector<Range> random_ranges(std::size_t n, std::uint32_t total_bits, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> length(0, 100);
  std::vector<Range> ranges(n);
  for (Range& r : ranges) {
    r.count = length(rng);
    r.first = std::uniform_int_distribution<std::uint32_t>(0, total_bits - r.count)(rng);
  }
  return ranges;
}

TEST(AtomicOr, ManyThreadsSettingOverlappingRangesMatchTheCpu) {
  test::context();
  constexpr std::size_t kWords = 1 << 16;  // 2 Mbit; each word is hit by ~20 threads
  const std::vector<Range> ranges = random_ranges(100000, kWords * 32, 7);

  gl::Buffer bits(kWords * 4);
  bits.clear();
  gl::Buffer range_buffer(ranges.size() * sizeof(Range), ranges.data());
  gl::Program program = test::shaders().compute("tests/render/gl/atomic_or.comp");
  bits.bind(GL_SHADER_STORAGE_BUFFER, 0);
  range_buffer.bind(GL_SHADER_STORAGE_BUFFER, 1);
  program.set("u_count", static_cast<unsigned>(ranges.size()));
  program.dispatch(static_cast<GLuint>((ranges.size() + 63) / 64));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::check_error("atomic_or dispatch");

  const std::vector<std::uint32_t> gpu = bits.read<std::uint32_t>(kWords);
  const std::vector<std::uint32_t> cpu = cpu_bits(ranges, kWords);
  std::size_t differing = 0;
  for (std::size_t w = 0; w < kWords; ++w) differing += gpu[w] != cpu[w];
  EXPECT_EQ(differing, 0u) << "words differing between GPU and CPU";
  // The test must be able to fail: the ranges leave some bits clear and set others.
  std::size_t set = 0;
  for (std::uint32_t w : cpu) set += static_cast<std::size_t>(__builtin_popcount(w));
  EXPECT_GT(set, 0u);
  EXPECT_LT(set, kWords * 32);
}

TEST(ClearPass, ZeroesExactlyTheRange) {
  test::context();
  constexpr std::size_t kWords = 1 << 16;
  std::vector<std::uint32_t> ones(kWords, 0xFFFFFFFFu);
  gl::Buffer buffer(kWords * 4, ones.data());
  GLint alignment = 1;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const std::size_t offset = static_cast<std::size_t>(alignment) * 4;  // bytes
  const std::size_t bytes = 16 * 1000;
  ClearPass clear(test::shaders());
  clear.run(buffer, offset, bytes);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<std::uint32_t> got = buffer.read<std::uint32_t>(kWords);
  for (std::size_t w = 0; w < kWords; ++w) {
    const bool inside = w * 4 >= offset && w * 4 < offset + bytes;
    ASSERT_EQ(got[w], inside ? 0u : 0xFFFFFFFFu) << "word " << w;
  }
  EXPECT_THROW(clear.run(buffer, offset, 10), Error);  // not a multiple of 16
}

}  // namespace
}  // namespace voxspan
