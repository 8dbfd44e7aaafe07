// The fluid's level set (see fluid_level_set.h and vdb_snapshot.h, "fluid").
#include "insitu/outputs/formats/fluid_level_set.h"

#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/FastSweeping.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "voxspan/error.h"

namespace voxspan {

namespace {

namespace vdb = openvdb;

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
        const std::size_t at =
            std::size_t(i) + std::size_t(d[0]) * (std::size_t(j) + std::size_t(d[1]) * k);
        if (cells.states[at] != cell::kInnerFull) {
          ++i;
          continue;
        }
        int end = i;
        while (end < d[0] && cells.states[at + std::size_t(end - i)] == cell::kInnerFull) ++end;
        count += std::size_t(end - i);
        const double cs = cells.cell_size;
        const vdb::Coord lo(first_voxel(cells.origin[0] + i * cs),
                            first_voxel(cells.origin[1] + j * cs),
                            first_voxel(cells.origin[2] + k * cs));
        const vdb::Coord hi(first_voxel(cells.origin[0] + end * cs) - 1,
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
    const float v = *it + distance;
    it.setValue(std::clamp(v, -band, band));
    if (v > band || v < -band) it.setValueOff();
  }
  vdb::tools::changeLevelSetBackground(sdf.tree(), band);
  vdb::tools::pruneLevelSet(sdf.tree());
}

}  // namespace

FluidLevelSet build_fluid_level_set(std::span<const ParticleSphere> particles,
                                    const std::array<double, 3>& origin,
                                    const CellStatesView& world_cells,
                                    const FluidLevelSetSettings& settings, std::string_view what,
                                    FluidLevelSetReport& report, Stages& stages) {
  CellStatesView cells = world_cells;
  for (std::size_t a = 0; a < 3; ++a) cells.origin[a] -= origin[a];
  SphereList list{particles, {}, 0};
  list.valid.reserve(particles.size());
  float r_min = std::numeric_limits<float>::max(), r_max = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!is_valid(particles[i])) {
      ++report.particles_invalid;
      continue;
    }
    list.valid.push_back(vdb::Index32(i));
    r_min = std::min(r_min, particles[i].radius);
    r_max = std::max(r_max, particles[i].radius);
  }
  const bool have_cells = !cells.empty() && cells.cell_size > 0;
  const double voxel = settings.voxel_size.value_or(!list.valid.empty() ? r_min
                                                    : have_cells        ? 0.25 * cells.cell_size
                                                                        : 1.0);
  if (!(voxel > 0) || !std::isfinite(voxel))
    throw make_error(what, ": voxel size ", voxel, " is not a positive number");
  list.grow = settings.closing.value_or(list.valid.empty() ? 0.0 : double(r_max));
  report.voxel_size = voxel;
  report.closing = list.grow;

  // The band is widened by the closing distance while building, so that after the erosion
  // the closest-particle attributes still cover the final surface; it is narrowed again after.
  const int grow_voxels = int(std::ceil(list.grow / voxel));
  FluidLevelSet ls;
  stages.next("rasterize");
  ls.sdf = vdb::createLevelSet<vdb::FloatGrid>(voxel, settings.half_width + grow_voxels);
  ls.sdf->setName("fluid");
  if (!list.valid.empty()) {
    vdb::tools::ParticlesToLevelSet<vdb::FloatGrid, vdb::Index32> raster(*ls.sdf);
    raster.rasterizeSpheres(list);
    raster.finalize(/*prune=*/true);
    ls.closest = raster.attributeGrid();
    report.particles_too_small = raster.getMinCount() + raster.getMaxCount();
    report.particles = list.valid.size() - report.particles_too_small;
  }
  stages.next("fill");
  if (settings.fill_inner && have_cells) report.inner_full_cells = fill_inner_full(cells, *ls.sdf);
  // Erode by what the spheres grew: the closing of "fluid" (vdb_snapshot.h). The rasterized
  // union holds true distances only outside the spheres, so first the Eikonal solution from the
  // surface (fast sweeping over the widened band), then the surface moves inward to where
  // that distance is -grow, and the band is cut back to half_width.
  stages.next("close");
  if (list.grow > 0 && !ls.sdf->tree().empty()) {
    ls.sdf = vdb::tools::sdfToSdf(*ls.sdf, 0.f);
    ls.sdf->setName("fluid");
    erode_and_narrow(*ls.sdf, float(list.grow), float(settings.half_width * voxel));
  }
  return ls;
}

void move_to_world(FluidLevelSet& ls, const std::array<double, 3>& origin) {
  if (origin == std::array<double, 3>{0, 0, 0}) return;  // the file as it always was
  const vdb::Vec3d by(origin[0], origin[1], origin[2]);
  for (const vdb::GridBase::Ptr& grid :
       {vdb::GridBase::Ptr(ls.sdf), vdb::GridBase::Ptr(ls.closest)})
    if (grid) {
      vdb::math::Transform::Ptr world = grid->transform().copy();
      world->postTranslate(by);
      grid->setTransform(world);
    }
}

}  // namespace voxspan
