// insitu/views/scenery.h - the solver's walls and obstacles (Adapter::set_scenery) as opaque
// solids behind and around the fluid of a surface view: the union of their spheres cast exactly
// on the CPU whatever the view's renderer (render/cpu/cpu_renderer.h), smoothed and lit like
// the fluid's opaque surface in the scenery's own colour, and handed to the view's renderer as
// the backdrop (render/backdrop.h) that it shows behind the fluid and cuts the fluid's spans at.
// Walls rarely move and the camera seldom does: the backdrop is made again only when the
// camera, the scenery or the environment changes.
//
// Cutaway: a closed tank seen from outside hides its water. Like a doll's house, the walls
// nearest the camera are left out: along each ray a wall surface that lies on the scenery's
// outer box (within a sphere's radius of its faces) is dropped when more scenery follows it
// behind, so the tank's near walls and lid go and its far walls and floor stay; a floor alone,
// or a wall with nothing behind it, stays.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "insitu/config/schema.h"
#include "insitu/config/settings.h"
#include "insitu/views/view_framing.h"
#include "render/backdrop.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "render/recorder.h"
#include "render/shade_options.h"

namespace voxspan {

class CpuRenderer;

struct ScenerySettings {
  bool draw = true;              // draw the scenery the solver gives
  Vec3d color{0.5, 0.45, 0.38};  // linear RGB albedo: warm sandstone, apart from the water's blues
  bool cutaway = true;           // leave out the walls facing the camera
  bool operator==(const ScenerySettings&) const = default;
};

const schema::Section<ScenerySettings>& scenery_section();

// A render step's scenery as the views see it: its spheres (on an MPI job's root every rank's,
// elsewhere the rank's own), a version that changes whenever they do (0: none ever given), and
// the box of every rank's spheres (empty: none).
struct Scenery {
  std::span<const ParticleSphere> spheres;
  std::uint64_t version = 0;
  Bounds box;
};

namespace pass {
inline constexpr StatName scenery{"scenery"};  // the walls' backdrop, when made anew
}  // namespace pass

// Per pixel, the scenery spans to draw: those of `spans` after the cutaway's (see above) into
// `out` (buffers reused), for a scenery whose spheres' box is `box`. Exposed for its tests.
void cut_away(const SpanImage& spans, const Bounds& box, double margin, SpanImage& out);

class SceneryLayer {
 public:
  SceneryLayer(const ScenerySettings& settings, double spacing);
  ~SceneryLayer();

  // The backdrop of a frame from `camera` with the fluid's `shade` options (their environment
  // surrounds the walls), made again only when the camera, the scenery (`version`) or the
  // environment changed; null when there is no scenery or the view does not draw it. `box`:
  // the scenery spheres' box. Timed as pass::scenery.
  const Backdrop* backdrop(const Camera& camera, std::span<const ParticleSphere> scenery,
                           std::uint64_t version, const Bounds& box, const ShadeOptions& shade,
                           Recorder& recorder);

 private:
  void render(const Camera& camera, std::span<const ParticleSphere> scenery, const Bounds& box,
              const ShadeOptions& shade);

  const ScenerySettings settings_;
  const double spacing_;
  std::unique_ptr<CpuRenderer> renderer_;  // made with the first backdrop
  std::vector<ParticleSphere> spheres_;    // in the frame's units, when it has its own
  SpanImage drawn_;                        // the scenery's spans after the cutaway
  FloatImage picture_;
  Backdrop backdrop_;
  // What the backdrop was made from.
  Camera camera_;
  std::uint64_t version_ = 0;
  ShadeOptions shade_;
};

}  // namespace voxspan
