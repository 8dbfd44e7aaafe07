// insitu/io/hdf5_file.h - the HDF5 particle readers (read_hdf5_particles, particle_data.cpp,
// opens the file and tells the layouts apart) and what they share: owned identifiers, HDF5's
// own error printing held off, a file opened with the reason it cannot be, a group's members,
// and numeric attributes (scalars, or the first value of an array: SWIFT stores its header's
// scalars as arrays of one).
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "insitu/io/particle_data.h"

namespace voxspan::hdf5 {

// Owns one HDF5 identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

// HDF5 prints its error stack to stderr by default; our errors name the problem instead.
class Quiet {
 public:
  Quiet();
  ~Quiet();
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// The particle file at `path` opened for reading (call with a Quiet in scope). Throws
// voxspan::Error naming it where it is missing, not HDF5, or truncated or corrupt.
Handle open_particle_file(const std::filesystem::path& path);

// The names of a group's members, in name order.
std::vector<std::string> member_names(hid_t group);

// Names as a message lists them: "fluid, wall".
std::string joined(const std::vector<std::string>& names);

// Whether `name` is a member of `group` (no error when it is not).
bool has_member(hid_t group, const char* name);

// A numeric attribute of an object as doubles, all its values; empty where it is absent or not
// numeric.
std::vector<double> numeric_attribute(hid_t object, const char* name);

// The particles of an open file (`path` for messages) in PySPH's layout (/particles,
// read_pysph_hdf5.cpp) and in the GADGET family's (/Header, /PartType<k>, read_gadget_hdf5.cpp).
ParticleData read_pysph_layout(hid_t file, const std::string& path,
                               const ParticleReadOptions& options);
ParticleData read_gadget_layout(hid_t file, const std::string& path,
                                const ParticleReadOptions& options);

}  // namespace voxspan::hdf5
