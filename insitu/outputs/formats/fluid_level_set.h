// insitu/outputs/formats/fluid_level_set.h - the fluid's level set as OpenVDB grids: the "fluid"
// grid of the snapshot (vdb_snapshot.h says what it is) and the one the mesh output meshes
// (mesh_files.h), built by one function for both. Includes OpenVDB, whose templates compile
// slowly: for vdb_snapshot.cpp and mesh_files.cpp only.
#pragma once

#include <openvdb/openvdb.h>

#include <array>
#include <span>
#include <string_view>

#include "insitu/outputs/formats/vdb_snapshot.h"
#include "render/frame_stats.h"
#include "voxspan/cell_states.h"
#include "voxspan/stopwatch.h"

namespace voxspan {

// Times consecutive stages into `stats` as "<prefix><name>": next() ends the running stage and
// starts another.
class Stages {
 public:
  Stages(FrameStats& stats, std::string_view prefix) : stats_(stats), prefix_(prefix) {}
  ~Stages() { stop(); }
  Stages(const Stages&) = delete;
  Stages& operator=(const Stages&) = delete;
  void next(std::string_view name) {
    stop();
    name_ = name;
    watch_.restart();
  }
  void stop() {
    if (!name_.empty()) stats_.add_time(std::string(prefix_) + std::string(name_), watch_.ms());
    name_ = {};
  }

 private:
  FrameStats& stats_;
  std::string_view prefix_, name_;
  Stopwatch watch_;
};

// Per voxel, the index of its closest particle (ParticlesToLevelSet's attribute transfer).
using ClosestParticleGrid = openvdb::FloatGrid::ValueConverter<openvdb::Index32>::Type;

struct FluidLevelSet {
  openvdb::FloatGrid::Ptr sdf;  // "fluid": narrow band of settings.half_width voxels
  // Over the band as it was before the closing eroded it (wider by the closing distance), so
  // that it covers the final surface; indices into the particles given. Null without particles.
  ClosestParticleGrid::Ptr closest;
};

// The union of the valid particles' spheres, closed by settings.closing, the inner-full cells
// filled (vdb_snapshot.h, "fluid"), in the particles' frame: world coordinates less `origin`
// (StepData::origin; the cells are in world coordinates), where floats hold them finely.
// Fills `report`; times the stages "rasterize", "fill" and "close" with `stages`. Throws
// voxspan::Error, its message starting with `what`, when the voxel size is not a positive number.
FluidLevelSet build_fluid_level_set(std::span<const ParticleSphere> particles,
                                    const std::array<double, 3>& origin,
                                    const CellStatesView& cells,
                                    const FluidLevelSetSettings& settings, std::string_view what,
                                    FluidLevelSetReport& report, Stages& stages);
// The level set's grids moved from the particles' frame to the world's: `origin` goes into
// their transforms, in double.
void move_to_world(FluidLevelSet& ls, const std::array<double, 3>& origin);

}  // namespace voxspan
