// Particles from the HDF5 snapshots of the GADGET family (GADGET-2 to 4, SWIFT, GIZMO, AREPO):
//   /Header        attributes NumPart_ThisFile[6], MassTable[6], Time, NumFilesPerSnapshot
//                  (SWIFT stores each scalar as an array of one)
//   /PartType<k>/  one dataset per field, a row per particle: Coordinates (N x 3),
//                  Velocities, Masses, Density (SWIFT: Densities), SmoothingLength(s),
//                  InternalEnergy, ...
// PartType0, the gas, is what SPH evolves: read by default; ParticleReadOptions::arrays names
// the types to read instead (PartType4, or `all`), concatenated with the fields all of them
// have. Every numeric field of one or three values per particle is an attribute, under its own
// name; where a type has no Masses its MassTable entry gives them. The spacing is the median of
// (mass / density)^(1 / dimensions) where the types have both (2 dimensions when every z is the
// same). A snapshot split over several files is read one file at a time; `chosen` says which.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "insitu/io/hdf5_file.h"
#include "insitu/io/particle_data.h"
#include "insitu/io/spacing_estimate.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

using hdf5::Handle;
using hdf5::joined;

constexpr int kTypes = 6;  // PartType0 .. PartType5

std::string type_name(int k) { return "PartType" + std::to_string(k); }

// One particle type's fields, as doubles, `components` values per particle.
struct Field {
  int components = 1;
  std::vector<double> values;
};
struct TypeData {
  std::size_t count = 0;
  std::map<std::string, Field> fields;
};

// The fields of /PartType<k> with one row per particle (the rows of Coordinates).
TypeData read_type(hid_t file, const std::string& name, const std::string& path) {
  Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.valid()) throw make_error(path, ": cannot open /", name);
  std::map<std::string, Field> read;
  for (const std::string& field : hdf5::member_names(group.get())) {
    Handle set(H5Dopen2(group.get(), field.c_str(), H5P_DEFAULT), H5Dclose);
    if (!set.valid()) continue;  // a subgroup
    Handle type(H5Dget_type(set.get()), H5Tclose);
    const H5T_class_t cls = H5Tget_class(type.get());
    if (cls != H5T_INTEGER && cls != H5T_FLOAT) continue;
    Handle space(H5Dget_space(set.get()), H5Sclose);
    hsize_t dims[2] = {0, 1};
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 1 || rank > 2) continue;
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    if (dims[1] != 1 && dims[1] != 3) continue;  // per-particle tensors and the like
    Field f{int(dims[1]), std::vector<double>(std::size_t(dims[0] * dims[1]))};
    if (!f.values.empty() &&
        H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, f.values.data()) < 0)
      throw make_error(path, ": cannot read /", name, "/", field);
    read.emplace(field, std::move(f));
  }
  const auto xyz = read.find("Coordinates");
  if (xyz == read.end() || xyz->second.components != 3)
    throw make_error(path, ": /", name, " has no Coordinates of three values per particle");
  TypeData out;
  out.count = xyz->second.values.size() / 3;
  for (auto& [field, f] : read)  // a field of another length is not per particle
    if (f.values.size() == out.count * std::size_t(f.components))
      out.fields.emplace(field, std::move(f));
  return out;
}

// The types to read: those `options` names (`all`: every one the file has), else the gas.
std::vector<std::string> types_to_read(const ParticleReadOptions& options,
                                       const std::vector<std::string>& available,
                                       const std::string& path) {
  if (options.arrays.size() == 1 && options.arrays[0] == "all") {
    if (available.empty())
      throw make_error(path, ": no particle types (no /PartType0 to /PartType5 group)");
    return available;
  }
  if (options.arrays.empty()) {
    if (std::find(available.begin(), available.end(), type_name(0)) == available.end())
      throw make_error(path, ": no gas particles (PartType0), the SPH particles; the file has ",
                       available.empty() ? std::string("none") : joined(available),
                       " (--arrays picks)");
    return {type_name(0)};
  }
  for (const std::string& n : options.arrays)
    if (std::find(available.begin(), available.end(), n) == available.end())
      throw make_error(path, ": no particle type \"", n, "\" (the file has: ", joined(available),
                       ")");
  return options.arrays;
}

// The particles' volumes mass / density, where every type has both (none otherwise).
std::vector<double> volumes(const std::vector<const TypeData*>& types) {
  std::vector<double> v;
  for (const TypeData* t : types) {
    auto m = t->fields.find("Masses");
    auto rho = t->fields.find("Density");
    if (rho == t->fields.end()) rho = t->fields.find("Densities");
    if (m == t->fields.end() || rho == t->fields.end()) return {};
    for (std::size_t i = 0; i < t->count; ++i)
      v.push_back(m->second.values[i] / rho->second.values[i]);
  }
  return v;
}

}  // namespace

ParticleData hdf5::read_gadget_layout(hid_t h5, const std::string& file,
                                      const ParticleReadOptions& options) {
  Handle header(H5Gopen2(h5, "Header", H5P_DEFAULT), H5Gclose);
  if (!header.valid()) throw make_error(file, ": cannot open /Header");
  if (!options.scenery.empty() && !(options.scenery.size() == 1 && options.scenery[0] == "none"))
    throw make_error(file, ": scenery arrays were named, but a GADGET-format snapshot has none");

  std::vector<std::string> available;
  for (int k = 0; k < kTypes; ++k)
    if (hdf5::has_member(h5, type_name(k).c_str())) available.push_back(type_name(k));
  const std::vector<std::string> names = types_to_read(options, available, file);
  std::vector<TypeData> types;
  for (const std::string& n : names) types.push_back(read_type(h5, n, file));

  // Masses from the mass table where a type stores none (all its particles weigh the same).
  const std::vector<double> mass_table = hdf5::numeric_attribute(header.get(), "MassTable");
  for (std::size_t t = 0; t < types.size(); ++t) {
    const std::size_t k = std::size_t(names[t].back() - '0');
    if (types[t].fields.count("Masses") == 0 && k < mass_table.size() && mass_table[k] > 0)
      types[t].fields.emplace("Masses",
                              Field{1, std::vector<double>(types[t].count, mass_table[k])});
  }

  ParticleData data;
  std::vector<const TypeData*> filled;
  for (const TypeData& t : types)
    if (t.count > 0) filled.push_back(&t);
  if (!filled.empty())
    for (const auto& [name, f] : filled.front()->fields) {
      if (name == "Coordinates") continue;
      const bool everywhere = std::all_of(filled.begin(), filled.end(), [&](const TypeData* t) {
        auto it = t->fields.find(name);
        return it != t->fields.end() && it->second.components == f.components;
      });
      if (everywhere) data.attributes.push_back({name, f.components, {}});
    }
  bool flat = true;
  for (const TypeData* t : filled) {
    const std::vector<double>& xyz = t->fields.at("Coordinates").values;
    for (std::size_t i = 0; i < t->count; ++i) {
      data.positions.push_back({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
      flat = flat && xyz[3 * i + 2] == data.positions.front()[2];
    }
    for (Attribute& a : data.attributes)
      for (double v : t->fields.at(a.name).values) a.values.push_back(float(v));
  }

  if (const std::vector<double> time = hdf5::numeric_attribute(header.get(), "Time"); !time.empty())
    data.time = time[0];
  data.spacing = spacing_from_volumes(volumes(filled), flat ? 2 : 3);
  std::string chosen = "GADGET-format " + names.front();
  for (std::size_t t = 1; t < names.size(); ++t) chosen += ", " + names[t];
  if (options.arrays.empty() && available.size() > 1) chosen += " (the gas; --arrays picks)";
  const std::vector<double> files = hdf5::numeric_attribute(header.get(), "NumFilesPerSnapshot");
  if (!files.empty() && files[0] > 1)
    chosen += "; this file is one of the snapshot's " + std::to_string(std::int64_t(files[0]));
  data.chosen = chosen;
  adopt_radius_attribute(data);
  return data;
}

}  // namespace voxspan
