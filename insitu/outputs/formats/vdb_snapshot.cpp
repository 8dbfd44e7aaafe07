// The OpenVDB snapshot (see vdb_snapshot.h). The one translation unit that builds grids:
// OpenVDB's templates compile slowly, so nothing else includes them.
#include "insitu/outputs/formats/vdb_snapshot.h"

#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/FastSweeping.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"
#include "voxspan/version.h"

namespace voxspan {

namespace vdb = openvdb;

void ensure_openvdb_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { vdb::initialize(); });
}

namespace {

// Times consecutive stages into `stats`: next() ends the running stage and starts another.
class Stages {
 public:
  explicit Stages(FrameStats& stats) : stats_(stats) {}
  ~Stages() { stop(); }
  Stages(const Stages&) = delete;
  Stages& operator=(const Stages&) = delete;
  void next(std::string_view name) {
    stop();
    name_ = name;
    watch_.restart();
  }
  void stop() {
    if (!name_.empty()) stats_.add_time(name_, watch_.ms());
    name_ = {};
  }

 private:
  FrameStats& stats_;
  std::string_view name_;
  Stopwatch watch_;
};

// The closest particle's index per voxel (ParticlesToLevelSet's attribute transfer).
using IndexGrid = vdb::FloatGrid::ValueConverter<vdb::Index32>::Type;

// The particle list concept of ParticlesToLevelSet over the valid boundary particles, their
// radii grown by the closing distance; the attribute is the particle's index, so that the
// closest particle of every voxel is known afterwards.
struct SphereList {
  using PosType = vdb::Vec3R;
  std::span<const ParticleSphere> spheres;
  std::vector<vdb::Index32> valid;  // indices into spheres
  double grow = 0;

  std::size_t size() const { return valid.size(); }
  void getPos(std::size_t n, vdb::Vec3R& xyz) const {
    const ParticleSphere& s = spheres[valid[n]];
    xyz = vdb::Vec3R(s.x, s.y, s.z);
  }
  void getPosRad(std::size_t n, vdb::Vec3R& xyz, vdb::Real& radius) const {
    getPos(n, xyz);
    radius = spheres[valid[n]].radius + grow;
  }
  void getAtt(std::size_t n, vdb::Index32& index) const { index = valid[n]; }
};

bool is_valid(const ParticleSphere& s) {
  return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) &&
         std::isfinite(s.radius) && s.radius > 0;
}

// Every voxel whose centre lies in an inner-full cell becomes "deep inside" (-background,
// inactive), runs of inner-full cells along x as one box. This is the union with the filled
// cells without building their own level set: the cells' faces are never a surface of the
// fluid (an inner-full cell's neighbours are all full, so boundary particles cover them).
std::size_t fill_inner_full(const CellStatesView& cells, vdb::FloatGrid& sdf) {
  const double voxel = sdf.voxelSize()[0];
  const float inside = -sdf.background();
  std::size_t count = 0;
  const auto& d = cells.dims;
  auto first_voxel = [&](double world) { return int(std::ceil(world / voxel)); };
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0];) {
        std::size_t at =
            std::size_t(i) + std::size_t(d[0]) * (std::size_t(j) + std::size_t(d[1]) * k);
        if (cells.states[at] != cell::kInnerFull) {
          ++i;
          continue;
        }
        int end = i;
        while (end < d[0] && cells.states[at + std::size_t(end - i)] == cell::kInnerFull) ++end;
        count += std::size_t(end - i);
        const double cs = cells.cell_size;
        vdb::Coord lo(first_voxel(cells.origin[0] + i * cs), first_voxel(cells.origin[1] + j * cs),
                      first_voxel(cells.origin[2] + k * cs));
        vdb::Coord hi(first_voxel(cells.origin[0] + end * cs) - 1,
                      first_voxel(cells.origin[1] + (j + 1) * cs) - 1,
                      first_voxel(cells.origin[2] + (k + 1) * cs) - 1);
        if (lo.x() <= hi.x() && lo.y() <= hi.y() && lo.z() <= hi.z())
          sdf.tree().fill(vdb::CoordBBox(lo, hi), inside, /*active=*/false);
        i = end;
      }
  return count;
}

// phi + distance, with the voxels beyond +-band made inactive: erosion of a level set whose
// band holds exact distances at least `distance + band` deep.
void erode_and_narrow(vdb::FloatGrid& sdf, float distance, float band) {
  for (auto it = sdf.tree().beginValueOn(); it; ++it) {
    float v = *it + distance;
    it.setValue(std::clamp(v, -band, band));
    if (v > band || v < -band) it.setValueOff();
  }
  vdb::tools::changeLevelSetBackground(sdf.tree(), band);
  vdb::tools::pruneLevelSet(sdf.tree());
}

vdb::GridBase::Ptr attribute_grid(const IndexGrid& closest, const AttributeSpan& a) {
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

  SphereList list{input.particles, {}, 0};
  list.valid.reserve(input.particles.size());
  float r_min = std::numeric_limits<float>::max(), r_max = 0;
  for (std::size_t i = 0; i < input.particles.size(); ++i) {
    if (!is_valid(input.particles[i])) {
      ++report.particles_invalid;
      continue;
    }
    list.valid.push_back(vdb::Index32(i));
    r_min = std::min(r_min, input.particles[i].radius);
    r_max = std::max(r_max, input.particles[i].radius);
  }
  const bool have_cells = !input.cells.empty() && input.cells.cell_size > 0;
  double voxel = settings.voxel_size.value_or(!list.valid.empty() ? r_min
                                              : have_cells        ? 0.25 * input.cells.cell_size
                                                                  : 1.0);
  if (!(voxel > 0) || !std::isfinite(voxel))
    throw make_error("VDB snapshot: voxel size ", voxel, " is not a positive number");
  list.grow = settings.closing.value_or(list.valid.empty() ? 0.0 : double(r_max));
  report.voxel_size = voxel;
  report.closing = list.grow;

  // The band is widened by the closing distance while building, so that after the erosion
  // the closest-particle attributes still cover the final surface; it is narrowed again after.
  const int grow_voxels = int(std::ceil(list.grow / voxel));
  Stages stage(report.timings);
  stage.next("vdb_rasterize");
  auto fluid = vdb::createLevelSet<vdb::FloatGrid>(voxel, settings.half_width + grow_voxels);
  fluid->setName("fluid");
  IndexGrid::Ptr closest;
  if (!list.valid.empty()) {
    vdb::tools::ParticlesToLevelSet<vdb::FloatGrid, vdb::Index32> raster(*fluid);
    raster.rasterizeSpheres(list);
    raster.finalize(/*prune=*/true);
    closest = raster.attributeGrid();
    report.particles_too_small = raster.getMinCount() + raster.getMaxCount();
    report.particles = list.valid.size() - report.particles_too_small;
  }
  stage.next("vdb_fill");
  if (settings.fill_inner && have_cells) {
    report.inner_full_cells = fill_inner_full(input.cells, *fluid);
  }
  // Erode by what the spheres grew: the closing of "fluid" in the header. The rasterized union
  // holds true distances only outside the spheres, so first the Eikonal solution from the
  // surface (fast sweeping over the widened band), then the surface moves inward to where
  // that distance is -grow, and the band is cut back to half_width.
  stage.next("vdb_close");
  if (list.grow > 0 && !fluid->tree().empty()) {
    fluid = vdb::tools::sdfToSdf(*fluid, 0.f);
    fluid->setName("fluid");
    erode_and_narrow(*fluid, float(list.grow), float(settings.half_width * voxel));
  }
  report.level_set_voxels = fluid->activeVoxelCount();

  stage.next("vdb_attributes");
  vdb::GridCPtrVec grids{fluid};
  for (const AttributeSpan& a : input.attributes)
    if (closest) grids.push_back(attribute_grid(*closest, a));
  if (settings.cell_states && have_cells) grids.push_back(cell_state_grid(input.cells));

  vdb::MetaMap meta;
  meta.insertMeta("creator", vdb::StringMetadata(std::string("voxspan ") + version()));
  meta.insertMeta("step", vdb::Int64Metadata(input.step));
  meta.insertMeta("time", vdb::DoubleMetadata(input.time));
  meta.insertMeta("boundary_particles", vdb::Int64Metadata(std::int64_t(report.particles)));
  meta.insertMeta("inner_full_cells", vdb::Int64Metadata(std::int64_t(report.inner_full_cells)));
  meta.insertMeta("closing", vdb::DoubleMetadata(report.closing));

  stage.next("vdb_write");
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
