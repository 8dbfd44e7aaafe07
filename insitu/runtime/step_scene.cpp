#include "insitu/runtime/step_scene.h"

#include <cstring>
#include <sstream>

#include "insitu/parallel/communicator.h"
#include "voxspan/log.h"

namespace voxspan {

std::string point_text(const std::array<double, 3>& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

Bounds StepScene::fluid_box(std::span<const ParticleSphere> boundary,
                            const std::array<double, 3>& origin) {
  BulkBox::Range range = BulkBox::range(boundary);
  if (comm_ != nullptr) {
    comm_->min(range.centres.lo);
    comm_->max(range.centres.hi);
    comm_->sum(range.count_and_radii);
  }
  flat_axis_ = voxspan::flat_axis(range.centres);
  BulkBox::histogram(boundary, range, bulk_scratch_, bulk_bins_);
  if (comm_ != nullptr) comm_->sum(bulk_bins_);
  BulkBox::Split split = BulkBox::split(boundary, BulkBox::kept(range, bulk_bins_));
  if (comm_ != nullptr) {
    comm_->min(split.box.lo);
    comm_->max(split.box.hi);
    comm_->min(split.left_out_box.lo);
    comm_->max(split.left_out_box.hi);
    comm_->sum(std::span(&split.left_out, 1));
  }
  // Binned in the spheres' frame (every rank's is the same), told and framed in the world's.
  split.box.move(origin);
  split.left_out_box.move(origin);
  tell_strays(split);
  return split.box;
}

// Escaping particles must not flood the log: said when they first appear and when their
// number has doubled since.
void StepScene::tell_strays(const BulkBox::Split& split) {
  if (split.left_out == 0) {
    strays_told_ = 0;
    return;
  }
  if (strays_told_ > 0 && split.left_out < 2 * strays_told_) return;
  strays_told_ = split.left_out;
  if (comm_ != nullptr && !comm_->root()) return;
  log_warning("automatic framing leaves out ", split.left_out,
              split.left_out == 1 ? " particle" : " particles",
              " far from the fluid (centres from ", point_text(split.left_out_box.lo), " to ",
              point_text(split.left_out_box.hi), "); it frames ", point_text(split.box.lo), " to ",
              point_text(split.box.hi), " (camera.bounds frames a box of your own)");
}

// With ranks the versions only grow, so their sum changes whenever any rank's does.
const Scenery& StepScene::update_scenery(const StepData& data) {
  if (comm_ == nullptr) {
    if (data.scenery_version != scenery_.version) {
      scenery_.box = Bounds::of_spheres(data.scenery);
      scenery_.version = data.scenery_version;
    }
    scenery_.spheres = data.scenery;
    return scenery_;
  }
  std::int64_t version = std::int64_t(data.scenery_version);
  comm_->sum(std::span(&version, 1));
  if (std::uint64_t(version) == scenery_.version) return scenery_;
  scenery_.version = std::uint64_t(version);
  scenery_.box = Bounds::of_spheres(data.scenery);
  comm_->min(scenery_.box.lo);
  comm_->max(scenery_.box.hi);
  const std::vector<std::vector<std::byte>> parts = comm_->gather(std::as_bytes(data.scenery));
  scenery_spheres_.clear();
  for (const std::vector<std::byte>& part : parts) {
    const std::size_t n = part.size() / sizeof(ParticleSphere);
    if (n == 0) continue;  // a rank with none (memcpy must not see its null data)
    const std::size_t at = scenery_spheres_.size();
    scenery_spheres_.resize(at + n);
    std::memcpy(scenery_spheres_.data() + at, part.data(), n * sizeof(ParticleSphere));
  }
  scenery_.spheres = comm_->root() ? std::span<const ParticleSphere>(scenery_spheres_)
                                   : std::span<const ParticleSphere>();
  return scenery_;
}

}  // namespace voxspan
