// render/frame_units.h - the units a surface frame is rendered in, and the surface renderer that
// renders in them (in_frame_units). The passes after the grid work in float and square
// view-space lengths, which overflow past about 1e19 and lose precision under about 1e-19. A
// scene's scale is a uniform similarity, so a frame whose camera stands farther than 2^32 or
// nearer than 2^-32 world units from its target is rendered in units of the power of two
// nearest that distance: positions, radii, camera, cell grid and every length of the options
// divided by it, absorption multiplied. Only the exponents change, so the frame's floats are
// those of the same scene at unit scale: the picture is the unit scene's. What leaves the
// renderer (span images, first-hit distances) is multiplied back into world units, and what
// enters it in world units (span images, backdrops) divided. In between, frames are rendered
// as given: nothing is copied.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "render/backdrop.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/shade_options.h"
#include "render/span_image.h"
#include "render/surface_renderer.h"

namespace voxspan {

struct FrameUnits {
  double unit = 1;  // world units per frame unit: 1, or a power of two past 2^32 or under 2^-32

  // The units of a frame from `camera` (its distance to its target sets them; every MPI rank
  // has the same camera, so every rank the same units).
  static FrameUnits of(const Camera& camera);
  bool scaled() const { return unit != 1; }

  double length(double world) const { return world / unit; }
  Camera camera(const Camera& world) const;
  CellStatesView cells(const CellStatesView& world) const;
  // Positions and radii into `out` (its storage reused). A finite coordinate too large for a
  // float in frame units (a stray far beyond a tiny scene) becomes infinite: counted invalid.
  void spheres(std::span<const ParticleSphere> world, std::vector<ParticleSphere>& out) const;
  SpanOptions options(const SpanOptions& world) const;
  SurfaceOptions options(const SurfaceOptions& world) const;
  ShadeOptions options(const ShadeOptions& world) const;

  // A span image from frame units into world units (`world`: the frame's camera in world
  // units), and one from world units into frame units; a backdrop's wall depths likewise.
  void to_world(const SpanImage& frame, const Camera& world, SpanImage& out) const;
  void to_frame(const SpanImage& world, SpanImage& out) const;
  void to_frame(const Backdrop& world, Backdrop& out) const;
};

// `renderer` behind the same interface, each frame in FrameUnits::of(its camera): at ordinary
// scales it passes everything through; past them it keeps the frame's spheres in frame units
// (a copy) and converts what enters and leaves, so that callers see world units throughout.
std::unique_ptr<SurfaceRenderer> in_frame_units(std::unique_ptr<SurfaceRenderer> renderer);

}  // namespace voxspan
