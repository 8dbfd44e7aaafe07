// insitu/views/view_framing.h - the camera of a view on each render step: as given (manual), or
// framed automatically around the fluid.
//
// Automatic framing looks along the configured direction at the box of the boundary
// particles' spheres (they enclose the fluid: every cell next to air or a surface is a
// boundary cell), from the nearest distance at which all eight corners of the box, moved out
// from its centre by `margin`, lie inside the view pyramid. Which box follows the fluid is the
// view's `framing`: grown over every render step so far (default; the camera only backs away,
// so a video of the run does not jitter), refitted on each step, or kept from the first step.
// Pure CPU, no GL: a few hundred nanoseconds per view plus one pass over the boundary spheres.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "insitu/config/settings.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// An axis-aligned box; empty() until something is added.
struct Bounds {
  std::array<double, 3> lo{1e300, 1e300, 1e300};
  std::array<double, 3> hi{-1e300, -1e300, -1e300};

  bool empty() const { return lo[0] > hi[0]; }
  void add(const Bounds& other);
  // The box of the spheres (centre +- radius); NaN/inf positions and radii <= 0 are skipped.
  static Bounds of_spheres(std::span<const ParticleSphere> spheres);
};

// The camera that frames `box` as the view says (automatic framing), or the manual camera.
// An empty box (no particle yet) gives a camera that looks at the origin from 1 unit away.
Camera frame_camera(const CameraConfig& camera, int width, int height, const Bounds& box);
Camera frame_camera(const ViewSettings& view, const Bounds& box);

// Depths per pixel (row 0 at the top, 0: nothing there) two ways: along the camera's axis (view
// z, what the views composite with) and along each pixel's ray from the eye (what the depth
// output writes, in the image's r channel). Storage reused.
void distances_from_view_depth(const Camera& camera, std::span<const float> view_depth,
                               FloatImage& distances);
void view_depth_from_distances(const Camera& camera, const FloatImage& distances,
                               std::vector<float>& view_depth);

// Keeps the box a view's framing follows from step to step.
class ViewFraming {
 public:
  explicit ViewFraming(const ViewSettings& view)
      : camera_(view.camera), width_(view.width), height_(view.height) {}
  // The camera for this render step's boundary spheres.
  Camera update(std::span<const ParticleSphere> boundary);
  // The same from this step's box of them (with MPI: the box of every rank's).
  Camera update(const Bounds& step_box);
  // The fluid's box as the framing follows it (the grown box under `grow`), kept for manual
  // cameras too (the ground plane of the environment goes under it).
  const Bounds& box() const { return box_; }

 private:
  CameraConfig camera_;
  int width_, height_;
  Bounds box_;
};

}  // namespace voxspan
