// render/perspective_grid.h - the view-aligned voxel grid of [ZD15] sec. 4.2: one column of
// voxels per pixel, depth layers spaced logarithmically, d_i = d_0 (1 + K_d)^i, with
// K_d = tan(alpha) * 2 tan(fov_y / 2) / height, so that the steepest step one layer makes
// between neighbouring columns is the normal-angle resolution alpha everywhere in depth.
//
// Depth is view-space z in world units (distance from the eye's plane along the view
// direction); a pixel's ray meets depth z at eye + z * world_ray(x, y), and a depth interval dz
// is dz * ray_scale(x, y) long in the world. Layer i is the slab [d_i, d_{i+1}).
//
// fit() fits d_0 and the far depth to the particles the camera sees, so no layer is spent on
// empty depth; the layer count is rounded up to whole 32-bit words and capped by
// GridOptions::max_layers. When the cap bites, K_d grows so that the capped layers still span
// [near, far]: alpha_degrees() then reports the coarser angle actually reached.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>

#include "render/camera.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct GridOptions {
  double alpha_degrees = 14;  // normal-angle resolution ([ZD15] sec. 5.1: 14 deg)
  int max_layers = 16384;     // cap on the layer count; a positive multiple of 32
  // The near plane is never closer than min_near (world units) nor than min_near_fraction of
  // the far depth: with the camera inside the fluid, the layers start there.
  double min_near = 0;
  double min_near_fraction = 0.01;
};

// Throws voxspan::Error naming the option that is out of range.
void validate(const GridOptions& options);

// What the framing saw: every particle is in exactly one class.
struct CullCounts {
  std::int64_t visible = 0;
  std::int64_t invalid = 0;  // NaN or infinite coordinate, or radius not > 0
  std::int64_t behind = 0;   // entirely behind the camera or before the near plane
  std::int64_t outside = 0;  // outside the view pyramid's four side planes
};

// The depth range of the visible spheres, and what was seen.
struct DepthRange {
  double lo = std::numeric_limits<double>::infinity();   // nearest depth
  double hi = -std::numeric_limits<double>::infinity();  // farthest depth
  CullCounts counts;
};

// Combines this process's depth range with those of the other processes that voxelize into the
// same grid (MPI ranks: lo the least, hi the greatest, counts summed), so that every one fits
// the same near, far and layers. Empty: one process.
using DepthRangeCombine = std::function<DepthRange(const DepthRange&)>;

// Pixels a sphere may cover, inclusive; empty when x0 > x1 or y0 > y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
  std::int64_t area() const { return empty() ? 0 : std::int64_t(x1 - x0 + 1) * (y1 - y0 + 1); }
};

class PerspectiveGrid {
 public:
  PerspectiveGrid() = default;

  // Fits near and far to the valid spheres inside the frustum (CullCounts says what was left
  // out). With no visible sphere the grid is empty(): zero layers.
  // `combine` (when set) makes the fit global: called once or twice on every process alike.
  static PerspectiveGrid fit(const Camera& camera, std::span<const ParticleSphere> particles,
                             const GridOptions& options, CullCounts* counts = nullptr,
                             const DepthRangeCombine& combine = {});
  // A grid over the depth range [near, far] as given (0 < near < far).
  static PerspectiveGrid over(const Camera& camera, double near, double far,
                              const GridOptions& options);
  // This grid in units `factor` times smaller (its depths times `factor`: the same layers),
  // seen from `camera`, this grid's camera in those units (render/frame_units.h).
  PerspectiveGrid rescaled(const Camera& camera, double factor) const;

  const Camera& camera() const { return camera_; }
  const ViewFrame& view() const { return view_; }
  int width() const { return view_.width; }
  int height() const { return view_.height; }

  bool empty() const { return layers_ == 0; }
  double near() const { return near_; }                     // d_0
  double far() const { return far_; }                       // farthest depth of the visible spheres
  double grid_far() const { return layer_depth(layers_); }  // d_L >= far
  int layers() const { return layers_; }                    // L, a multiple of 32
  int words_per_column() const { return layers_ / 32; }
  double k_d() const { return k_d_; }
  double log2_step() const { return log2_step_; }  // log2(1 + K_d)
  // The angle resolution reached: the one asked for unless the layer cap bit.
  double alpha_degrees() const { return alpha_degrees_; }
  int layers_needed() const { return layers_needed_; }  // before rounding and the cap
  bool layer_cap_hit() const { return layer_cap_hit_; }

  double layer_depth(double i) const;   // d_i
  double layer_of(double depth) const;  // fractional i with d_i = depth
  // Thickness of the layer that holds `depth` (clamped to the grid): d_{i+1} - d_i.
  double layer_thickness(double depth) const;

  // Pixel bounds of a sphere given in view space: the pixels whose centres lie within the
  // bounds of its silhouette (exact tangents, plus 0.01 pixel), so every pixel whose centre ray
  // meets the sphere is inside. Empty when the sphere is outside the frustum's sides or behind
  // the eye; the whole image when the sphere reaches the eye's plane.
  PixelRect sphere_pixels(glm::dvec3 view_center, double radius) const;

 private:
  static PerspectiveGrid with_frame(const Camera& camera, const GridOptions& options);
  DepthRange survey(std::span<const ParticleSphere> particles, double floor) const;
  void set_depth_range(double near, double far, const GridOptions& options);

  Camera camera_;
  ViewFrame view_;
  double near_ = 0, far_ = 0, k_d_ = 0, log2_step_ = 0, alpha_degrees_ = 0;
  int layers_ = 0, layers_needed_ = 0;
  bool layer_cap_hit_ = false;
};

}  // namespace voxspan
