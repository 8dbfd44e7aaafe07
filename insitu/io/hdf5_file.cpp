#include "insitu/io/hdf5_file.h"

#include "insitu/io/particle_data.h"
#include "voxspan/error.h"

namespace voxspan::hdf5 {
namespace {

// The message of the innermost HDF5 error on this thread's stack: what went wrong, not the
// calls that passed it up ("truncated file: eof = 1024, ... stored_eof = 6144").
std::string innermost_error() {
  std::string message = "HDF5 gives no reason";
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc && *e->desc) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &message);
  return message;
}

}  // namespace

Quiet::Quiet() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}
Quiet::~Quiet() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

Handle open_particle_file(const std::filesystem::path& path) {
  require_particle_file(path);
  const std::string file = path.string();
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw make_error("cannot read particles from ", file, ": not an HDF5 file");
  Handle h5(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  // The signature is there but HDF5 cannot open the file: most often a dump cut short (the
  // solver killed while writing, a copy not finished), which HDF5 calls a "truncated file".
  if (!h5.valid())
    throw make_error("cannot read particles from ", file,
                     ": the HDF5 file is truncated or corrupt (", innermost_error(), ")");
  return h5;
}

std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info{};
  std::vector<std::string> names;
  if (H5Gget_info(group, &info) < 0) return names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t size =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size < 0) continue;
    std::string name(static_cast<std::size_t>(size) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(size));
    names.push_back(name);
  }
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

bool has_member(hid_t group, const char* name) { return H5Lexists(group, name, H5P_DEFAULT) > 0; }

std::vector<double> numeric_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return {};
  Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) return {};
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) return {};
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n <= 0) return {};
  std::vector<double> values(static_cast<std::size_t>(n));
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()) < 0) return {};
  return values;
}

}  // namespace voxspan::hdf5
