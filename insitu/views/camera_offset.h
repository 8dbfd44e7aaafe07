// insitu/views/camera_offset.h - a user's orbit, pan and zoom of a view's camera, kept on top of
// its framing (the live page's `live.interactive`; insitu/live/camera_mailbox.h).
//
// In: the changes asked for since the last render step (CameraChange, merged), and each step's
// framed camera (insitu/views/view_framing.h: automatic framing still decides the centre and
// the distance). Out: the camera the view renders with. The offset is relative, so that it
// follows the framing as the fluid's box grows: the orbit in degrees about the framing's
// target, the zoom as a factor of its distance, the pan in heights of its view at the target.
// Pure arithmetic on a few doubles: nothing allocated.
#pragma once

#include <glm/glm.hpp>

#include "render/camera.h"

namespace voxspan {

// What was asked for one view since the last render step; requests merge into one (orbits and
// pans add up, zooms multiply, a reset drops what came before it). Plain doubles: an MPI job
// broadcasts it as bytes.
struct CameraChange {
  double requests = 0;            // how many were merged; 0: nothing asked
  double reset = 0;               // 1: back to the framing's camera first
  double d_phi = 0, d_theta = 0;  // degrees: about the camera's up, then towards it
  double pan_x = 0, pan_y = 0;    // the camera's move, in its view's width and height as shown
  double zoom = 1;                // > 1: closer

  bool any() const { return requests > 0; }
  // `later` after this one.
  void merge(const CameraChange& later);
};

// Bounds of the offset, whatever the requests add up to: the camera stays a camera.
struct CameraOffsetLimits {
  static constexpr double kMinZoom = 0.01, kMaxZoom = 100;
  static constexpr double kMaxShift = 100;     // view heights from the framing's target
  static constexpr double kMaxElevation = 89;  // degrees, as orbited() keeps it
};

class CameraOffset {
 public:
  // Applies a change, seen on the camera `framed` gives with the offset so far.
  void add(const CameraChange& change, const Camera& framed);
  // The camera the view renders with: turned about `pivot` (the view's ViewFraming::pivot(), as
  // Cinema's angles turn it), then panned and zoomed.
  Camera on(const Camera& framed, glm::dvec3 pivot) const;

 private:
  double phi_ = 0, theta_ = 0, zoom_ = 1;
  glm::dvec3 shift_{0};  // the target's move, in heights of the framed view at its target
};

}  // namespace voxspan
