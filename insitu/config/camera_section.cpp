// A view's camera keys (views[i].camera): automatic framing or a manual eye and target, and
// the checks that keep the two apart.
#include <cmath>

#include "insitu/config/settings.h"
#include "insitu/config/yaml_reader.h"

namespace voxspan {
namespace {

using schema::Section;
using yaml::Checker;
using yaml::MapReader;

double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// sin of the angle between a and b is |a x b| / (|a| |b|).
bool parallel(const Vec3d& a, const Vec3d& b) {
  Vec3d c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return length(c) <= 1e-6 * length(a) * length(b);
}

bool valid_bounds(const std::vector<std::array<double, 2>>& bounds) {
  if (bounds.size() != 3) return false;
  for (const std::array<double, 2>& axis : bounds)
    if (!std::isfinite(axis[0]) || !std::isfinite(axis[1]) || !(axis[0] < axis[1])) return false;
  return true;
}

void check_camera(MapReader& r, CameraConfig& c) {
  const bool manual_keys = r.has("eye") || r.has("target");
  if (!r.has("auto")) c.automatic = !manual_keys;
  Checker& ch = r.checker();
  if (length(c.up) == 0) ch.error(r.find("up"), r.path("up"), "must not be zero");
  if (c.automatic) {
    if (manual_keys) {
      const char* key = r.has("eye") ? "eye" : "target";
      ch.error(r.find(key), r.path(key),
               "automatic framing (auto: true) chooses the eye and target itself; remove it or "
               "set auto: false");
    }
    if (!c.bounds.empty() && !valid_bounds(c.bounds))
      ch.error(r.find("bounds"), r.path("bounds"),
               "must be three [low, high] pairs of finite numbers, low < high (x, y, z)");
    if (length(c.direction) == 0)
      ch.error(r.find("direction"), r.path("direction"), "must not be zero");
    else if (length(c.up) > 0 && parallel(c.direction, c.up))
      ch.error(r.find("direction"), r.path("direction"),
               "must not be parallel to camera.up (the world's up, the ground's normal): for a "
               "view from straight above or below, tilt it a little, e.g. [0, 0.05, -1]");
    return;
  }
  for (const char* key : {"direction", "margin", "framing", "bounds"})
    if (r.has(key))
      ch.error(r.find(key), r.path(key),
               "is for automatic framing; a camera with eye and target looks at the target");
  if (!r.has("eye") || !r.has("target")) {
    ch.error(r.node(), r.path(), "a manual camera needs both eye and target");
    return;
  }
  const Vec3d d{c.target[0] - c.eye[0], c.target[1] - c.eye[1], c.target[2] - c.eye[2]};
  if (length(d) == 0) ch.error(r.find("target"), r.path("target"), "must differ from camera.eye");
  else if (length(c.up) > 0 && parallel(d, c.up))
    ch.error(r.find("up"), r.path("up"), "must not be parallel to the viewing direction");
}

bool manual(const CameraConfig& c) { return !c.automatic; }
bool automatic(const CameraConfig& c) { return c.automatic; }

}  // namespace

const Section<CameraConfig>& camera_section() {
  using C = CameraConfig;
  static const Section<C> s{
      "views[i].camera",
      {schema::flag("auto", &C::automatic, "automatic framing")
           .default_shown_as("true unless `eye`/`target` given"),
       schema::vec3("eye", &C::eye, "manual only, with `target`").only_when(manual),
       schema::vec3("target", &C::target, "manual only, with `eye`; not the eye").only_when(manual),
       schema::vec3("up", &C::up,
                    "the world's up: the picture's up and the ground's normal; not parallel to "
                    "the viewing direction"),
       schema::number("fov", &C::fov_degrees, schema::above_up_to(0, 179),
                      "vertical field of view, degrees"),
       schema::vec3("direction", &C::direction,
                    "automatic only: the camera looks along it at the fluid's box; with it and "
                    "`up` at their defaults a 2D run (every particle in one plane x, y or z = "
                    "const) is seen head-on, y up in the x-y plane, z up in the others")
           .only_when(automatic),
       schema::number("margin", &C::margin, schema::above_up_to(0, 100),
                      "automatic only: the box, grown about its centre by this, just fits the "
                      "view (all eight corners inside)")
           .only_when(automatic),
       schema::choice("framing", &C::framing, kFramingNames,
                      "automatic only: the box is the union over all render steps so far (the "
                      "camera only backs away: a steady video), each step's own, or the first "
                      "step's; particles far from the fluid's bulk (under 1 % of the surface "
                      "shell, 8 diameters or more away) are left out of it, with a warning")
           .only_when(automatic),
       schema::pairs("bounds", &C::bounds,
                     "automatic only: [[x0, x1], [y0, y1], [z0, z1]], a box to frame instead of "
                     "the fluid's (a domain you know), every step")
           .only_when(automatic)},
      check_camera};
  return s;
}

}  // namespace voxspan
