#include "vdb_level_set.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/RayIntersector.h>

#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace voxspan::tools {
namespace {

// ParticlesToLevelSet's particle list concept, over the caller's arrays (no copy).
class ParticleList {
 public:
  using PosType = openvdb::Vec3R;
  ParticleList(const std::vector<float>& x, const std::vector<float>& y,
               const std::vector<float>& z, double radius)
      : x_(x), y_(y), z_(z), radius_(radius) {}
  std::size_t size() const { return x_.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& p) const { p = openvdb::Vec3R(x_[n], y_[n], z_[n]); }
  void getPosRad(std::size_t n, openvdb::Vec3R& p, openvdb::Real& r) const {
    getPos(n, p);
    r = radius_;
  }

 private:
  const std::vector<float>&x_, &y_, &z_;
  double radius_;
};

// A ray's hits, one after the other: the first is the entry; from inside the next crossing is
// the exit. Past this many crossings a ray stops (a frame's rays meet far fewer).
constexpr int kMaxCrossings = 64;

}  // namespace

PeerSurface vdb_level_set_surface(const std::vector<float>& x, const std::vector<float>& y,
                                  const std::vector<float>& z, double radius, const Camera& camera,
                                  const VdbLevelSetOptions& options) {
  if (!(options.voxel > 0) || !(radius > 0) || x.size() != y.size() || x.size() != z.size())
    throw make_error("vdb_level_set_surface: voxel and radius must be > 0 and x, y, z alike");
  openvdb::initialize();
  PeerSurface out;
  const Stopwatch total;
  openvdb::FloatGrid::Ptr grid;
  {
    const Stopwatch watch;
    grid = openvdb::createLevelSet<openvdb::FloatGrid>(options.voxel, options.half_width);
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
    raster.setRmin(options.min_radius_voxels);
    raster.rasterizeSpheres(ParticleList(x, y, z, radius));
    raster.finalize(true);
    if (raster.ignoredParticles())
      out.note = std::to_string(raster.getMinCount()) + " particles under the minimum radius (" +
                 std::to_string(options.min_radius_voxels) + " voxels) left out";
    out.ms["rasterize"] = watch.ms();
  }
  if (options.smoothing > 0) {
    const Stopwatch watch;
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
    for (int i = 0; i < options.smoothing; ++i) filter.mean(1);
    out.ms["smooth"] = watch.ms();
  }
  out.elements = grid->activeVoxelCount();

  const Stopwatch watch;
  const ViewFrame view(camera);
  const std::size_t pixels = std::size_t(camera.width) * camera.height;
  out.first_hit.assign(pixels, std::numeric_limits<float>::infinity());
  out.thickness.assign(pixels, 0.0f);
  out.spans.assign(pixels, {});
  using Intersector = openvdb::tools::LevelSetRayIntersector<openvdb::FloatGrid>;
  const Intersector intersector(*grid);
  // A crossing is an entry or an exit as the field is negative (inside) or not a tenth of a
  // voxel past it, where the level set's gradient (1) far outweighs the crossing's rounding;
  // the next crossing is looked for from there.
  const double past = 0.1 * options.voxel;
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height), [&](const auto& rows) {
    Intersector local = intersector;  // one per task: the intersector is not thread safe
    const openvdb::FloatGrid::ConstAccessor values = grid->getConstAccessor();
    const openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
        sample(values, grid->transform());
    for (int py = rows.begin(); py < rows.end(); ++py)
      for (int px = 0; px < camera.width; ++px) {
        const glm::dvec3 d = glm::normalize(view.world_ray(px, py));
        const openvdb::Vec3R eye(view.eye.x, view.eye.y, view.eye.z), dir(d.x, d.y, d.z);
        const std::size_t i = std::size_t(px) + std::size_t(py) * camera.width;
        double t0 = 0, inside = 0, entry = 0;
        bool in = sample.wsSample(eye) < 0;  // the eye in the fluid: inside from it on
        for (int k = 0; k < kMaxCrossings; ++k) {
          openvdb::math::Ray<double> ray(eye, dir, t0);
          openvdb::Vec3R hit;
          double t = 0;
          if (!local.intersectsWS(ray, hit, t)) break;
          if (k == 0) out.first_hit[i] = float(t);
          t0 = t + past;
          const bool entering = sample.wsSample(eye + t0 * dir) < 0;
          if (entering && !in) {
            entry = t;
          } else if (!entering && in) {
            inside += t - entry;
            out.spans[i].insert(out.spans[i].end(), {float(entry), float(t)});
          }
          in = entering;
        }
        out.thickness[i] = float(inside);
      }
  });
  out.ms["cast"] = watch.ms();
  out.ms["total"] = total.ms();
  return out;
}

}  // namespace voxspan::tools
