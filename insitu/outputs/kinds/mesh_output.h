// insitu/outputs/kinds/mesh_output.h - outputs.mesh: the fluid's surface as a polygon mesh,
// <folder>/fluid_<step>.ply or .obj, for Blender and ParaView (insitu/outputs/formats/
// mesh_files.h has the surface and the files). Its settings, for the code that reads them by
// type (the tests).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/outputs/formats/mesh_files.h"

namespace voxspan {

struct MeshSettings : CloneAs<MeshSettings, OutputSettings> {
  MeshSettings() : CloneAs(false, "mesh", TriggerSpec{100, 0, false, true}) {}
  // Sphere radius of every particle (world units); nullopt = half the particle spacing, as the
  // VDB snapshot's (the render radius when the spacing is unknown).
  std::optional<double> radius;
  FluidMeshSettings surface;  // voxel size, closing, fill, adaptivity
  MeshFormat format = MeshFormat::ply;
  std::vector<std::string> attributes;  // per-vertex float properties (PLY only)
  std::span<const std::string> needed_attributes() const override { return attributes; }
  bool operator==(const MeshSettings&) const = default;
};

}  // namespace voxspan
