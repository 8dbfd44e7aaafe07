// insitu/outputs/kinds/level_set_outputs.h - what the outputs built on the fluid's level set
// (outputs.vdb: the level set itself; outputs.mesh: its surface) share: the keys of the level
// set, and the output itself but for the file it writes (the step copied on the solver's
// thread, in an MPI job every rank's part gathered on the root, and handed to the writer).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "insitu/config/schema.h"
#include "insitu/outputs/formats/vdb_snapshot.h"
#include "insitu/outputs/kinds/snapshot_copy.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {

// The level set's `voxel_size`, `closing` and `fill_inner` (`half_width` is the VDB's own).
std::vector<schema::Key<FluidLevelSetSettings>> fluid_level_set_keys();

// `radius` (the member `radius`: every particle's sphere radius, nullopt `auto`), then the
// level set's keys, of the settings S of an output whose member `level_set` holds the level
// set's settings (VdbSnapshotSettings, FluidMeshSettings).
template <class S, class L>
std::vector<schema::Key<S>> level_set_keys(std::optional<double> S::*radius, L S::*level_set) {
  static_assert(std::is_base_of_v<FluidLevelSetSettings, L>);
  std::vector<schema::Key<S>> keys{schema::number_or_auto(
      "radius", radius, schema::above(0),
      "sphere radius of every particle in the level set; `auto` = half the particle spacing, so "
      "that the level set holds the particles' own volume (the render radius when the spacing is "
      "unknown)")};
  for (schema::Key<FluidLevelSetSettings>& k : fluid_level_set_keys())
    keys.push_back(schema::rebased<S>(
        std::move(k), [level_set](auto& s) -> auto& { return s.*level_set; }));
  return keys;
}

// An output of the whole fluid, one file per step: on the solver's thread the boundary spheres
// (each of radius `radius`; nullopt: half the particle spacing, or their own radii when the
// spacing is unknown), the attributes it names and the cell states copied into a pooled slot;
// in an MPI job every rank's part gathered on the root first, so that the file holds the whole
// fluid with no seams where the ranks' parts meet. `write_file` writes the file on the writer's
// thread, on the root only; `label` names its jobs ("VDB snapshot"). A kind derives from it for
// the constructor from its settings that output_kind wants.
class LevelSetOutput : public Output {
 public:
  using WriteFile = std::function<void(const VdbSnapshotInput&)>;
  LevelSetOutput(const OutputContext& context, std::optional<double> radius,
                 AttributeNames attributes, const char* label, WriteFile write_file);

  // Collective in an MPI job (every rank, every step it is due).
  void write(const OutputStep& step) final;
  OutputTally tally() const final { return jobs_.tally(); }

 private:
  const char* const label_;
  const AttributeNames attributes_;
  const double radius_;  // 0: the spheres' own radii
  Communicator* const comm_;
  SnapshotCopy gathered_;  // with ranks: the job's whole snapshot, on the root
  PooledJobs<SnapshotCopy> jobs_;
};

}  // namespace voxspan
