// insitu/particle_data.h - particles and cell states as owned data: what a writer job keeps
// after the solver's step has moved on, and what the particle-file readers return.
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

#include "voxspan/cell_states.h"

namespace voxspan {

// A float attribute as the file writers take it (named so as not to clash with the solver-side
// voxspan::AttributeView of voxspan/particles.h, a strided view of the solver's own arrays).
struct AttributeSpan {
  std::string_view name;
  int components = 1;  // 1 or 3
  std::span<const float> values;
  std::size_t count() const { return components > 0 ? values.size() / components : 0; }
};

struct NamedAttribute {
  std::string name;
  int components = 1;
  std::vector<float> values;
  AttributeSpan view() const { return {name, components, values}; }
};

// Throws voxspan::Error naming the attribute unless every attribute has 1 or 3 components and
// exactly `count` tuples.
void check_attributes(std::span<const AttributeSpan> attributes, std::size_t count);

struct CellStatesData {
  std::array<double, 3> origin{0, 0, 0};
  double cell_size = 0;
  std::array<int, 3> dims{0, 0, 0};
  std::vector<std::uint8_t> states;

  static CellStatesData copy_of(const CellStatesView& view);
  CellStatesView view() const { return {origin, cell_size, dims, states.data()}; }
};

struct ParticleData {
  std::vector<std::array<double, 3>> positions;
  std::vector<float> radii;  // empty when the file has no radius
  std::vector<NamedAttribute> attributes;
  std::optional<double> time;         // simulated time, when the file says
  std::optional<std::int64_t> step;   // step/iteration, when the file says

  std::size_t size() const { return positions.size(); }
  const NamedAttribute* attribute(std::string_view name) const;
  std::vector<AttributeSpan> attribute_views() const;
  // Packed spheres for the renderer; default_radius where the file has none.
  std::vector<ParticleSphere> spheres(float default_radius) const;
};

struct ParticleReadOptions {
  // PySPH: the particle arrays to read (e.g. {"fluid"}); empty = every array in the file.
  std::vector<std::string> arrays;
};

// By extension: .vtp/.vtu (VTK XML), .csv, .xyz, .hdf5/.h5 (PySPH). Throws voxspan::Error
// naming the file and what is wrong with it.
ParticleData read_particles(const std::filesystem::path& path,
                            const ParticleReadOptions& options = {});
ParticleData read_vtk_particles(const std::filesystem::path& path);
ParticleData read_csv_particles(const std::filesystem::path& path);
ParticleData read_xyz_particles(const std::filesystem::path& path);
ParticleData read_pysph_hdf5(const std::filesystem::path& path,
                             const ParticleReadOptions& options = {});

// Names the files use for radii (first match wins): radius, radii, r.
bool is_radius_name(std::string_view name);
// Moves a radius attribute (scalar, named as above) into data.radii. Called by every reader.
void adopt_radius_attribute(ParticleData& data);

}  // namespace voxspan
