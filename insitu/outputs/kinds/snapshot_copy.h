// insitu/outputs/kinds/snapshot_copy.h - what a snapshot output (OpenVDB, VTK) keeps of a render
// step for its writer job: the boundary spheres, the attributes it asked for and the cell
// states, copied into a pooled slot whose vectors keep their capacity.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "insitu/parallel/communicator.h"
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
  // In an MPI job, every rank's copy gathered on the root (collective): the spheres and the
  // attributes one after the other in rank order, the cell states of every rank's grid in one
  // grid over them all (they must share a cell size and lie on one lattice). Returns whether
  // this rank holds the whole (the root).
  bool gather(Communicator& comm);
  std::vector<AttributeSpan> attribute_spans() const;
};

}  // namespace voxspan
