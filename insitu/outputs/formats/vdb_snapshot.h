// insitu/outputs/formats/vdb_snapshot.h - an OpenVDB snapshot of the whole fluid for offline work
// (Houdini, Blender, ParaView), from what the renderer already has: the boundary particles and the
// cell states.
//
// Grids in the file:
//   "fluid"       FloatGrid, level set (narrow band, `half_width` voxels each side): the union
//                 of the boundary particles' spheres, closed by `closing` (dilate the spheres
//                 by it, erode the result by it: the gaps between neighbouring spheres close
//                 and the outer surface stays where the spheres put it), with every inner-full
//                 cell filled in, so the interior is solid although its particles were left
//                 out ([ZD15] sec. 3.1: only boundary particles leave the solver).
//   <attribute>   FloatGrid or Vec3SGrid per requested particle attribute, on the voxels near
//                 the boundary particles, each voxel holding its closest particle's value.
//   "cell_state"  Int32Grid, one voxel per simulation cell (voxel centres at cell centres),
//                 value = the state byte of voxspan/cell_states.h; background 4 (inner-empty,
//                 as space outside the grid is), active where the state is anything else.
// File metadata: step, time, voxspan version, particle and cell counts.
// Cost: linear in the boundary particles' narrow-band voxels; the fill is one mask fill per
// inner-full cell. Everything OpenVDB stays inside vdb_snapshot.cpp (and fluid_level_set.cpp,
// which builds "fluid" for it and for the mesh).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>

#include "render/frame_stats.h"
#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// The "fluid" level set's settings and what building it found: the snapshot's and the mesh's
// (mesh_files.h), which is the zero level set of the same grid.
struct FluidLevelSetSettings {
  std::optional<double> voxel_size;  // nullopt: the smallest particle radius
  int half_width = 3;
  std::optional<double> closing;  // nullopt: the largest particle radius; 0: no closing
  bool fill_inner = true;
  bool operator==(const FluidLevelSetSettings&) const = default;
};

struct FluidLevelSetReport {
  double voxel_size = 0;
  double closing = 0;
  std::size_t particles = 0;            // rasterized
  std::size_t particles_too_small = 0;  // radius + closing under 1.5 voxels: left out
  std::size_t particles_invalid = 0;    // NaN/inf position or non-positive radius: left out
  std::size_t inner_full_cells = 0;     // filled
};

struct VdbSnapshotSettings : FluidLevelSetSettings {
  bool cell_states = true;
  bool operator==(const VdbSnapshotSettings&) const = default;
};

struct VdbSnapshotInput {
  std::span<const ParticleSphere> particles;  // the boundary particles
  CellStatesView cells;                       // may be empty: no fill, no cell-state grid
  std::span<const AttributeSpan> attributes;  // one tuple per boundary particle
  std::int64_t step = 0;
  double time = 0;
  std::array<double, 3> origin{0, 0, 0};  // the particles' (StepData::origin)
};

struct VdbSnapshotReport : FluidLevelSetReport {
  std::uint64_t level_set_voxels = 0;  // active voxels of "fluid"
  std::uint64_t bytes = 0;             // file size
  // Wall time per stage: "vdb_rasterize", "vdb_fill", "vdb_close", "vdb_attributes",
  // "vdb_write" (for the per-step stats).
  FrameStats timings;
};

// openvdb::initialize(), once per process. The outputs call it when they are made, on the
// solver's thread: initialized first on the writer thread, its statics would be newer than the
// exit handler that drains the writer (sim_adapter/adapter.cpp) and gone before it runs.
void ensure_openvdb_initialized();

// Builds the grids and writes them atomically (temp name, fsync when sync, rename). Throws
// WriteError on I/O failure, voxspan::Error on bad input (attribute sizes, voxel size).
VdbSnapshotReport write_vdb_snapshot(const std::filesystem::path& path,
                                     const VdbSnapshotInput& input,
                                     const VdbSnapshotSettings& settings, bool sync = true);

}  // namespace voxspan
