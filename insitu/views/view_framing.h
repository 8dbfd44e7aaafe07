// insitu/views/view_framing.h - the camera of a view on each render step: as given (manual), or
// framed automatically around the fluid.
//
// Automatic framing looks along the configured direction at the box of the boundary
// particles' spheres (they enclose the fluid: every cell next to air or a surface is a
// boundary cell) without those far from the bulk (BulkBox), or at the configured `bounds`,
// from the nearest distance at which all eight corners of the box, moved out
// from its centre by `margin`, lie inside the view pyramid. Which box follows the fluid is the
// view's `framing`: grown over every render step so far (default; the camera only backs away,
// so a video of the run does not jitter), refitted on each step, or kept from the first step.
// Pure CPU, no GL: a few hundred nanoseconds per view plus one pass over the boundary spheres.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/views/legend.h"
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
  // The box moved by `by` (nothing when empty).
  void move(const std::array<double, 3>& by);
  // The box of the spheres (centre +- radius); NaN/inf positions and radii <= 0 are skipped.
  static Bounds of_spheres(std::span<const ParticleSphere> spheres);
};

// The box automatic framing looks at: the fluid's bulk, without the spheres far from it (a
// solver's escaped particles: one at 2 m from a 0.2 m block made every frame a dot). Per axis,
// the spheres' centres are binned over their range (kBulkBins bins); nonempty bins closer than
// kBulkGapDiameters mean diameters are one body of fluid; bodies at either end that hold under
// kStrayShare of the spheres are left out and counted, all the others framed. Four phases, so
// that an MPI job reduces between them (insitu/runtime/step_scene.h): the ranks' ranges
// (min/max), their histograms (sum), then the box (min/max) and what it left out (sum).
struct BulkBox {
  static constexpr int kBulkBins = 4096;
  static constexpr double kBulkGapDiameters = 8;
  static constexpr double kStrayShare = 0.01;

  // 1. The centres' range (lo/hi: reduce by min/max), how many spheres and their radii's sum
  // (reduce by sum).
  struct Range {
    Bounds centres;
    std::array<double, 2> count_and_radii{0, 0};
  };
  static Range range(std::span<const ParticleSphere> spheres);
  // 2. Per axis kBulkBins counts of centres over the range (reduce by sum), axis-major; each
  // of kBulkChunks chunks of the spheres counts into its own part of `scratch` (kept by the
  // caller: nothing allocated once sized).
  static constexpr std::size_t kBulkChunks = 16;
  static void histogram(std::span<const ParticleSphere> spheres, const Range& range,
                        std::vector<std::int64_t>& scratch, std::vector<std::int64_t>& bins);
  // 3. The centres kept, per axis, from the summed histogram.
  static Bounds kept(const Range& range, std::span<const std::int64_t> bins);
  // 4. The box of the kept spheres (centre +- radius; reduce by min/max), and the centres of
  // those left out: their box (min/max) and count (sum).
  struct Split {
    Bounds box, left_out_box;
    std::int64_t left_out = 0;
  };
  static Split split(std::span<const ParticleSphere> spheres, const Bounds& kept);
};

// The four phases on one process.
BulkBox::Split bulk_box(std::span<const ParticleSphere> spheres);

// The axis (0, 1, 2) along which every particle's centre has the same coordinate, from the
// centres' box (BulkBox::Range::centres): a 2D run, which PySPH stores in the plane z = 0 and
// DualSPHysics in y = const. -1 for a 3D fluid, a line of particles, one point or none.
int flat_axis(const Bounds& centres);

// The camera that frames `box` as the view says (automatic framing), or the manual camera.
// An empty box (no particle yet) gives a camera that looks at the origin from 1 unit away.
// Automatic framing fits the box between the picture's `clear` margins (what the view's
// legends cover): the box's centre at the middle of the space between them, the camera moved
// sideways rather than turned, so that it still looks along `direction`. A 2D fluid (`flat`:
// flat_axis) with `direction` and `up` left at their defaults is seen head-on, its plane's
// upward axis up (head_on_orientation).
Camera frame_camera(const CameraConfig& camera, int width, int height, const Bounds& box,
                    const LegendMargins& clear = {}, int flat = -1);
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
  // `clear`: the margins the view's legends cover (View::legend_margins).
  explicit ViewFraming(const ViewSettings& view, const LegendMargins& clear = {})
      : camera_(view.camera), width_(view.width), height_(view.height), clear_(clear) {}
  // The camera for this render step's boundary spheres.
  Camera update(std::span<const ParticleSphere> boundary);
  // The same from this step's box of them (with MPI: the box of every rank's) and the fluid's
  // flat axis (flat_axis; -1: a 3D fluid).
  Camera update(const Bounds& step_box, int flat = -1);
  // The fluid's box as the framing follows it (the grown box under `grow`), kept for manual
  // cameras too (the ground plane of the environment goes under it).
  const Bounds& box() const { return box_; }
  // The point the camera's turns (Cinema's angles) go about: the box's centre under automatic
  // framing (the camera may stand beside it, clear of a legend), the target of a manual camera.
  glm::dvec3 pivot() const;
  // Whether the last update grew the box's largest side over 4 times (a far particle joined
  // the fluid's bulk, or the fluid really spread): the views say so.
  bool jumped() const { return jumped_; }

 private:
  CameraConfig camera_;
  int width_, height_;
  LegendMargins clear_;
  Bounds box_;
  bool jumped_ = false;
};

}  // namespace voxspan
