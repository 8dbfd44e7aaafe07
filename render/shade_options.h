// render/shade_options.h - how the passes after the voxelization turn spans into a picture
// ([ZD15] sec. 3.3-3.6): the surface filter, the shading mode, the fluid's material, the
// environment around it and deep ambient occlusion. Units are world units throughout.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "render/enum_names.h"

namespace voxspan {

// The filter of sec. 3.4 / 4.6: iterated 3x3 smoothing of reciprocal depth along the surface
// links. A surface point at depth z gets n(z) = ceil(2 (radius / pixel(z))^2) iterations
// (pixel(z) = the pixel's width at depth z; n iterations of the kernel spread like a Gaussian of
// sqrt(n / 2) pixels), so the smoothing radius is about `radius` in the world at every
// distance, up to `max_screen_radius` of the picture's height. Only points linked across (the same
// surface in the neighbour pixel) are used, so silhouettes keep their depth and a lone droplet
// stays; no point moves more than `radius`, spans of a column never cross, and a thin sheet's two
// sides move alike (where they would cross, they meet), so spray and thin sheets survive.
struct SurfaceOptions {
  double filter_radius = 0;  // world units; 0 = no filter
  // The cap on the filter's radius on the screen, as a share of the picture's height: it bounds
  // the reads per pixel (about 8 radii in pixels per pass) where the surface comes close to the
  // eye, and, being a share, smooths a picture alike at every size (a cap in pixels, or in
  // iterations, leaves the particles' bumps at 1920x1080 that it smooths away at 640x360).
  double max_screen_radius = 1.0 / 40;
  // Folds (render/model/links.glsl): neighbouring pixels' surface points linked across a
  // depth step longer than this (world units, along the view axis) lie on two sheets of a
  // folded surface, the nearer hiding the other, and are not linked; 0 = no folds.
  double fold_step = 0;
};

enum class ShadeMode { opaque, translucent, refractive };
inline constexpr EnumName<ShadeMode> kShadeModeNames[] = {{"opaque", ShadeMode::opaque},
                                                          {"translucent", ShadeMode::translucent},
                                                          {"refractive", ShadeMode::refractive}};
inline const char* shade_mode_name(ShadeMode mode) { return name_of(kShadeModeNames, mode).data(); }

// The fluid: Beer-Lambert absorption per world unit (RGB), refractive index, the light it
// scatters towards the eye when deep (translucent and refractive modes) and its colour as an
// opaque surface. The default absorption is clear water's in metres.
struct Material {
  glm::dvec3 absorption{0.45, 0.12, 0.05};
  double ior = 1.33;
  glm::dvec3 scatter_color{0.02, 0.06, 0.09};
  glm::dvec3 albedo{0.35, 0.55, 0.8};

  // Clear water's tint (the default absorption's proportions) at any scale: red keeps a
  // tenth of its light through `depth` world units of fluid, green and blue more.
  static glm::dvec3 water_absorption(double depth);
};

// A sky gradient over an infinite ground plane dot(x, up) = ground_height carrying a checker of
// side ground_tile, fading into the horizon colour over ground_fade, and a directional sun.
struct Environment {
  // The fluid rests on a floor at `floor_height` (where an SPH solver's wall lies, half a
  // `spacing` under its lowest particles): the ground there, and the contact up to those
  // particles' centres, so that no ray meets the union's bumpy bottom as a free surface.
  void rest_on_floor(double floor_height, double spacing) {
    ground_height = floor_height;
    ground_contact = 0.5 * spacing;
  }

  glm::dvec3 up{0, 1, 0};
  // The world point a frame's (0, 0, 0) stands for (render/frame_origin.h): a frame far from the
  // world's origin is rendered shifted, and the ground's plane and checker shift back with it
  // (in double on the host), so that they stay where the world has them.
  glm::dvec3 origin{0};
  double ground_height = 0;  // world units, as the other lengths here
  double ground_tile = 0.1;
  double ground_fade = 0;  // 0: 40 tiles
  // Up to this height above the ground the fluid's lower surface rests on it: a ray leaving the
  // fluid there downwards goes on unbent to the ground (column_march.glsl); 0: nowhere.
  double ground_contact = 0;
  // The same against the walls of a backdrop (render/backdrop.h), in view depth: a ray leaving
  // the fluid within this depth in front of its column's walls goes on unbent to them.
  double wall_contact = 0;
  glm::dvec3 sky_zenith{0.22, 0.42, 0.8};
  glm::dvec3 sky_horizon{0.78, 0.84, 0.9};
  glm::dvec3 ground_light{0.8, 0.76, 0.68};
  glm::dvec3 ground_dark{0.28, 0.26, 0.24};
  glm::dvec3 sun_direction{0.35, 1.0, 0.45};  // towards the sun; normalized when used
  glm::dvec3 sun_color{1.0, 0.96, 0.88};
};

// Deep ambient occlusion of the front surface (sec. 3.6) from all stored layers within
// `radius` (world units).
struct AoOptions {
  double radius = 0.05;
  double strength = 1.0;
  int samples = 16;  // columns sampled per pixel, 1..64
};

struct ShadeOptions {
  ShadeMode mode = ShadeMode::translucent;
  Material material;
  Environment environment;
  bool deep_ao = false;
  AoOptions ao;
  int bounces = 3;          // refractive mode: hits past the first entry that bend the ray
  int march_budget = 1024;  // refractive mode: column events per ray per dispatch, 1..1024
                            // (an event loops at most ~30 times in binary searches, and
                            // llvmpipe stops an invocation after 65535 loop iterations)
};

// Refractive mode: march dispatches at most (each advances every ray by march_budget events):
// enough for every path of the bounces to cross the image twice over and every boundary of the
// fullest column (`most_spans` spans) twice; rays still marching then leave to the environment
// (and are counted).
int refract_dispatch_limit(int width, int height, std::uint32_t most_spans,
                           const ShadeOptions& options);

// Throw voxspan::Error naming the option that is out of range.
void validate(const SurfaceOptions& options);
void validate(const ShadeOptions& options);

}  // namespace voxspan
