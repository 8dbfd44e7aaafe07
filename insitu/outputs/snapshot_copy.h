// insitu/outputs/snapshot_copy.h - what a snapshot output (OpenVDB, VTK) keeps of a render
// step for its writer job: the boundary spheres, the attributes it asked for and the cell
// states, copied into a pooled slot whose vectors keep their capacity.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "voxspan/adapter.h"
#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct SnapshotCopy {
  std::vector<ParticleSphere> spheres;
  std::vector<Attribute> attributes;
  CellStates cells;
  std::int64_t step = 0;
  double time = 0;

  // Copies the step; every sphere's radius becomes `radius` when it is > 0. Throws
  // voxspan::Error when the adapter did not compact one of `names`.
  void fill(const StepData& data, std::span<const std::string> names, double radius = 0);
  std::vector<AttributeSpan> attribute_spans() const;
};

}  // namespace voxspan
