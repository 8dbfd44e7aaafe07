#include "insitu/views/view_framing.h"

#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace voxspan {
namespace {

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

constexpr double kPi = 3.14159265358979323846;

}  // namespace

void Bounds::add(const Bounds& o) {
  for (int a = 0; a < 3; ++a) {
    lo[std::size_t(a)] = std::min(lo[std::size_t(a)], o.lo[std::size_t(a)]);
    hi[std::size_t(a)] = std::max(hi[std::size_t(a)], o.hi[std::size_t(a)]);
  }
}

Bounds Bounds::of_spheres(std::span<const ParticleSphere> spheres) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, spheres.size(), 16384), Bounds{},
      [&](const tbb::blocked_range<std::size_t>& range, Bounds b) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const ParticleSphere& s = spheres[i];
          if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) &&
                std::isfinite(s.radius) && s.radius > 0))
            continue;
          const double c[3] = {s.x, s.y, s.z};
          for (std::size_t a = 0; a < 3; ++a) {
            b.lo[a] = std::min(b.lo[a], c[a] - s.radius);
            b.hi[a] = std::max(b.hi[a], c[a] + s.radius);
          }
        }
        return b;
      },
      [](Bounds a, const Bounds& b) {
        a.add(b);
        return a;
      });
}

Camera frame_camera(const ViewSettings& view, const Bounds& box) {
  return frame_camera(view.camera, view.width, view.height, box);
}

Camera frame_camera(const CameraConfig& c, int width, int height, const Bounds& box) {
  Camera camera;
  camera.up = vec(c.up);
  camera.fov_y_degrees = c.fov_degrees;
  camera.width = width;
  camera.height = height;
  if (!c.automatic) {
    camera.eye = vec(c.eye);
    camera.target = vec(c.target);
    return camera;
  }
  const glm::dvec3 forward = glm::normalize(vec(c.direction));
  if (box.empty()) {
    camera.target = glm::dvec3(0);
    camera.eye = -forward;
    return camera;
  }
  const glm::dvec3 lo(box.lo[0], box.lo[1], box.lo[2]), hi(box.hi[0], box.hi[1], box.hi[2]);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_y = std::tan(0.5 * c.fov_degrees * kPi / 180.0);
  const double tan_x = tan_y * double(width) / double(height);
  // A corner p (relative to the centre) at depth dist + p.forward is inside the pyramid when
  // |p.right| <= tan_x depth and |p.up| <= tan_y depth: the distance is the largest bound.
  const glm::dvec3 half = 0.5 * (hi - lo) * c.margin;
  double dist = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? half.x : -half.x, (corner & 2) ? half.y : -half.y,
                       (corner & 4) ? half.z : -half.z);
    const double depth_offset = glm::dot(p, forward);
    dist = std::max(dist, std::abs(glm::dot(p, right)) / tan_x - depth_offset);
    dist = std::max(dist, std::abs(glm::dot(p, up)) / tan_y - depth_offset);
  }
  // A box of zero size (one particle of radius 0 never gets here) still needs a distance.
  dist = std::max(dist, 1e-6 * std::max(1.0, glm::length(centre)));
  camera.target = centre;
  camera.eye = centre - dist * forward;
  return camera;
}

Camera ViewFraming::update(std::span<const ParticleSphere> boundary) {
  return update(Bounds::of_spheres(boundary));
}

Camera ViewFraming::update(const Bounds& now) {
  // A manual camera keeps the box too: the environment's ground lies under it.
  const Framing framing = camera_.framing;
  if (framing != Framing::first || box_.empty()) {
    if (framing == Framing::grow) box_.add(now);
    else if (!now.empty()) box_ = now;
  }
  return frame_camera(camera_, width_, height_, box_);
}

void distances_from_view_depth(const Camera& camera, std::span<const float> view_depth,
                               FloatImage& distances) {
  if (distances.width != camera.width || distances.height != camera.height)
    distances = FloatImage(camera.width, camera.height);
  const ViewFrame f(camera);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t k = std::size_t(x) + std::size_t(camera.width) * std::size_t(y);
      distances.set(x, y, glm::vec4(float(double(view_depth[k]) * f.ray_scale(x, y)), 0, 0, 0));
    }
}

void view_depth_from_distances(const Camera& camera, const FloatImage& distances,
                               std::vector<float>& view_depth) {
  const ViewFrame f(camera);
  view_depth.resize(std::size_t(distances.width) * std::size_t(distances.height));
  for (int y = 0; y < distances.height; ++y)
    for (int x = 0; x < distances.width; ++x)
      view_depth[std::size_t(x) + std::size_t(distances.width) * std::size_t(y)] =
          float(double(distances.at(x, y).r) / f.ray_scale(x, y));
}

}  // namespace voxspan
