// The OpenVDB snapshot (see vdb_snapshot.h): the "fluid" level set from fluid_level_set.cpp, the
// attribute and cell-state grids, the file. OpenVDB's templates compile slowly, so only the
// formats that build grids include them.
#include "insitu/outputs/formats/vdb_snapshot.h"

#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>

#include <mutex>

#include "insitu/outputs/formats/fluid_level_set.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"
#include "voxspan/version.h"

namespace voxspan {

namespace vdb = openvdb;

void ensure_openvdb_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { vdb::initialize(); });
}

namespace {

vdb::GridBase::Ptr attribute_grid(const ClosestParticleGrid& closest, const AttributeSpan& a) {
  auto fill = [&](auto grid, auto value_of) {
    grid->setTransform(closest.transform().copy());
    grid->setName(std::string(a.name));
    auto acc = grid->getAccessor();
    for (auto it = closest.cbeginValueOn(); it; ++it) acc.setValue(it.getCoord(), value_of(*it));
    return grid;
  };
  if (a.components == 3)
    return fill(vdb::Vec3SGrid::create(vdb::Vec3s(0)), [&](vdb::Index32 i) {
      return vdb::Vec3s(a.values[3 * i], a.values[3 * i + 1], a.values[3 * i + 2]);
    });
  return fill(vdb::FloatGrid::create(0.f), [&](vdb::Index32 i) { return a.values[i]; });
}

vdb::Int32Grid::Ptr cell_state_grid(const CellStatesView& cells) {
  auto grid = vdb::Int32Grid::create(cell::kInnerEmpty);
  grid->setName("cell_state");
  auto transform = vdb::math::Transform::createLinearTransform(cells.cell_size);
  transform->postTranslate(vdb::Vec3d(cells.origin[0] + 0.5 * cells.cell_size,
                                      cells.origin[1] + 0.5 * cells.cell_size,
                                      cells.origin[2] + 0.5 * cells.cell_size));
  grid->setTransform(transform);
  grid->insertMeta("states", vdb::StringMetadata("0 empty, 1 partial, 2 full; +4 inner "
                                                 "(the cell and its 26 neighbours agree)"));
  auto acc = grid->getAccessor();
  std::size_t at = 0;
  for (int k = 0; k < cells.dims[2]; ++k)
    for (int j = 0; j < cells.dims[1]; ++j)
      for (int i = 0; i < cells.dims[0]; ++i, ++at)
        if (cells.states[at] != cell::kInnerEmpty)
          acc.setValue(vdb::Coord(i, j, k), cells.states[at]);
  return grid;
}

// Archive::write to any seekable stream (io::File insists on opening the file itself, and
// then cannot tell a full disk from success).
class StreamArchive : public vdb::io::Archive {
 public:
  void write_to(std::ostream& os, const vdb::GridCPtrVec& grids, const vdb::MetaMap& meta) const {
    vdb::io::Archive::write(os, grids, /*seekable=*/true, meta);
  }
};

}  // namespace

VdbSnapshotReport write_vdb_snapshot(const std::filesystem::path& path,
                                     const VdbSnapshotInput& input,
                                     const VdbSnapshotSettings& settings, bool sync) {
  ensure_openvdb_initialized();
  check_attributes(input.attributes, input.particles.size());
  VdbSnapshotReport report;

  Stages stage(report.timings, "vdb_");
  FluidLevelSet ls = build_fluid_level_set(input.particles, input.origin, input.cells, settings,
                                           "VDB snapshot", report, stage);
  move_to_world(ls, input.origin);
  report.level_set_voxels = ls.sdf->activeVoxelCount();

  stage.next("attributes");
  vdb::GridCPtrVec grids{ls.sdf};
  for (const AttributeSpan& a : input.attributes)
    if (ls.closest) grids.push_back(attribute_grid(*ls.closest, a));
  const bool have_cells = !input.cells.empty() && input.cells.cell_size > 0;
  if (settings.cell_states && have_cells) grids.push_back(cell_state_grid(input.cells));

  vdb::MetaMap meta;
  meta.insertMeta("creator", vdb::StringMetadata(std::string("voxspan ") + version()));
  meta.insertMeta("step", vdb::Int64Metadata(input.step));
  meta.insertMeta("time", vdb::DoubleMetadata(input.time));
  meta.insertMeta("boundary_particles", vdb::Int64Metadata(std::int64_t(report.particles)));
  meta.insertMeta("inner_full_cells", vdb::Int64Metadata(std::int64_t(report.inner_full_cells)));
  meta.insertMeta("closing", vdb::DoubleMetadata(report.closing));

  stage.next("write");
  AtomicFile file(path);
  try {
    StreamArchive().write_to(file.stream(), grids, meta);
  } catch (const vdb::Exception& e) {
    file.check();  // a failed write (ENOSPC...) is a WriteError with its errno
    throw make_error("OpenVDB could not write ", path.string(), ": ", e.what());
  }
  file.commit(sync);
  report.bytes = file.bytes_written();
  stage.stop();
  return report;
}

}  // namespace voxspan
