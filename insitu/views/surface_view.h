// insitu/views/surface_view.h - views[i] of kind `surface` (the default): the fluid's surfaces
// from the span image, shaded opaque, translucent or refractive ([ZD15]). Its stages:
//   voxelize (sec. 3.1-4.4) -> the span stages of the context (none in one process; MPI
//   compositing) -> connect, filter, normals, deep AO (3.3-3.6) -> shade (3.5) -> read back,
// and, when an output asks, the first-hit distance of every pixel (render/gl/passes/first_hit.h).
// With `color_by`, the first surface coloured by an attribute SPH-interpolated there
// (insitu/views/surface_colors.h). With `slice`, an SPH slice plane (insitu/views/slice_layer.h)
// drawn where it lies nearer than the first surface (opaque over the water: it shows where the
// plane leaves the fluid or where the water in front of it was cut away; a particles view can cut).
// Its settings, for the code that reads them by type (tests, tools).
//
// Reads: the step's boundary spheres and cell states, the camera, the fluid's box (the ground
// plane lies under it). Writes: the picture (and depth) in host memory, storage reused.
// Costs: the renderer's passes (render/README.md, render/SHADING.md) plus one read-back of
// width x height x 16 bytes per image.
#pragma once

#include <cstdint>
#include <optional>

#include "insitu/config/settings.h"
#include "insitu/views/scenery.h"
#include "insitu/views/slice_layer.h"
#include "insitu/views/view_keys.h"
#include "render/shade_options.h"

namespace voxspan {

inline Vec3d array_of(glm::dvec3 v) { return {v.x, v.y, v.z}; }

// Its colouring by an attribute at the first surface (insitu/views/surface_colors.h): color_by
// empty gives the shading's own colours.
struct SurfaceSettings : CloneAs<SurfaceSettings, ViewSettings>, ColorBySettings {
  ShadeMode shading = ShadeMode::translucent;
  bool deep_ao = false;
  double alpha_degrees = 14;  // normal-angle resolution of the depth layers ([ZD15], 4.2)
  std::optional<double> gap;  // gap-bridging distance, world units; nullopt = auto (spacing)
  int max_spans = 0;          // stored spans per pixel; 0 = no cap (exact lists)
  std::optional<double> filter_radius;  // world units; nullopt = auto; 0 = off
  int max_layers = 16384;               // cap on depth layers, a multiple of 32 (paper: 16384)
  std::optional<Vec3d> absorption;      // Beer-Lambert, per world unit, RGB; nullopt = auto
  double ior = 1.33;                    // refractive index (refractive mode)
  int bounces = 3;                      // refraction/reflection bounces (refractive mode)
  // What surrounds the fluid (render/model/environment.glsl): the ground plane's height
  // (nullopt = the floor under the fluid) and checker side (nullopt = 12 spacings), and the
  // colours, by default render/shade_options.h's.
  std::optional<double> ground_height, ground_tile;
  Vec3d ground_light = array_of(Environment{}.ground_light);
  Vec3d ground_dark = array_of(Environment{}.ground_dark);
  Vec3d sky_zenith = array_of(Environment{}.sky_zenith);
  Vec3d sky_horizon = array_of(Environment{}.sky_horizon);
  SliceField slice;  // an SPH slice plane in the view; quantity empty: none
  ScenerySettings scenery;
  bool operator==(const SurfaceSettings&) const = default;
};

}  // namespace voxspan
