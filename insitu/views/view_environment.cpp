#include "insitu/views/view_environment.h"

#include <algorithm>
#include <cmath>

namespace voxspan {

glm::dvec3 sun_direction(glm::dvec3 up) {
  up = glm::normalize(up);
  const glm::dvec3 other = std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 a = glm::normalize(glm::cross(up, other)), b = glm::cross(up, a);
  return up + 0.35 * a + 0.45 * b;
}

namespace {

// The lowest point of the box along `up`.
double lowest(const Bounds& box, glm::dvec3 up) {
  up = glm::normalize(up);
  double low = 1e300;
  for (int k = 0; k < 8; ++k)
    low = std::min(
        low, glm::dot(up, glm::dvec3(k & 1 ? box.hi[0] : box.lo[0], k & 2 ? box.hi[1] : box.lo[1],
                                     k & 4 ? box.hi[2] : box.lo[2])));
  return low;
}

}  // namespace

double floor_height(const Bounds& sphere_box, glm::dvec3 up, double spacing) {
  return lowest(sphere_box, up) + 0.5 * spacing;
}

double smallest_side(const Bounds& box) {
  return std::min({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
}

}  // namespace voxspan
