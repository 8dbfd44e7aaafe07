#include "insitu/io/particle_data.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include "insitu/io/hdf5_file.h"
#include "voxspan/error.h"

namespace voxspan {

const Attribute* ParticleData::attribute(std::string_view name) const {
  for (const Attribute& a : attributes)
    if (a.name == name) return &a;
  return nullptr;
}

std::vector<AttributeSpan> ParticleData::attribute_views() const {
  std::vector<AttributeSpan> views;
  views.reserve(attributes.size());
  for (const Attribute& a : attributes) views.push_back(a.view());
  return views;
}

std::vector<ParticleSphere> ParticleData::spheres(float default_radius) const {
  std::vector<ParticleSphere> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    out[i] = {float(positions[i][0]), float(positions[i][1]), float(positions[i][2]),
              radii.empty() ? default_radius : radii[i]};
  return out;
}

bool is_radius_name(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return lower == "radius" || lower == "radii" || lower == "r";
}

void require_particle_file(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::status(path, ec);
  if (s.type() == std::filesystem::file_type::not_found)
    throw make_error("cannot read particles from ", path.string(), ": no such file");
  if (ec) throw make_error("cannot read particles from ", path.string(), ": ", ec.message());
  if (s.type() == std::filesystem::file_type::directory)
    throw make_error("cannot read particles from ", path.string(), ": a directory, not a file");
}

void adopt_radius_attribute(ParticleData& data) {
  auto it = std::find_if(data.attributes.begin(), data.attributes.end(),
                         [](const auto& a) { return a.components == 1 && is_radius_name(a.name); });
  if (it == data.attributes.end()) return;
  data.radii = std::move(it->values);
  data.attributes.erase(it);
}

std::optional<std::int64_t> step_in_name(const std::filesystem::path& path) {
  const std::string stem = path.stem().string();
  std::size_t begin = stem.size();
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  // 18 digits at most: an int64 holds them all.
  if (begin == stem.size() || stem.size() - begin > 18) return std::nullopt;
  return std::stoll(stem.substr(begin));
}

std::string extension_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

ParticleData read_hdf5_particles(const std::filesystem::path& path,
                                 const ParticleReadOptions& options) {
  const hdf5::Quiet quiet;
  const hdf5::Handle h5 = hdf5::open_particle_file(path);
  if (hdf5::has_member(h5.get(), "particles"))
    return hdf5::read_pysph_layout(h5.get(), path.string(), options);
  if (!hdf5::has_member(h5.get(), "Header")) {
    std::string members;
    for (const std::string& n : hdf5::member_names(h5.get()))
      members += (members.empty() ? "/" : ", /") + n;
    throw make_error("cannot read particles from ", path.string(),
                     ": neither PySPH's layout (/particles) nor a GADGET-format snapshot "
                     "(/Header, /PartType0...); the file has ",
                     members.empty() ? std::string("nothing") : members);
  }
  return hdf5::read_gadget_layout(h5.get(), path.string(), options);
}

namespace {

ParticleData read_particles_of_format(const std::filesystem::path& path,
                                      const ParticleReadOptions& options) {
  const std::string ext = extension_of(path);
  if (ext == ".hdf5" || ext == ".h5") return read_hdf5_particles(path, options);
  const bool vtk = ext == ".vtp" || ext == ".vtu" || ext == ".vtk";
  // numpy.savetxt's and many codes' plain tables: read as CSV (any separator, header or none).
  const bool table = ext == ".csv" || ext == ".txt" || ext == ".dat";
  if (!vtk && !table && ext != ".xyz")
    throw make_error("cannot read particles from ", path.string(), ": unknown extension \"", ext,
                     "\" (known: .vtp .vtu .vtk .csv .txt .dat .xyz .hdf5 .h5)");
  // Named arrays would otherwise read as the whole file, silently; `all` is what it holds.
  const auto refuse_names = [&](const char* what, const std::vector<std::string>& list) {
    std::string names;
    for (const std::string& n : list) names += (names.empty() ? "" : ", ") + n;
    throw make_error("cannot read particles from ", path.string(), ": ", what, " were named (",
                     names,
                     "), but only HDF5 files (.hdf5 .h5: PySPH's arrays, GADGET's particle "
                     "types) have named arrays; a ",
                     ext, " file is one set of particles");
  };
  const auto only = [](const std::vector<std::string>& list, const char* word) {
    return list.size() == 1 && list[0] == word;
  };
  if (!options.arrays.empty() && !only(options.arrays, "all"))
    refuse_names("particle arrays", options.arrays);
  if (!options.scenery.empty() && !only(options.scenery, "none"))
    refuse_names("scenery arrays", options.scenery);
  if (vtk) return read_vtk_particles(path);
  return table ? read_csv_particles(path) : read_xyz_particles(path);
}

}  // namespace

ParticleData read_particles(const std::filesystem::path& path, const ParticleReadOptions& options) {
  ParticleData data = read_particles_of_format(path, options);
  if (!data.step) data.step = step_in_name(path);
  return data;
}

}  // namespace voxspan
