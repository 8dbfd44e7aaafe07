// insitu/outputs/formats/mesh_files.h - the fluid's surface as a polygon mesh, for Blender,
// ParaView and anything else that opens PLY or OBJ (what splashsurf's users get).
//
// In: the boundary particles, their attributes and the cell states, as the OpenVDB snapshot
// takes them (vdb_snapshot.h). The surface is the zero level set of that snapshot's "fluid"
// grid, built the same way: the union of the particles' spheres closed by `closing`, the
// inner-full cells filled. Out: OpenVDB's volumeToMesh of it (dual contouring on the voxel
// grid: quads, and triangles only where `adaptivity` merges), a unit normal per vertex (the
// level set's gradient there, by central differences of its trilinear interpolation one voxel
// apart; the area-weighted normal of the faces around it where the gradient vanishes), and
// per vertex the attributes asked for, each from its nearest particle (of the closest
// particles of the eight voxels around the vertex, the one nearest to it: the particle whose
// value the snapshot's attribute grid holds there). Faces wind counter-clockwise seen from
// outside, so that their right-hand normals point out of the fluid as the vertex normals do.
//
// Files: PLY, binary in the machine's byte order (little endian on every platform we build
// for): vertex x y z nx ny nz, then one float property per attribute component
// (`density`; `velocity_x` `velocity_y` `velocity_z`), faces as `list uchar int vertex_indices`
// of 3 or 4 entries. OBJ: `v`, `vn` and `f a//a b//b c//c [d//d]` lines (attributes cannot go
// in it). Both written atomically (writer/atomic_file.h). The distance of the surface to the
// exact union of the spheres: docs/benchmarks.md, "Mesh output".
//
// Cost: the level set as the snapshot's (linear in the narrow band's voxels), then linear in
// the surface's voxels; everything OpenVDB stays inside mesh_files.cpp (and
// fluid_level_set.cpp, which builds the snapshot's level set for it).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "insitu/outputs/formats/vdb_snapshot.h"
#include "render/enum_names.h"
#include "render/frame_stats.h"
#include "voxspan/attribute.h"

namespace voxspan {

enum class MeshFormat { ply, obj };
inline constexpr EnumName<MeshFormat> kMeshFormatNames[] = {{"ply", MeshFormat::ply},
                                                            {"obj", MeshFormat::obj}};

// The level set's settings are the snapshot's; its band (half_width, not a key of outputs.mesh)
// needs no more than its default 3 voxels: the mesher and the gradient look one voxel about the
// surface.
struct FluidMeshSettings : FluidLevelSetSettings {
  double adaptivity = 0;  // volumeToMesh's: 0 every voxel's quad, up to 1 merged
  bool operator==(const FluidMeshSettings&) const = default;
};

// The input is the snapshot's: the boundary particles, the cell states, one attribute tuple per
// particle, the step and the time.
using FluidMeshInput = VdbSnapshotInput;

struct FluidMesh {
  // In the particles' frame (FluidMeshInput::origin), where floats hold them finely; the files
  // hold origin + point, in double where origin is not the world's.
  std::vector<std::array<float, 3>> points;
  std::array<double, 3> origin{0, 0, 0};
  std::vector<std::array<float, 3>> normals;  // unit, outward, one per point
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 4>> quads;
  std::vector<Attribute> attributes;  // one tuple per point, the input's names and components

  bool shifted() const { return origin != std::array<double, 3>{0, 0, 0}; }
  std::array<double, 3> world_point(std::size_t i) const {
    return {origin[0] + points[i][0], origin[1] + points[i][1], origin[2] + points[i][2]};
  }
};

struct FluidMeshReport : FluidLevelSetReport {
  // Points whose normal is the faces' for want of a gradient, and points no particle's voxel
  // reached (their attributes are 0); both are 0 on every scene we tested.
  std::size_t normals_from_faces = 0;
  std::size_t points_without_particle = 0;
  std::uint64_t bytes = 0;  // file size, when written
  // Wall time per stage: "mesh_rasterize", "mesh_fill", "mesh_close", "mesh_extract",
  // "mesh_normals", "mesh_attributes", "mesh_write".
  FrameStats timings;
};

// The surface of the fluid (see above). Throws voxspan::Error on bad input (attribute sizes,
// voxel size, adaptivity outside [0, 1]).
FluidMesh mesh_fluid(const FluidMeshInput& input, const FluidMeshSettings& settings,
                     FluidMeshReport* report = nullptr);

// The mesh as a PLY or OBJ file, written atomically (temp name, fsync when sync, rename);
// `comment` goes in the header (the creator, the step). Returns the bytes written. Throws
// WriteError on I/O failure.
std::uint64_t write_mesh_file(const std::filesystem::path& path, const FluidMesh& mesh,
                              MeshFormat format, std::string_view comment, bool sync = true);

// mesh_fluid, then write_mesh_file with the creator, step and time as the comment.
FluidMeshReport write_fluid_mesh(const std::filesystem::path& path, const FluidMeshInput& input,
                                 const FluidMeshSettings& settings, MeshFormat format,
                                 bool sync = true);

}  // namespace voxspan
