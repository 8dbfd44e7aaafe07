#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace {

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void validate(const Camera& c) {
  if (!finite(c.eye)) throw make_error("camera eye is not finite");
  if (!finite(c.target)) throw make_error("camera target is not finite");
  if (!finite(c.up)) throw make_error("camera up is not finite");
  const glm::dvec3 view = c.target - c.eye;
  const double distance = glm::length(view);
  if (!(distance > 0)) throw make_error("camera eye equals its target: no view direction");
  if (!(glm::length(c.up) > 0)) throw make_error("camera up is the zero vector");
  if (glm::length(glm::cross(view / distance, glm::normalize(c.up))) < 1e-9)
    throw make_error("camera up is parallel to the view direction (target - eye)");
  if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180))
    throw make_error("camera fov_y_degrees = ", c.fov_y_degrees, " is outside (0, 180)");
  constexpr int kMaxSide = 16384;
  if (c.width < 1 || c.width > kMaxSide || c.height < 1 || c.height > kMaxSide)
    throw make_error("camera image size ", c.width, "x", c.height, " is outside 1..", kMaxSide);
}

ViewFrame::ViewFrame(const Camera& c) : eye(c.eye), width(c.width), height(c.height) {
  validate(c);
  forward = glm::normalize(c.target - c.eye);
  right = glm::normalize(glm::cross(forward, c.up));
  up = glm::cross(right, forward);
  tan_half_y = std::tan(glm::radians(c.fov_y_degrees) / 2);
  tan_half_x = tan_half_y * c.width / c.height;
  side_scale_x = 1 / std::sqrt(1 + tan_half_x * tan_half_x);
  side_scale_y = 1 / std::sqrt(1 + tan_half_y * tan_half_y);
}

Camera orbited(const Camera& camera, double phi_degrees, double theta_degrees) {
  if (phi_degrees == 0 && theta_degrees == 0) return camera;
  const glm::dvec3 up = glm::normalize(camera.up);
  const glm::dvec3 d = camera.eye - camera.target;
  const double distance = glm::length(d);
  const double phi = glm::radians(phi_degrees);
  // Rodrigues' rotation of d about up.
  const glm::dvec3 turned = d * std::cos(phi) + glm::cross(up, d) * std::sin(phi) +
                            up * glm::dot(up, d) * (1 - std::cos(phi));
  glm::dvec3 level = turned - up * glm::dot(up, turned);
  if (glm::length(level) < 1e-12 * distance) {  // looking along up: any level direction
    const glm::dvec3 any = std::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    level = any - up * glm::dot(up, any);
  }
  level = glm::normalize(level);
  const double limit = glm::radians(89.0);
  const double elevation =
      std::clamp(std::asin(std::clamp(glm::dot(up, turned) / distance, -1.0, 1.0)) +
                     glm::radians(theta_degrees),
                 -limit, limit);
  Camera out = camera;
  out.eye = camera.target + distance * (std::cos(elevation) * level + std::sin(elevation) * up);
  return out;
}

Camera orbited(const Camera& camera, double phi_degrees, double theta_degrees, glm::dvec3 pivot) {
  Camera out = orbited(camera, phi_degrees, theta_degrees);
  if (out == camera) return camera;
  // The target's place relative to the pivot, in the camera's axes before and after the turn.
  const ViewFrame before(camera), after(out);
  const glm::dvec3 o = camera.target - pivot;
  out.target = pivot + glm::dot(o, before.right) * after.right + glm::dot(o, before.up) * after.up +
               glm::dot(o, before.forward) * after.forward;
  out.eye += out.target - camera.target;
  return out;
}

}  // namespace voxspan
