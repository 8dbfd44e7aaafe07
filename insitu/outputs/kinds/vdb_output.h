// insitu/outputs/kinds/vdb_output.h - outputs.vdb: an OpenVDB snapshot of the whole fluid,
// <folder>/fluid_<step>.vdb (insitu/outputs/formats/vdb_snapshot.h has the grids). Its settings,
// for the code that reads them by type (the tests).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/outputs/formats/vdb_snapshot.h"

namespace voxspan {

struct VdbSettings : CloneAs<VdbSettings, OutputSettings> {
  VdbSettings() : CloneAs(false, "snapshots", TriggerSpec{100, 0, false, true}) {}
  // Sphere radius of every particle in the level set (world units); nullopt = half the
  // particle spacing, so that the level set holds the particles' own volume (each particle
  // stands for a cube of one spacing), or the render radius when the spacing is unknown.
  std::optional<double> radius;
  VdbSnapshotSettings snapshot;         // voxel size, narrow band, closing, fill, cell states
  std::vector<std::string> attributes;  // particle attributes as float/vec3 grids
  std::span<const std::string> needed_attributes() const override { return attributes; }
  bool operator==(const VdbSettings&) const = default;
};

}  // namespace voxspan
