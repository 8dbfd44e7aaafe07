// insitu/runtime/step_scene.h - what a render step's views frame and show besides the fluid,
// the same on every rank of an MPI job: the box of the fluid's bulk (BulkBox of
// insitu/views/view_framing.h over every rank's boundary spheres; spheres far from it left out,
// said in a warning when they first appear and again when their number has doubled) and the
// scenery (insitu/views/scenery.h: this process's walls, or on an MPI job's root every rank's,
// gathered again only when some rank gives new ones).
//
// Reads the step's boundary spheres and scenery; collective under MPI: every rank calls both
// on every render step. Cost: two passes over the boundary spheres and, with ranks, a few small
// reductions (the histogram's 3 x 4096 counts the largest); nothing allocated once sized.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "insitu/views/scenery.h"
#include "insitu/views/view_framing.h"
#include "sim_adapter/voxspan/adapter.h"

namespace voxspan {

class Communicator;

// A point as a log line writes it: (x, y, z).
std::string point_text(const std::array<double, 3>& p);

class StepScene {
 public:
  // `comm`: null in one process; with ranks the root says the warnings.
  explicit StepScene(Communicator* comm) : comm_(comm) {}

  // This step's box of the boundary spheres over every rank, without those far from the bulk,
  // in world coordinates: the spheres' own are measured from `origin` (StepData::origin).
  Bounds fluid_box(std::span<const ParticleSphere> boundary, const std::array<double, 3>& origin);
  // The axis every particle's centre lies flat along at the last fluid_box (flat_axis: a 2D
  // run), -1 for a 3D fluid.
  int flat_axis() const { return flat_axis_; }

  // The scenery for this step's views, brought up to `data`'s.
  const Scenery& update_scenery(const StepData& data);
  // The scenery as the last update left it.
  const Scenery& scenery() const { return scenery_; }

 private:
  void tell_strays(const BulkBox::Split& split);

  Communicator* const comm_;
  std::vector<std::int64_t> bulk_scratch_, bulk_bins_;
  std::int64_t strays_told_ = 0;
  int flat_axis_ = -1;
  Scenery scenery_;
  std::vector<ParticleSphere> scenery_spheres_;  // every rank's, on the root of an MPI job
};

}  // namespace voxspan
