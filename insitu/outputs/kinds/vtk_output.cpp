// outputs.vtk: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread; <folder>/particles_<step>.vtp and cells_<step>.vti written on the
// writer's, each then listed in its .pvd series (particles.pvd, cells.pvd).
#include "insitu/outputs/kinds/vtk_output.h"

#include <cstdio>
#include <cstring>
#include <memory>

#include "insitu/outputs/formats/vtk_files.h"
#include "insitu/outputs/kinds/snapshot_copy.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {
namespace {

void check_vtk(yaml::MapReader& r, VtkSettings& v) {
  if (v.enabled && !v.particles && !v.cells)
    r.checker().error(r.node(), r.path(),
                      "enabled but writes nothing: set particles or cells to true");
}

const schema::Section<VtkSettings>& vtk_section() {
  using V = VtkSettings;
  static const schema::Section<V> s{
      "outputs.vtk",
      output_keys<V>(
          {schema::flag("particles", &V::particles, ".vtp of the surface-shell particles"),
           schema::flag("cells", &V::cells, ".vti of the cell states"),
           schema::names("attributes", &V::attributes,
                         "particle attributes written as point data")}),
      check_vtk};
  return s;
}

// In an MPI job every rank writes its particles' piece (particles_<step>_<rank>.vtp) and the
// root writes particles_<step>.pvtp over the pieces, so ParaView opens each step as one dataset.
// The cell states go to the root, every rank's in one grid, as in the VDB snapshot: each rank's
// grid may span the whole domain, and pieces that overlap would disagree where a rank holds no
// particles.
class VtkOutput final : public Output {
 public:
  VtkOutput(const VtkSettings& s, const OutputContext& c)
      : settings_(s),
        attributes_(attribute_names(s, "vtk")),
        folder_(c.folder),
        fsync_(c.fsync),
        comm_(c.comm),
        rank_(c.comm != nullptr ? c.comm->rank() : 0),
        ranks_(c.comm != nullptr ? c.comm->size() : 1),
        jobs_(c.writer, c.slots, [this](SnapshotCopy& copy) { write_files(copy); }) {
    if (rank_ != 0) return;
    if (s.particles) particles_ = std::make_unique<PvdSeries>(folder_ / "particles.pvd", fsync_);
    if (s.cells) cells_ = std::make_unique<PvdSeries>(folder_ / "cells.pvd", fsync_);
  }

  void write(const OutputStep& step) override {
    // Collective, so before a slot is taken: a rank without a free one still takes part.
    const bool gather = settings_.cells && ranks_ > 1;
    if (gather) merged_cells_ = gather_cells(*comm_, step.data.cells);
    jobs_.submit("VTK files", [&](SnapshotCopy& copy) {
      copy.fill(step.data, attributes_);
      if (gather) std::swap(copy.cells, merged_cells_);  // the job's on the root, none elsewhere
    });
  }

  OutputTally tally() const override { return jobs_.tally(); }

 private:
  void write_files(const SnapshotCopy& s) {
    const std::vector<AttributeSpan> attributes = s.attribute_spans();
    if (settings_.particles) {
      write_vtp(folder_ / piece(s.step, rank_, "particles", "vtp"), s.spheres, attributes, fsync_,
                s.origin);
      if (particles_) particles_->add(s.time, particle_dataset(s.step, attributes, s.origin));
    }
    if (settings_.cells && !s.cells.states.empty()) {
      const std::string name = step_file_name("cells", s.step, "vti");
      write_vti(folder_ / name, s.cells.view(), fsync_);
      if (cells_) cells_->add(s.time, name);
    }
  }

  // "<prefix>_<step>.<ext>" alone, "<prefix>_<step>_<rank>.<ext>" for a rank's piece.
  std::string piece(std::int64_t step, int rank, const char* prefix, const char* ext) const {
    if (ranks_ == 1) return step_file_name(prefix, step, ext);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%04d", rank);
    std::string name = step_file_name(prefix, step, ext);
    return name.insert(name.size() - std::strlen(ext) - 1, suffix);
  }

  // The file the particles' series lists for a step: the root's piece alone, else a .pvtp.
  std::string particle_dataset(std::int64_t step, std::span<const AttributeSpan> attributes,
                               const std::array<double, 3>& origin) {
    if (ranks_ == 1) return piece(step, 0, "particles", "vtp");
    std::vector<std::string> pieces;
    for (int r = 0; r < ranks_; ++r) pieces.push_back(piece(step, r, "particles", "vtp"));
    const std::string name = step_file_name("particles", step, "pvtp");
    write_file_atomically(folder_ / name, pvtp_document(pieces, attributes, origin), fsync_);
    return name;
  }

  const VtkSettings settings_;
  const AttributeNames attributes_;
  const std::filesystem::path folder_;
  const bool fsync_;
  Communicator* const comm_;
  const int rank_, ranks_;
  CellStates merged_cells_;                       // with ranks: the step's, on the root
  std::unique_ptr<PvdSeries> particles_, cells_;  // the root's
  PooledJobs<SnapshotCopy> jobs_;
};

}  // namespace

OutputKind vtk_output_kind() {
  return output_kind<VtkSettings, VtkOutput>("vtk", "VTK sets", vtk_section());
}

}  // namespace voxspan
