#include "insitu/views/camera_offset.h"

#include <algorithm>
#include <cmath>

namespace voxspan {
namespace {

// The camera's elevation above the plane normal to its up, in degrees.
double elevation_degrees(const Camera& c) {
  const glm::dvec3 d = c.eye - c.target;
  const double sine = glm::dot(glm::normalize(c.up), d) / glm::length(d);
  return glm::degrees(std::asin(std::clamp(sine, -1.0, 1.0)));
}

// The height its view spans at its target: the unit of the pan.
double view_height(const Camera& c) {
  return 2 * glm::length(c.eye - c.target) * std::tan(glm::radians(c.fov_y_degrees) / 2);
}

}  // namespace

void CameraChange::merge(const CameraChange& later) {
  const double before = requests;
  if (later.reset != 0) {
    *this = later;
  } else {
    d_phi += later.d_phi;
    d_theta += later.d_theta;
    // Asked on the view as this change's zoom so far shows it.
    pan_x += later.pan_x / zoom;
    pan_y += later.pan_y / zoom;
    zoom *= later.zoom;
  }
  requests = before + later.requests;
}

void CameraOffset::add(const CameraChange& change, const Camera& framed) {
  using L = CameraOffsetLimits;
  if (change.reset != 0) *this = {};
  phi_ = std::remainder(phi_ + change.d_phi, 360.0);
  // Kept where orbited() keeps the elevation: what a drag past the pole adds is not stored,
  // so dragging back turns the camera at once.
  const double base = elevation_degrees(framed);
  theta_ = std::clamp(theta_ + change.d_theta, -L::kMaxElevation - base, L::kMaxElevation - base);
  if (change.pan_x != 0 || change.pan_y != 0) {
    const ViewFrame shown(on(framed, framed.target));  // a turn's axes are any pivot's
    const double aspect = double(framed.width) / double(framed.height);
    shift_ += (change.pan_x * aspect * shown.right + change.pan_y * shown.up) / zoom_;
    const double length = glm::length(shift_);
    if (length > L::kMaxShift) shift_ *= L::kMaxShift / length;
  }
  zoom_ = std::clamp(zoom_ * change.zoom, L::kMinZoom, L::kMaxZoom);
}

Camera CameraOffset::on(const Camera& framed, glm::dvec3 pivot) const {
  // The framing's camera bit for bit: an offset never asked for (or reset) changes no picture.
  if (phi_ == 0 && theta_ == 0 && zoom_ == 1 && shift_ == glm::dvec3(0)) return framed;
  Camera c = orbited(framed, phi_, theta_, pivot);
  const glm::dvec3 toward_eye = c.eye - c.target;
  c.target += shift_ * view_height(framed);
  c.eye = c.target + toward_eye / zoom_;
  return c;
}

}  // namespace voxspan
