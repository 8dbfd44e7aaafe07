// insitu/outputs/kinds/snapshot_copy.h - what a snapshot output (OpenVDB, VTK) keeps of a render
// step for its writer job: the boundary spheres, the attributes it asked for and the cell
// states, copied into a pooled slot whose vectors keep their capacity.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/parallel/communicator.h"
#include "voxspan/adapter.h"
#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// The attributes an output names, with its key for messages ("run.yaml:7:3:
// outputs.vdb.attributes").
struct AttributeNames {
  std::vector<std::string> names;
  std::string key;
};
// Those of `outputs.<kind>`.
inline AttributeNames attribute_names(const OutputSettings& s, std::string_view kind) {
  const std::span<const std::string> names = s.needed_attributes();
  const std::string path = "outputs." + std::string(kind) + ".attributes";
  return {{names.begin(), names.end()}, s.source.key_path("attributes", path)};
}

struct SnapshotCopy {
  std::vector<ParticleSphere> spheres;
  std::array<double, 3> origin{0, 0, 0};  // the spheres' (StepData::origin), every rank's
  std::vector<Attribute> attributes;
  CellStates cells;
  std::int64_t step = 0;
  double time = 0;

  // Copies the step; every sphere's radius becomes `radius` when it is > 0. Throws
  // voxspan::Error when the adapter did not compact one of `names`: with their key and what the
  // solver passes instead where it passes no such attribute.
  void fill(const StepData& data, const AttributeNames& names, double radius = 0);
  // In an MPI job, every rank's copy gathered on the root (collective): the spheres and the
  // attributes one after the other in rank order, the cell states of every rank's grid in one
  // grid over them all (they must share a cell size and lie on one lattice); the spheres as they
  // are, every rank's measured from the same origin (the adapter agrees on it). Returns whether
  // this rank holds the whole (the root).
  bool gather(Communicator& comm);
  std::vector<AttributeSpan> attribute_spans() const;
};

// In an MPI job, every rank's cell states in one grid on the root (collective; empty elsewhere),
// as SnapshotCopy::gather merges them.
CellStates gather_cells(Communicator& comm, const CellStatesView& mine);

}  // namespace voxspan
