// insitu/outputs/formats/vtk_files.h - ParaView-readable snapshots: the boundary particles as a
// .vtp (points with a "radius" array and the named attributes), the cell states as a .vti (cell
// data "state", the byte of voxspan/cell_states.h: 0 empty, 1 partial, 2 full, +4 inner), and a
// .pvd time series that lists them. Documents are made in memory (VTK's XML writers, inline
// binary, no appended section) and written atomically; the .pvd is rewritten whole, atomically,
// after each new entry, so ParaView never reads a half-updated series.
#pragma once

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// The particles' points are origin + (x, y, z), added in double: Float32 when `origin` is the
// world's (as the spheres are), else Float64, which holds a position 4.2e6 away (UTM-like
// coordinates) to 1e-9 where a float holds it to 0.5.
std::string vtp_document(std::span<const ParticleSphere> particles,
                         std::span<const AttributeSpan> attributes,
                         const std::array<double, 3>& origin = {0, 0, 0});
std::string vti_document(const CellStatesView& cells);

void write_vtp(const std::filesystem::path& path, std::span<const ParticleSphere> particles,
               std::span<const AttributeSpan> attributes, bool sync = true,
               const std::array<double, 3>& origin = {0, 0, 0});
void write_vti(const std::filesystem::path& path, const CellStatesView& cells, bool sync = true);

// The .pvtp of an MPI job's step: one dataset made of every rank's .vtp piece (`pieces`,
// relative to its folder), with the point arrays the pieces have (`radius` and `attributes`,
// whose values are not read: only names and components).
std::string pvtp_document(std::span<const std::string> pieces,
                          std::span<const AttributeSpan> attributes,
                          const std::array<double, 3>& origin = {0, 0, 0});

// A .pvd collection, one file a time step. add() appends (time, file) and rewrites the .pvd;
// file is relative to the .pvd's folder. If the rewrite fails (WriteError), the entry stays
// listed for the next one.
class PvdSeries {
 public:
  struct Entry {
    double time;
    std::string file;
  };
  explicit PvdSeries(std::filesystem::path path, bool sync = true)
      : path_(std::move(path)), sync_(sync) {}
  void add(double time, std::string file);
  const std::vector<Entry>& entries() const { return entries_; }
  const std::filesystem::path& path() const { return path_; }
  static std::string document(std::span<const Entry> entries);

 private:
  std::filesystem::path path_;
  bool sync_;
  std::vector<Entry> entries_;
};

}  // namespace voxspan
