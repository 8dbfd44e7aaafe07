// The snapshot inspector's OpenVDB side (see vdb_inspect.h): grid statistics, and a picture of
// a level set with OpenVDB's reference ray tracer.
#include "insitu/io/vdb_inspect.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/RayTracer.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "voxspan/error.h"

namespace voxspan {

void ensure_openvdb_initialized();  // vdb_snapshot.cpp

namespace vdb = openvdb;

namespace {

double magnitude(double v) { return v; }
template <class T> double magnitude(const vdb::math::Vec3<T>& v) { return double(v.length()); }

template <class GridT> bool value_range(const vdb::GridBase& base, double& lo, double& hi) {
  const auto* grid = dynamic_cast<const GridT*>(&base);
  if (!grid) return false;
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    double v = magnitude(*it);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo > hi) lo = hi = 0;
  return true;
}

VdbGridSummary summarize(const vdb::GridBase& grid) {
  VdbGridSummary s;
  s.name = grid.getName();
  s.value_type = grid.valueType();
  s.grid_class = vdb::GridBase::gridClassToMenuName(grid.getGridClass());
  vdb::Vec3d voxel = grid.voxelSize();
  s.voxel_size = {voxel[0], voxel[1], voxel[2]};
  s.active_voxels = grid.activeVoxelCount();
  vdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (s.active_voxels > 0) {
    s.index_min = {box.min().x(), box.min().y(), box.min().z()};
    s.index_max = {box.max().x(), box.max().y(), box.max().z()};
    // Voxel centres of the extreme voxels, widened by half a voxel: the region they cover.
    vdb::Vec3d lo = grid.indexToWorld(box.min().asVec3d() - vdb::Vec3d(0.5));
    vdb::Vec3d hi = grid.indexToWorld(box.max().asVec3d() + vdb::Vec3d(0.5));
    for (int a = 0; a < 3; ++a) {
      s.world_min[a] = std::min(lo[a], hi[a]);
      s.world_max[a] = std::max(lo[a], hi[a]);
    }
  }
  value_range<vdb::FloatGrid>(grid, s.min_value, s.max_value) ||
      value_range<vdb::DoubleGrid>(grid, s.min_value, s.max_value) ||
      value_range<vdb::Int32Grid>(grid, s.min_value, s.max_value) ||
      value_range<vdb::Int64Grid>(grid, s.min_value, s.max_value) ||
      value_range<vdb::Vec3SGrid>(grid, s.min_value, s.max_value) ||
      value_range<vdb::Vec3DGrid>(grid, s.min_value, s.max_value);
  if (const auto* ls = dynamic_cast<const vdb::FloatGrid*>(&grid);
      ls && grid.getGridClass() == vdb::GRID_LEVEL_SET && s.active_voxels > 0)
    s.level_set_volume = vdb::tools::levelSetVolume(*ls);
  return s;
}

// Opens a .vdb file with errors that name it.
class OpenFile {
 public:
  explicit OpenFile(const std::filesystem::path& path) : file_(path.string()) {
    ensure_openvdb_initialized();
    try {
      file_.open(/*delayLoad=*/false);
    } catch (const vdb::Exception& e) {
      throw make_error("cannot read VDB file ", path.string(), ": ", e.what());
    }
  }
  ~OpenFile() { file_.close(); }
  vdb::io::File& operator*() { return file_; }
  vdb::io::File* operator->() { return &file_; }

 private:
  vdb::io::File file_;
};

}  // namespace

VdbFileSummary inspect_vdb(const std::filesystem::path& path) {
  OpenFile file(path);
  VdbFileSummary summary;
  vdb::MetaMap::Ptr meta = file->getMetadata();
  for (auto it = meta->beginMeta(); it != meta->endMeta(); ++it)
    summary.metadata.emplace_back(it->first, it->second->str());
  vdb::GridPtrVecPtr grids = file->getGrids();
  for (const vdb::GridBase::Ptr& grid : *grids) summary.grids.push_back(summarize(*grid));
  return summary;
}

ImageRGBA8 render_level_set(const std::filesystem::path& path, const LevelSetView& view) {
  OpenFile file(path);
  vdb::FloatGrid::Ptr level_set;
  vdb::GridPtrVecPtr grids = file->getGrids();  // kept: a range-for over *temporary dangles
  for (const vdb::GridBase::Ptr& grid : *grids) {
    if (grid->getGridClass() != vdb::GRID_LEVEL_SET) continue;
    if (!view.grid.empty() && grid->getName() != view.grid) continue;
    level_set = vdb::gridPtrCast<vdb::FloatGrid>(grid);
    if (level_set) break;
  }
  if (!level_set)
    throw make_error(path.string(), ": no float level set",
                     view.grid.empty() ? std::string() : " named \"" + view.grid + "\"");
  if (view.width <= 0 || view.height <= 0)
    throw make_error("picture size ", view.width, "x", view.height, " is not positive");

  vdb::tools::Film film(std::size_t(view.width), std::size_t(view.height),
                        vdb::tools::Film::RGBA(0.55f, 0.62f, 0.70f, 1.f));
  if (level_set->activeVoxelCount() > 0) {
    vdb::CoordBBox box = level_set->evalActiveVoxelBoundingBox();
    vdb::Vec3d lo = level_set->indexToWorld(box.min()), hi = level_set->indexToWorld(box.max());
    vdb::Vec3d centre = 0.5 * (lo + hi);
    double radius = 0.5 * (hi - lo).length();
    vdb::Vec3d dir(view.direction[0], view.direction[1], view.direction[2]);
    if (dir.length() == 0) throw make_error("view direction must not be zero");
    dir.normalize();
    const double aspect = double(view.width) / double(view.height);
    const double half_v = 0.5 * view.fov_degrees * vdb::math::pi<double>() / 180.0;
    const double half_h = std::atan(std::tan(half_v) * aspect);
    const double distance = 1.05 * radius / std::sin(std::min(half_v, half_h));
    vdb::Vec3d eye = centre - dir * distance;
    // PerspectiveCamera: half the frame width over the focal length is tan(horizontal fov/2).
    const double focal = 50.0, aperture = 2.0 * focal * std::tan(half_v) * aspect;
    vdb::tools::PerspectiveCamera camera(film, vdb::Vec3R(0.0), eye, focal, aperture,
                                         1e-3 * distance, 4.0 * distance);
    camera.lookAt(centre, vdb::Vec3R(view.up[0], view.up[1], view.up[2]));
    vdb::tools::DiffuseShader<> shader(vdb::tools::Film::RGBA(0.85f, 0.9f, 1.0f));
    vdb::tools::rayTrace(*level_set, shader, camera, 1, 0, true);
  }
  ImageRGBA8 image{view.width, view.height,
                   std::vector<std::uint8_t>(std::size_t(view.width) * view.height * 4)};
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const auto& p = film.pixel(std::size_t(x), std::size_t(y));
      std::uint8_t* out = &image.pixels[(std::size_t(y) * view.width + x) * 4];
      out[0] = linear_to_srgb8(p.r);
      out[1] = linear_to_srgb8(p.g);
      out[2] = linear_to_srgb8(p.b);
      out[3] = 255;
    }
  return image;
}

}  // namespace voxspan
