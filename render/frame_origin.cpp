#include "render/frame_origin.h"

#include <cmath>

namespace voxspan {

FrameOrigin FrameOrigin::near(glm::dvec3 point, double unit) {
  const double reach = std::ldexp(unit, 10);
  const bool near_world_origin =
      std::abs(point.x) < reach && std::abs(point.y) < reach && std::abs(point.z) < reach;
  // A non-finite point or unit is left to the renderers' own checks.
  if (near_world_origin || !std::isfinite(reach) || !std::isfinite(point.x) ||
      !std::isfinite(point.y) || !std::isfinite(point.z))
    return {};
  return {point};
}

Camera FrameOrigin::camera(const Camera& world) const {
  Camera c = world;
  c.eye -= at;
  c.target -= at;
  return c;
}

Environment FrameOrigin::environment(const Environment& world) const {
  Environment e = world;
  e.origin += at;
  return e;
}

}  // namespace voxspan
