#include "parallel_scan.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_scan.h>

#include <limits>

#include "voxspan/error.h"

namespace voxspan::detail {

std::uint32_t exclusive_scan(std::span<const std::uint32_t> in, std::span<std::uint32_t> out) {
  const std::size_t n = in.size();
  // 64-bit running sums, so an overflow is seen instead of wrapping.
  std::uint64_t total = tbb::parallel_scan(
      tbb::blocked_range<std::size_t>(0, n, 1 << 14), std::uint64_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::uint64_t sum, bool final_pass) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint32_t v = in[i];
          if (final_pass) out[i] = static_cast<std::uint32_t>(sum);
          sum += v;
        }
        return sum;
      },
      [](std::uint64_t a, std::uint64_t b) { return a + b; });
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw make_error("more than 2^32 - 1 particles in one classification (", total, ")");
  out[n] = static_cast<std::uint32_t>(total);
  return static_cast<std::uint32_t>(total);
}

}  // namespace voxspan::detail
