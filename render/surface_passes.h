// render/surface_passes.h - the passes both renderers run on a frame's span image ([ZD15] sec.
// 3.3-3.6), in order, with the names they are timed under and the counts they report, written
// once here:
//   connect (3.3)  -> links.unlinkable_spans
//   filter (3.4, 4.6; the iteration rule below) -> filter.iterations
//   normals (3.4, 4.5)
//   deep AO (3.6), when ShadeOptions::deep_ao
//   shade (3.5: opaque, translucent or refractive) -> refract.* in refractive mode
// Each renderer implements the steps (the GL passes in render/gl/renderer.cpp, the CPU
// renderer's loops over the model files in render/cpu/cpu_renderer.cpp); the rules inside the
// steps are written once too, in render/model/*.glsl.
#pragma once

#include <cstdint>
#include <optional>

#include "render/perspective_grid.h"
#include "render/recorder.h"
#include "render/shade_options.h"

namespace voxspan {

// The filter's iteration rule (SurfaceOptions): a point at depth z stands for
// n(z) = ceil(2 (radius / pixel(z))^2) iterations of the 3x3 kernel, capped, which its four
// passes give (render/model/surface_filter.glsl).
inline constexpr int kFilterPasses = 4;
// The `scale` of n(z) = ceil(scale / z^2): 2 (radius / pixel(1))^2.
double filter_iteration_scale(const PerspectiveGrid& grid, double radius);
// The iterations a point at `depth` gets, before the cap.
double filter_iterations_at(const PerspectiveGrid& grid, double radius, double depth);
// The most iterations a point gets: those of a radius of `max_screen_radius` of the height.
int filter_iteration_cap(const PerspectiveGrid& grid, const SurfaceOptions& options);
// The iterations a frame stands for: those of its nearest depth, capped; 0 with the filter off.
int filter_iterations(const PerspectiveGrid& grid, const SurfaceOptions& options);

// What the refractive shade did.
struct RefractTally {
  int dispatches = 0;                  // march dispatches (refract_dispatch_limit)
  std::int64_t unfinished = 0;         // rays still marching after the last one (sent to the sky)
  std::optional<std::int64_t> events;  // column events, all rays (GL only)
  std::optional<std::int64_t> most_events;  // by one ray in one dispatch (GL only)
};

// One renderer's steps. run() calls them in the order above on the renderer's current span
// image, each inside a scope of the renderer's clock (time()).
class SurfacePasses {
 public:
  // `grid` and `has_spans`: the span image's. Options are validated first.
  void run(const PerspectiveGrid& grid, bool has_spans, const SurfaceOptions& surfaces,
           const ShadeOptions& shade, Recorder& recorder);

 protected:
  ~SurfacePasses() = default;
  virtual Recorder::Scope time(Recorder& recorder, StatName pass) = 0;  // host or device
  // Returns the spans no link can name.
  virtual std::int64_t connect(const SurfaceOptions& options) = 0;
  // `iterations` 0: no filter, the span depths are the surface's.
  virtual void filter(int iterations, const SurfaceOptions& options) = 0;
  virtual void normals(const SurfaceOptions& options) = 0;
  virtual void deep_ao() = 0;
  virtual RefractTally shade(const ShadeOptions& options) = 0;  // a tally in refractive mode
};

}  // namespace voxspan
