// Particles from PySPH's HDF5 output (pysph.solver.utils.dump with the .hdf5 extension):
//   /solver_data            attributes t (time), dt, count (iteration)
//   /particles/<array>/arrays/<property>   one dataset per property, N values (N * stride
//                           for strided properties); properties not stored are empty datasets
//                           (attribute stored = false); an array with no particles at the
//                           time (an inlet's fluid at first) has its stored ones empty
//   /particles/<array>/constants/...       (not read)
// Positions are x, y, z (z = 0 for 2D runs, stored or not); u, v, w become the vector attribute
// "velocity"; every other stored per-particle property is a scalar attribute. Several arrays
// (fluid, boundary...) are concatenated, keeping the attributes all of them have. With no arrays
// named the fluid's are read: the arrays named like a fluid ("fluid" in the name), else those whose
// particles move, else every one (a file written at rest with other names), and ParticleData
// says which and why. The spacing is the median of (m / rho)^(1 / dimensions) when the arrays
// store mass and density (2 dimensions when every z is the same).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>

#include "insitu/io/hdf5_file.h"
#include "insitu/io/particle_data.h"
#include "insitu/io/spacing_estimate.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

using hdf5::Handle;
using hdf5::joined;
using hdf5::member_names;

// Whether PySPH stored a property (its "stored" attribute). h5py writes numpy's bool as an
// enum over int8, which HDF5 converts to no integer type: its byte is read as it is.
bool stored_flag(hid_t set) {
  if (H5Aexists(set, "stored") <= 0) return false;
  Handle attr(H5Aopen(set, "stored", H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) return false;
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle native(H5Tget_native_type(type.get(), H5T_DIR_ASCEND), H5Tclose);
  unsigned char bytes[8] = {};
  if (!native.valid() || H5Tget_size(native.get()) > sizeof bytes ||
      H5Aread(attr.get(), native.get(), bytes) < 0)
    return false;
  return std::any_of(std::begin(bytes), std::end(bytes), [](unsigned char b) { return b != 0; });
}

// One particle array's stored properties, as doubles.
struct ArrayData {
  std::size_t count = 0;
  bool empty = false;  // no particles at this time (its stored properties empty)
  std::map<std::string, std::vector<double>> properties;  // 1 value per particle
};

ArrayData read_array(hid_t particles, const std::string& name, const std::string& file) {
  Handle arrays(H5Gopen2(particles, (name + "/arrays").c_str(), H5P_DEFAULT), H5Gclose);
  if (!arrays.valid())
    throw make_error(file, ": particle array \"", name, "\" has no \"arrays\" group");
  ArrayData out;
  bool counted = false;
  std::vector<std::string> stored_empty;
  for (const std::string& prop : member_names(arrays.get())) {
    Handle set(H5Dopen2(arrays.get(), prop.c_str(), H5P_DEFAULT), H5Dclose);
    if (!set.valid()) continue;
    Handle space(H5Dget_space(set.get()), H5Sclose);
    Handle type(H5Dget_type(set.get()), H5Tclose);
    H5T_class_t cls = H5Tget_class(type.get());
    if (cls != H5T_INTEGER && cls != H5T_FLOAT) continue;
    hssize_t n = H5Sget_simple_extent_npoints(space.get());
    if (n <= 0) {
      // Not stored, or stored with no particles: an array can be empty at times (PySPH's
      // inlet/outlet examples start with no fluid).
      if (stored_flag(set.get())) stored_empty.push_back(prop);
      continue;
    }
    const std::vector<double> stride = hdf5::numeric_attribute(set.get(), "stride");
    if (!stride.empty() && stride[0] != 1)
      continue;  // per-particle tensors and the like: not an attribute we draw
    std::vector<double> values(static_cast<std::size_t>(n));
    if (H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
      throw make_error(file, ": cannot read /particles/", name, "/arrays/", prop);
    if (!counted) out.count = values.size(), counted = true;
    if (values.size() != out.count) continue;  // not per particle
    out.properties.emplace(prop, std::move(values));
  }
  if (!counted && std::find(stored_empty.begin(), stored_empty.end(), "x") != stored_empty.end()) {
    for (const std::string& prop : stored_empty)
      out.properties.emplace(prop, std::vector<double>{});
    out.empty = true;
  }
  for (const char* axis : {"x", "y"})
    if (!out.properties.count(axis))
      throw make_error(file, ": particle array \"", name, "\" has no stored \"", axis,
                       "\" property");
  return out;
}

bool named_like_fluid(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return name.find("fluid") != std::string::npos;
}

bool moves(const ArrayData& a) {
  for (const char* v : {"u", "v", "w"}) {
    auto it = a.properties.find(v);
    if (it != a.properties.end() &&
        std::any_of(it->second.begin(), it->second.end(), [](double x) { return x != 0; }))
      return true;
  }
  return false;
}

// The arrays a file's fluid is when none are named (see the file's comment), and why.
std::vector<std::size_t> pick_fluid(const std::vector<std::string>& names,
                                    const std::vector<ArrayData>& arrays, std::string& why) {
  std::vector<std::size_t> named, moving, all;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (named_like_fluid(names[i])) named.push_back(i);
    if (moves(arrays[i])) moving.push_back(i);
    all.push_back(i);
  }
  if (!named.empty() && named.size() < names.size()) {
    why = "named like a fluid";
    return named;
  }
  if (!moving.empty() && moving.size() < names.size()) {
    why = "their particles move, the others' do not";
    return moving;
  }
  why = names.size() == 1              ? "the file's only array"
        : named.size() == names.size() ? "every array is named like a fluid"
                                       : "no array is named like a fluid or alone in moving";
  return all;
}

// The particles' volumes m / rho, where every array stores mass and density (none otherwise).
std::vector<double> volumes(const std::vector<const ArrayData*>& arrays) {
  std::vector<double> v;
  for (const ArrayData* a : arrays) {
    auto m = a->properties.find("m"), rho = a->properties.find("rho");
    if (m == a->properties.end() || rho == a->properties.end()) return {};
    for (std::size_t i = 0; i < a->count; ++i) v.push_back(m->second[i] / rho->second[i]);
  }
  return v;
}

// The arrays read as scenery (ParticleReadOptions::scenery): by default those not read as the
// fluid whose particles stand still (walls, obstacles; not an inlet's fluid); named ones must
// exist and must not be read as the fluid too.
template <class StandsStill>
std::vector<std::string> scenery_arrays(const ParticleReadOptions& options,
                                        const std::vector<std::string>& available,
                                        const std::vector<std::string>& fluid,
                                        const std::string& file, StandsStill stands_still) {
  const auto in = [](const std::vector<std::string>& list, const std::string& n) {
    return std::find(list.begin(), list.end(), n) != list.end();
  };
  if (options.scenery.size() == 1 && options.scenery[0] == "none") return {};
  if (options.scenery.empty()) {
    std::vector<std::string> rest;
    for (const std::string& n : available)
      if (!in(fluid, n) && stands_still(n)) rest.push_back(n);
    return rest;
  }
  for (const std::string& n : options.scenery) {
    if (!in(available, n))
      throw make_error(file, ": no particle array \"", n,
                       "\" for the scenery (the file has: ", joined(available), ")");
    if (in(fluid, n))
      throw make_error(file, ": particle array \"", n, "\" is read as the fluid and as scenery");
  }
  return options.scenery;
}

// An array's particles appended to the scenery.
void add_scenery(const ArrayData& a, ParticleData& data) {
  const auto& x = a.properties.at("x");
  const auto& y = a.properties.at("y");
  const auto z = a.properties.find("z");
  for (std::size_t i = 0; i < a.count; ++i)
    data.scenery.push_back({x[i], y[i], z == a.properties.end() ? 0.0 : z->second[i]});
}

}  // namespace

ParticleData hdf5::read_pysph_layout(hid_t h5, const std::string& file,
                                     const ParticleReadOptions& options) {
  Handle particles(H5Gopen2(h5, "particles", H5P_DEFAULT), H5Gclose);
  if (!particles.valid()) throw make_error(file, ": cannot open /particles");

  std::vector<std::string> available = member_names(particles.get());
  const bool everything = options.arrays.size() == 1 && options.arrays[0] == "all";
  std::vector<std::string> names =
      options.arrays.empty() || everything ? available : options.arrays;
  for (const std::string& n : names)
    if (std::find(available.begin(), available.end(), n) == available.end())
      throw make_error(file, ": no particle array \"", n, "\" (the file has: ", joined(available),
                       ")");
  if (names.empty()) throw make_error(file, ": no particle arrays under /particles");

  std::vector<ArrayData> read;
  for (const std::string& n : names) read.push_back(read_array(particles.get(), n, file));
  std::vector<std::size_t> picked(names.size());
  for (std::size_t i = 0; i < picked.size(); ++i) picked[i] = i;
  std::string why;
  if (options.arrays.empty()) picked = pick_fluid(names, read, why);
  std::vector<const ArrayData*> arrays;
  std::vector<std::string> chosen, others;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const bool in = std::find(picked.begin(), picked.end(), i) != picked.end();
    if (in) arrays.push_back(&read[i]), chosen.push_back(names[i]);
    else others.push_back(names[i]);
  }

  // An array with no particles now has no say in which attributes the others share.
  std::vector<const ArrayData*> filled;
  for (const ArrayData* a : arrays)
    if (!a->empty) filled.push_back(a);

  ParticleData data;
  // Properties every array has, except the positions and velocities handled below.
  std::vector<std::string> common;
  for (const auto& [prop, values] : (filled.empty() ? arrays : filled).front()->properties) {
    if (prop == "x" || prop == "y" || prop == "z" || prop == "u" || prop == "v" || prop == "w")
      continue;
    bool everywhere = std::all_of(filled.begin(), filled.end(),
                                  [&](const ArrayData* a) { return a->properties.count(prop); });
    if (everywhere) common.push_back(prop);
  }
  bool velocity = std::all_of(filled.begin(), filled.end(), [](const ArrayData* a) {
    return a->properties.count("u") && a->properties.count("v");
  });
  for (const std::string& prop : common) data.attributes.push_back({prop, 1, {}});
  if (velocity) data.attributes.push_back({"velocity", 3, {}});

  // PySPH's 2D runs store z too, all 0: a flat fluid is 2D, its mass an area's.
  bool three_d = false;
  std::optional<double> first_z;
  for (const ArrayData* array : filled) {
    const ArrayData& a = *array;
    if (auto zs = a.properties.find("z"); zs != a.properties.end() && !zs->second.empty()) {
      if (!first_z) first_z = zs->second.front();
      three_d = three_d || std::any_of(zs->second.begin(), zs->second.end(),
                                       [&](double v) { return v != *first_z; });
    }
    const auto& x = a.properties.at("x");
    const auto& y = a.properties.at("y");
    auto z = a.properties.find("z");
    for (std::size_t i = 0; i < a.count; ++i)
      data.positions.push_back({x[i], y[i], z == a.properties.end() ? 0.0 : z->second[i]});
    for (std::size_t c = 0; c < common.size(); ++c)
      for (double v : a.properties.at(common[c])) data.attributes[c].values.push_back(float(v));
    if (velocity) {
      auto& vel = data.attributes.back().values;
      auto w = a.properties.find("w");
      for (std::size_t i = 0; i < a.count; ++i) {
        vel.push_back(float(a.properties.at("u")[i]));
        vel.push_back(float(a.properties.at("v")[i]));
        vel.push_back(w == a.properties.end() ? 0.f : float(w->second[i]));
      }
    }
  }

  Handle solver(H5Gopen2(h5, "solver_data", H5P_DEFAULT), H5Gclose);
  if (solver.valid()) {
    if (auto t = hdf5::numeric_attribute(solver.get(), "t"); !t.empty()) data.time = t[0];
    if (auto count = hdf5::numeric_attribute(solver.get(), "count"); !count.empty())
      data.step = std::int64_t(count[0]);
  }
  data.spacing = spacing_from_volumes(volumes(filled), three_d ? 3 : 2);
  std::map<std::string, ArrayData> more;  // arrays read for the scenery alone
  const auto array = [&](const std::string& n) -> const ArrayData& {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return read[i];
    auto [it, fresh] = more.try_emplace(n);
    if (fresh) it->second = read_array(particles.get(), n, file);
    return it->second;
  };
  const std::vector<std::string> scenery = scenery_arrays(
      options, available, chosen, file, [&](const std::string& n) { return !moves(array(n)); });
  for (const std::string& n : scenery) add_scenery(array(n), data);
  std::vector<std::string> unused;
  for (const std::string& n : others)
    if (std::find(scenery.begin(), scenery.end(), n) == scenery.end()) unused.push_back(n);
  if (options.arrays.empty())
    data.chosen = "PySPH arrays " + joined(chosen) + " (" + why + ")" +
                  (scenery.empty() ? "" : "; scenery: " + joined(scenery) + " (--scenery picks)") +
                  (unused.empty() ? "" : "; left out: " + joined(unused) + " (--arrays picks)");
  // A 2D run may store no z at all (output arrays without it): said, as it sets the spacing's
  // dimensions and the picture's axis.
  const bool no_z = std::any_of(filled.begin(), filled.end(),
                                [](const ArrayData* a) { return !a->properties.count("z"); });
  if (no_z)
    data.chosen += std::string(data.chosen.empty() ? "" : "; ") +
                   "no z stored: read as a 2D run in the x-y plane (z = 0)";
  adopt_radius_attribute(data);
  return data;
}

}  // namespace voxspan
