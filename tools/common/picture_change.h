// tools/common/picture_change.h - how far adaptive sampling moved a volume view's picture: per
// pixel the worst channel (alpha included) against another picture, the change its tolerance
// bounds, and the slack the float compositing's rounding takes over it.
#pragma once

#include <algorithm>
#include <cmath>

#include "render/float_image.h"

namespace voxspan::tools {

inline constexpr double kToleranceSlack = 1e-6;

inline double worst_channel(const FloatImage& a, const FloatImage& b, int x, int y) {
  const glm::vec4 p = a.at(x, y), q = b.at(x, y);
  double worst = 0;
  for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(p[c]) - double(q[c])));
  return worst;
}

}  // namespace voxspan::tools
