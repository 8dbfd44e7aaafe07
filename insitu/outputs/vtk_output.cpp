// outputs.vtk: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread; <folder>/particles_<step>.vtp and cells_<step>.vti written on the
// writer's, each then listed in its .pvd series (particles.pvd, cells.pvd).
#include "insitu/outputs/vtk_output.h"

#include <memory>

#include "insitu/outputs/output.h"
#include "insitu/outputs/pooled_jobs.h"
#include "insitu/outputs/snapshot_copy.h"
#include "insitu/outputs/vtk_files.h"

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
      output_keys<V>({schema::flag("particles", &V::particles, ".vtp of the boundary particles"),
                      schema::flag("cells", &V::cells, ".vti of the cell states"),
                      schema::names("attributes", &V::attributes,
                                    "particle attributes written as point data")}),
      check_vtk};
  return s;
}

class VtkOutput final : public Output {
 public:
  VtkOutput(const VtkSettings& s, const OutputContext& c)
      : settings_(s),
        folder_(c.folder),
        fsync_(c.fsync),
        jobs_(c.writer, c.slots, [this](SnapshotCopy& copy) { write_files(copy); }) {
    if (s.particles) particles_ = std::make_unique<PvdSeries>(folder_ / "particles.pvd", fsync_);
    if (s.cells) cells_ = std::make_unique<PvdSeries>(folder_ / "cells.pvd", fsync_);
  }

  void write(const OutputStep& step) override {
    jobs_.submit("VTK files",
                 [&](SnapshotCopy& copy) { copy.fill(step.data, settings_.attributes); });
  }

  OutputTally tally() const override { return jobs_.tally(); }

 private:
  void write_files(const SnapshotCopy& s) {
    if (particles_) {
      const std::string name = step_file_name("particles", s.step, "vtp");
      const std::vector<AttributeSpan> attributes = s.attribute_spans();
      write_vtp(folder_ / name, s.spheres, attributes, fsync_);
      particles_->add(s.time, name);
    }
    if (cells_ && !s.cells.states.empty()) {
      const std::string name = step_file_name("cells", s.step, "vti");
      write_vti(folder_ / name, s.cells.view(), fsync_);
      cells_->add(s.time, name);
    }
  }

  const VtkSettings settings_;
  const std::filesystem::path folder_;
  const bool fsync_;
  std::unique_ptr<PvdSeries> particles_, cells_;
  PooledJobs<SnapshotCopy> jobs_;
};

}  // namespace

OutputKind vtk_output_kind() {
  return output_kind<VtkSettings, VtkOutput>("vtk", "VTK sets", vtk_section());
}

}  // namespace voxspan
