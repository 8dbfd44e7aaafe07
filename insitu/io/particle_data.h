// insitu/io/particle_data.h - particles read from files, as the offline tools get them.
//
// Attributes are named float arrays with 1 (scalar) or 3 (vector) interleaved components,
// one tuple per particle, in the particles' order.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct ParticleData {
  std::vector<std::array<double, 3>> positions;
  std::vector<float> radii;  // empty when the file has no radius
  std::vector<Attribute> attributes;
  std::optional<double> time;        // simulated time, when the file says
  std::optional<std::int64_t> step;  // step/iteration, when the file (or its name) says
  std::optional<double> spacing;     // the rest spacing, when the file gives it (PySPH: m, rho)
  std::string chosen;                // what of the file was read, when it had a choice
  // The walls and obstacles (PySPH's arrays that are not the fluid: Adapter::set_scenery).
  std::vector<std::array<double, 3>> scenery;

  std::size_t size() const { return positions.size(); }
  const Attribute* attribute(std::string_view name) const;
  std::vector<AttributeSpan> attribute_views() const;
  // Packed spheres for the renderer; default_radius where the file has none.
  std::vector<ParticleSphere> spheres(float default_radius) const;
  // The step an offline run gives this file after one at `previous` (-1 before the first): the
  // file's own (PySPH's iteration count) when it says one past `previous`, else previous + 1,
  // so that steps rise as triggers and frame names need.
  std::int64_t step_after(std::int64_t previous) const {
    return step && *step > previous ? *step : previous + 1;
  }
};

struct ParticleReadOptions {
  // HDF5 files: PySPH's particle arrays to read (e.g. {"fluid"}), or a GADGET-format snapshot's
  // particle types (e.g. {"PartType4"}); {"all"}: every one; empty: the fluid's (PySPH:
  // kPickFluid in read_pysph_hdf5.cpp; GADGET: the gas, PartType0).
  std::vector<std::string> arrays;
  // PySPH: the arrays read as scenery (walls, obstacles); empty: every array not read as the
  // fluid (none when `arrays` is `all`); {"none"}: none.
  std::vector<std::string> scenery;
};

// By extension (any case): .vtp/.vtu (VTK XML), .vtk (legacy VTK), .csv (also .txt and .dat:
// numpy.savetxt's tables), .xyz, .hdf5/.h5 (PySPH's
// layout, or a GADGET-format snapshot: SWIFT, GIZMO...). Throws voxspan::Error naming the file
// and what is wrong with it; also where options.arrays names arrays (other than `all`) and the
// file is not HDF5: the other formats hold one unnamed set of particles.
ParticleData read_particles(const std::filesystem::path& path,
                            const ParticleReadOptions& options = {});
ParticleData read_vtk_particles(const std::filesystem::path& path);
ParticleData read_csv_particles(const std::filesystem::path& path);
ParticleData read_xyz_particles(const std::filesystem::path& path);
// HDF5: PySPH's layout (/particles) or the GADGET family's (/Header, /PartType<k>), as the file
// has it.
ParticleData read_hdf5_particles(const std::filesystem::path& path,
                                 const ParticleReadOptions& options = {});

// Throws voxspan::Error naming the file unless it is a file that exists. Every reader calls
// it first: HDF5 would call a missing file "not an HDF5 file", VTK "not readable".
void require_particle_file(const std::filesystem::path& path);

// The file's extension in lower case, with its dot: what picks its reader.
std::string extension_of(const std::filesystem::path& path);

// The number that ends a file's name before its extension, as a series' files carry their
// step ("PartFluid_0050.vtk": 50, "ParticleData_Fluid_10.vtk": 10); nullopt when none does.
// read_particles gives it as the step of a file whose format stores none.
std::optional<std::int64_t> step_in_name(const std::filesystem::path& path);

// Names the files use for radii (first match wins): radius, radii, r.
bool is_radius_name(std::string_view name);
// Moves a radius attribute (scalar, named as above) into data.radii. Called by every reader.
void adopt_radius_attribute(ParticleData& data);

}  // namespace voxspan
