// outputs.vdb: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread; the grids built and written on the writer's (insitu/outputs/
// vdb_snapshot.h).
#include "insitu/outputs/kinds/vdb_output.h"

#include "insitu/outputs/kinds/snapshot_copy.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {
namespace {

const schema::Section<VdbSettings>& vdb_section() {
  using V = VdbSettings;
  using S = VdbSnapshotSettings;
  static const schema::Section<V> s{
      "outputs.vdb",
      output_keys<V>(
          {schema::number_or_auto(
               "radius", &V::radius, schema::above(0),
               "sphere radius of every particle in the level set; `auto` = half the "
               "particle spacing, so that the level set holds the particles' own "
               "volume (the render radius when the spacing is unknown)"),
           schema::lifted(&V::snapshot,
                          schema::number_or_auto("voxel_size", &S::voxel_size, schema::above(0),
                                                 "world units; `auto` = the radius")),
           schema::lifted(&V::snapshot,
                          schema::integer("half_width", &S::half_width, 1, 64,
                                          "narrow band, voxels on each side of the surface")),
           schema::lifted(&V::snapshot,
                          schema::number_or_auto(
                              "closing", &S::closing, schema::at_least(0),
                              "gap closing distance (dilate, then erode by it); `auto` = the "
                              "radius; 0: none")),
           schema::lifted(&V::snapshot,
                          schema::flag("fill_inner", &S::fill_inner,
                                       "inner-full cells filled: the file holds the whole fluid")),
           schema::lifted(&V::snapshot,
                          schema::flag("cell_states", &S::cell_states, "the cell-state grid")),
           schema::names("attributes", &V::attributes,
                         "particle attributes written as float or vec3 grids")})};
  return s;
}

class VdbOutput final : public Output {
 public:
  VdbOutput(const VdbSettings& s, const OutputContext& c)
      : settings_(s),
        folder_(c.folder),
        fsync_(c.fsync),
        radius_(s.radius.value_or(c.particle_spacing > 0 ? 0.5 * c.particle_spacing : 0.0)),
        comm_(c.comm),
        jobs_(c.writer, c.slots, [this](SnapshotCopy& copy) { write_snapshot(copy); }) {}

  void write(const OutputStep& step) override {
    if (comm_ == nullptr || comm_->size() == 1) {
      jobs_.submit("VDB snapshot", [&](SnapshotCopy& copy) {
        copy.fill(step.data, settings_.attributes, radius_);
      });
      return;
    }
    // Every rank's part, gathered on the root before any slot is taken: a rank without a free
    // slot still takes part. One file per snapshot, the whole fluid, where Houdini opens it.
    gathered_.fill(step.data, settings_.attributes, radius_);
    if (!gathered_.gather(*comm_)) return;
    jobs_.submit("VDB snapshot", [&](SnapshotCopy& copy) { std::swap(copy, gathered_); });
  }

  OutputTally tally() const override { return jobs_.tally(); }

 private:
  void write_snapshot(const SnapshotCopy& s) const {
    const std::vector<AttributeSpan> attributes = s.attribute_spans();
    write_vdb_snapshot(folder_ / step_file_name("fluid", s.step, "vdb"),
                       {s.spheres, s.cells.view(), attributes, s.step, s.time}, settings_.snapshot,
                       fsync_);
  }

  const VdbSettings settings_;
  const std::filesystem::path folder_;
  const bool fsync_;
  const double radius_;  // 0: the spheres' own radii
  Communicator* const comm_;
  SnapshotCopy gathered_;  // with ranks: the job's whole snapshot, on the root
  PooledJobs<SnapshotCopy> jobs_;
};

}  // namespace

OutputKind vdb_output_kind() {
  return output_kind<VdbSettings, VdbOutput>("vdb", "VDB", vdb_section());
}

}  // namespace voxspan
