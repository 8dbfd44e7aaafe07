// render/frame_origin.h - the world point a frame's float positions are measured from. The
// passes read positions as floats, whose 24 bits hold a coordinate of 4.2e6 (UTM-like world
// coordinates) to 0.5: a fluid 0.05 apart stored so collapses onto slabs. Frame units
// (render/frame_units.h) keep the floats exact at any scale; this keeps them exact at any
// translation: a frame far from the world's origin has its positions shifted by `at` in double
// before they become floats, and its camera and environment shifted with them. Depths,
// distances and pictures do not change under a translation, so nothing that leaves a renderer
// is shifted back. Frames near the world's origin pass through bit for bit.
#pragma once

#include <glm/glm.hpp>

#include <array>

#include "render/camera.h"
#include "render/shade_options.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct FrameOrigin {
  glm::dvec3 at{0};  // world coordinates of the frame's (0, 0, 0)

  // The frame of a scene around `point` whose lengths that matter are of order `unit` (the
  // particle spacing): voxspan::frame_origin_near (voxspan/classify.h).
  static FrameOrigin near(glm::dvec3 point, double unit);
  // The frame the boundary spheres of a step are in (StepData::origin).
  static FrameOrigin of(const std::array<double, 3>& origin) {
    return {glm::dvec3(origin[0], origin[1], origin[2])};
  }
  bool shifted() const { return at != glm::dvec3(0); }

  // A world position as the frame's floats hold it: shifted in double, then rounded once.
  glm::vec3 position(double x, double y, double z) const {
    return glm::vec3(glm::dvec3(x, y, z) - at);
  }
  Camera camera(const Camera& world) const;
  // The cell grid's origin, in double.
  CellStatesView cells(const CellStatesView& world) const;
  // The ground stays where the world has it (Environment::origin).
  Environment environment(const Environment& world) const;
};

}  // namespace voxspan
