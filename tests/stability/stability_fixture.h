// The stability suite's one way to run a scene: the same particles, camera and options through
// both renderers (the GL renderer on this binary's one context, llvmpipe without a GPU, and
// the CPU renderer), the spans read back and the picture shaded in all three modes, then held
// to what every case must show:
//   - finite pixels: no NaN or infinity in any channel of any mode's picture;
//   - bounded memory: at most `max_spans` spans per pixel (so spans <= pixels x cap), the
//     stats' stored and found counts those of the image, the layers within the grid's cap, and
//     the GL renderer's GPU memory under a bound stated in pixels, layers and particles;
//   - the spans within their stated error of the exact reference (render/reference): the GL
//     ones by the voxelization's bounds (tests/render/gl/test_voxelize_accuracy.cpp: counts and
//     boundaries within one layer on >= 99.5 % of pixels, the summed inside length within
//     1 % or 3/4 of a layer per boundary), the CPU ones equal to it up to float rounding (1e-3 of a
//     layer).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "render/cpu/cpu_renderer.h"
#include "render/float_image.h"
#include "render/frame_stats.h"
#include "render/gl/renderer.h"
#include "render/span_image.h"
#include "render/surface_renderer.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"

namespace voxspan::test {

inline constexpr std::array<ShadeMode, 3> kModes = {ShadeMode::opaque, ShadeMode::translucent,
                                                    ShadeMode::refractive};

struct Scene {
  std::string name;
  Particles particles;
  Camera camera;
  VoxelizeOptions voxelize;
  SurfaceOptions surfaces;
  CellStatesView cells;  // none by default
  // World size of the scene relative to a unit one: the shading's lengths (absorption, ground
  // tiles, AO radius) follow it, so that a scaled scene shades as its unit twin does.
  double scale = 1;
  double ground_tile = 0.1;
  double ground_height = -1;
};

ShadeOptions shading(const Scene& scene, ShadeMode mode);

struct Frame {
  SpanImage spans;
  std::array<FloatImage, 3> images;  // kModes' order
  FrameStats stats;
  FloatImage first_hit;  // render_as_view's; empty otherwise
};

Frame render_gl(const Scene& scene);
Frame render_cpu(const Scene& scene);
// The scene as a view renders it: through the surface-renderer interface of `backend` as
// make_surface_renderer gives it (frames far from unit scale in their own units,
// render/frame_units.h), with the first-hit distances.
Frame render_as_view(const Scene& scene, RenderBackend backend);

// Non-finite channels over all three pictures.
std::int64_t nonfinite_channels(const Frame& frame);

// What the checks measured, printed in one line per case and renderer.
struct Checked {
  Frame gl, cpu;
  SpanImage reference;  // exact, in the CPU renderer's grid
  SpanComparison gl_vs_reference;
  double cpu_worst_layers = 0;  // largest boundary difference of the CPU spans, in layers
  bool cpu_counts_equal = true;
};

// Both renderers and every check above, to the same bounds for every case.
struct Bounds {
  double count_match = 0.995, boundary_match = 0.995, inside_match = 0.995;
  double inside_sum_error = 0.01;   // relative, or
  double inside_sum_layers = 0.75;  // layers per boundary on average, whichever is larger
  double cpu_layers = 1e-3;
};
Checked check_both(const Scene& scene, const Bounds& bounds = {});

// The bound on the GL renderer's GPU memory in one frame (bytes), from what it must hold: the
// particles (16 B each), per pixel its span record, its picture and its AO (36 B), per span the
// span, its owner, links, normals and the filter's two depth buffers (52 B), the tile lists
// (4 B per entry), the bits and scratch of the image (or of one tile of the memory budget when
// smaller), plus 4 MiB for the passes' small and fixed buffers.
std::int64_t gpu_bytes_bound(const Scene& scene, const Frame& gl);

}  // namespace voxspan::test
