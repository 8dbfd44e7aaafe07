// outputs.mesh: the boundary particles, the attributes it names and the cell states copied on
// the solver's thread, as the VDB snapshot's (level_set_outputs.h); the surface meshed and
// written on the writer's (insitu/outputs/formats/mesh_files.h).
#include "insitu/outputs/kinds/mesh_output.h"

#include "insitu/outputs/kinds/level_set_outputs.h"
#include "insitu/outputs/output.h"

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
  static const schema::Section<M> s{
      "outputs.mesh",
      output_keys<M>(schema::joined(
          std::vector<schema::Key<M>>{schema::choice(
              "format", &M::format, kMeshFormatNames,
              "`ply`: binary, with normals and the attributes; `obj`: text, with normals")},
          level_set_keys(&M::radius, &M::surface),
          std::vector<schema::Key<M>>{
              schema::lifted(&M::surface,
                             schema::number("adaptivity", &FluidMeshSettings::adaptivity,
                                            schema::between(0, 1),
                                            "OpenVDB's volumeToMesh: 0 a quad per surface "
                                            "voxel; towards 1 fewer, larger faces where it is "
                                            "flat")),
              schema::names("attributes", &M::attributes,
                            "particle attributes as per-vertex float properties (PLY), each from "
                            "the vertex's nearest particle")})),
      check_mesh};
  return s;
}

class MeshOutput final : public LevelSetOutput {
 public:
  MeshOutput(const MeshSettings& s, const OutputContext& c)
      : LevelSetOutput(c, s.radius, attribute_names(s, "mesh"), "fluid mesh",
                       [surface = s.surface, format = s.format, folder = c.folder,
                        fsync = c.fsync](const FluidMeshInput& input) {
                         const char* extension = format == MeshFormat::ply ? "ply" : "obj";
                         write_fluid_mesh(folder / step_file_name("fluid", input.step, extension),
                                          input, surface, format, fsync);
                       }) {}
};

}  // namespace

OutputKind mesh_output_kind() {
  return output_kind<MeshSettings, MeshOutput>("mesh", "meshes", mesh_section());
}

}  // namespace voxspan
