// outputs.mesh: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread, as the VDB snapshot's; the surface meshed and written on the writer's
// (insitu/outputs/formats/mesh_files.h).
#include "insitu/outputs/kinds/mesh_output.h"

#include "insitu/outputs/kinds/snapshot_copy.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {
namespace {

// Said at start-up rather than found by the writer: OBJ has no place for per-vertex values,
// and a PLY property is one word that must not be one of the vertex's own.
void check_mesh(yaml::MapReader& r, MeshSettings& m) {
  if (m.attributes.empty()) return;
  const YAML::Node at = r.has("attributes") ? r.find("attributes") : r.node();
  if (m.format == MeshFormat::obj)
    r.checker().error(at, r.path("attributes"),
                      "OBJ files hold no per-vertex attributes: set format: ply, or leave "
                      "attributes out");
  for (const std::string& name : m.attributes) {
    const bool reserved = name == "x" || name == "y" || name == "z" || name == "nx" ||
                          name == "ny" || name == "nz" || name == "vertex_indices";
    if (reserved || name.find_first_of(" \t\r\n") != std::string::npos)
      r.checker().error(at, r.path("attributes"),
                        "\"" + name + "\" cannot name a PLY vertex property (" +
                            (reserved ? "the vertex's own" : "not one word") + ")");
  }
}

const schema::Section<MeshSettings>& mesh_section() {
  using M = MeshSettings;
  using F = FluidMeshSettings;
  static const schema::Section<M> s{
      "outputs.mesh",
      output_keys<M>(
          {schema::choice("format", &M::format, kMeshFormatNames,
                          "`ply`: binary, with normals and the attributes; `obj`: text, with "
                          "normals"),
           schema::number_or_auto("radius", &M::radius, schema::above(0),
                                  "sphere radius of every particle; `auto` = half the particle "
                                  "spacing (the render radius when the spacing is unknown)"),
           schema::lifted(&M::surface,
                          schema::number_or_auto("voxel_size", &F::voxel_size, schema::above(0),
                                                 "world units; `auto` = the radius")),
           schema::lifted(&M::surface,
                          schema::number_or_auto(
                              "closing", &F::closing, schema::at_least(0),
                              "gap closing distance (dilate, then erode by it); `auto` = the "
                              "radius; 0: none (the spheres' union as it is)")),
           schema::lifted(&M::surface,
                          schema::flag("fill_inner", &F::fill_inner,
                                       "inner-full cells filled: one closed surface, no inner "
                                       "shells")),
           schema::lifted(&M::surface,
                          schema::number("adaptivity", &F::adaptivity, schema::between(0, 1),
                                         "OpenVDB's volumeToMesh: 0 a quad per surface voxel; "
                                         "towards 1 fewer, larger faces where it is flat")),
           schema::names("attributes", &M::attributes,
                         "particle attributes as per-vertex float properties (PLY), each from "
                         "the vertex's nearest particle")}),
      check_mesh};
  return s;
}

class MeshOutput final : public Output {
 public:
  MeshOutput(const MeshSettings& s, const OutputContext& c)
      : settings_(s),
        folder_(c.folder),
        fsync_(c.fsync),
        radius_(s.radius.value_or(c.particle_spacing > 0 ? 0.5 * c.particle_spacing : 0.0)),
        comm_(c.comm),
        jobs_(c.writer, c.slots, [this](SnapshotCopy& copy) { write_mesh(copy); }) {}

  void write(const OutputStep& step) override {
    if (comm_ == nullptr || comm_->size() == 1) {
      jobs_.submit("fluid mesh", [&](SnapshotCopy& copy) {
        copy.fill(step.data, settings_.attributes, radius_);
      });
      return;
    }
    // Every rank's part gathered on the root, as the VDB snapshot's: one surface for the whole
    // fluid, with no seams where the ranks' parts meet.
    gathered_.fill(step.data, settings_.attributes, radius_);
    if (!gathered_.gather(*comm_)) return;
    jobs_.submit("fluid mesh", [&](SnapshotCopy& copy) { std::swap(copy, gathered_); });
  }

  OutputTally tally() const override { return jobs_.tally(); }

 private:
  void write_mesh(const SnapshotCopy& s) const {
    const std::vector<AttributeSpan> attributes = s.attribute_spans();
    const char* extension = settings_.format == MeshFormat::ply ? "ply" : "obj";
    write_fluid_mesh(folder_ / step_file_name("fluid", s.step, extension),
                     {s.spheres, s.cells.view(), attributes, s.step, s.time}, settings_.surface,
                     settings_.format, fsync_);
  }

  const MeshSettings settings_;
  const std::filesystem::path folder_;
  const bool fsync_;
  const double radius_;  // 0: the spheres' own radii
  Communicator* const comm_;
  SnapshotCopy gathered_;  // with ranks: the job's whole snapshot, on the root
  PooledJobs<SnapshotCopy> jobs_;
};

}  // namespace

OutputKind mesh_output_kind() {
  return output_kind<MeshSettings, MeshOutput>("mesh", "meshes", mesh_section());
}

}  // namespace voxspan
