// outputs.vdb: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread (level_set_outputs.h); the grids built and written on the writer's
// (insitu/outputs/formats/vdb_snapshot.h).
#include "insitu/outputs/kinds/vdb_output.h"

#include "insitu/outputs/kinds/level_set_outputs.h"
#include "insitu/outputs/output.h"

namespace voxspan {
namespace {

const schema::Section<VdbSettings>& vdb_section() {
  using V = VdbSettings;
  using S = VdbSnapshotSettings;
  static const schema::Section<V> s{
      "outputs.vdb",
      output_keys<V>(schema::joined(
          level_set_keys(&V::radius, &V::snapshot),
          std::vector<schema::Key<V>>{
              // half_width is the level set's, a key of the VDB's alone (<S, int>: of S).
              schema::lifted(&V::snapshot,
                             schema::integer<S, int>("half_width", &S::half_width, 1, 64,
                                                     "narrow band, voxels on each side of the "
                                                     "surface")),
              schema::lifted(&V::snapshot,
                             schema::flag("cell_states", &S::cell_states, "the cell-state grid")),
              schema::names("attributes", &V::attributes,
                            "particle attributes written as float or vec3 grids")}))};
  return s;
}

class VdbOutput final : public LevelSetOutput {
 public:
  VdbOutput(const VdbSettings& s, const OutputContext& c)
      : LevelSetOutput(c, s.radius, attribute_names(s, "vdb"), "VDB snapshot",
                       [snapshot = s.snapshot, folder = c.folder,
                        fsync = c.fsync](const VdbSnapshotInput& input) {
                         write_vdb_snapshot(folder / step_file_name("fluid", input.step, "vdb"),
                                            input, snapshot, fsync);
                       }) {}
};

}  // namespace

OutputKind vdb_output_kind() {
  return output_kind<VdbSettings, VdbOutput>("vdb", "VDB", vdb_section());
}

}  // namespace voxspan
