#include "render/surface_passes.h"

#include <algorithm>
#include <cmath>

#include "render/stat_names.h"

namespace voxspan {

namespace {
// n iterations of the kernel spread like a Gaussian of sqrt(n / 2) pixels.
double iterations_for_pixels(double radius) { return 2 * radius * radius; }
}  // namespace

// pixel(z) = 2 tan(fov_y / 2) / height * z.
double filter_iteration_scale(const PerspectiveGrid& grid, double radius) {
  const double pixel_at_unit_depth = 2 * grid.view().tan_half_y / grid.height();
  return iterations_for_pixels(radius / pixel_at_unit_depth);
}

double filter_iterations_at(const PerspectiveGrid& grid, double radius, double depth) {
  return std::ceil(filter_iteration_scale(grid, radius) / (depth * depth));
}

int filter_iteration_cap(const PerspectiveGrid& grid, const SurfaceOptions& options) {
  return static_cast<int>(
      std::ceil(iterations_for_pixels(options.max_screen_radius * grid.height())));
}

int filter_iterations(const PerspectiveGrid& grid, const SurfaceOptions& options) {
  if (options.filter_radius <= 0) return 0;
  // The nearest surface needs the most iterations.
  return static_cast<int>(
      std::min<double>(filter_iteration_cap(grid, options),
                       filter_iterations_at(grid, options.filter_radius, grid.near())));
}

void SurfacePasses::run(const PerspectiveGrid& grid, bool has_spans, const SurfaceOptions& surfaces,
                        const ShadeOptions& shade, Recorder& recorder) {
  validate(surfaces);
  validate(shade);
  {
    auto t = time(recorder, pass::connect);
    recorder.count(counter::links_unlinkable_spans, connect(surfaces));
  }
  {
    auto t = time(recorder, pass::filter);
    const int iterations = has_spans ? filter_iterations(grid, surfaces) : 0;
    filter(iterations, surfaces);
    recorder.count(counter::filter_iterations, iterations);
  }
  {
    auto t = time(recorder, pass::normals);
    normals(surfaces);
  }
  if (shade.deep_ao) {
    auto t = time(recorder, pass::deep_ao);
    deep_ao();
  }
  auto t = time(recorder, pass::shade);
  const RefractTally tally = this->shade(shade);
  if (shade.mode != ShadeMode::refractive) return;
  recorder.count(counter::refract_dispatches, tally.dispatches);
  recorder.count(counter::refract_unfinished, tally.unfinished);
  if (tally.events) recorder.count(counter::refract_events, *tally.events);
  if (tally.most_events) recorder.count(counter::refract_most_events, *tally.most_events);
}

}  // namespace voxspan
