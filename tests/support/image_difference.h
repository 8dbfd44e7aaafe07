// The largest difference between two pictures' (or float buffers') values, channel by channel:
// what the renderers' tests hold against their tolerances (tests only). Buffers of different
// sizes differ by infinity.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "render/float_image.h"

namespace voxspan::test {

inline double largest_difference(std::span<const float> a, std::span<const float> b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, double(std::abs(a[i] - b[i])));
  return d;
}

inline double largest_difference(const FloatImage& a, const FloatImage& b) {
  return largest_difference(a.rgba, b.rgba);
}

// The q-quantile (q in [0, 1]) of the channel differences of two pictures of one size.
inline double difference_quantile(const FloatImage& a, const FloatImage& b, double q) {
  std::vector<double> d(a.rgba.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::abs(double(a.rgba[i]) - b.rgba[i]);
  if (d.empty()) return 0;
  const auto at = d.begin() + std::ptrdiff_t(q * double(d.size() - 1));
  std::nth_element(d.begin(), at, d.end());
  return *at;
}

}  // namespace voxspan::test
