#include "render/reference/volume_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "render/model/volume_host.h"

namespace voxspan {
namespace {

// A particle whose support the ray crosses, and where.
struct Crossing {
  std::size_t index;
  double near, far;  // depth interval of the chord
};

bool usable(const VolumeParticle& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.h) &&
         std::isfinite(p.weight) && std::isfinite(p.value) && p.h > 0 && p.weight > 0;
}

struct Sums {
  double s = 0, w = 0;
};

// The sums of the ray's crossings at depth z on the ray z * dir (view space).
template <SphKernel K>
Sums sums_at(std::span<const VolumeParticle> particles, const std::vector<glm::dvec3>& centres,
             const std::vector<Crossing>& crossings, glm::dvec3 dir, double z,
             std::int64_t& evaluations) {
  Sums out;
  for (const Crossing& c : crossings) {
    if (z < c.near || z > c.far) continue;
    const VolumeParticle& p = particles[c.index];
    const glm::dvec3 d = z * dir - centres[c.index];
    const double shape = kernel_shape<K>(std::sqrt(glm::dot(d, d)) / double(p.h));
    out.s += double(p.weight) * double(p.value) * shape;
    out.w += double(p.weight) * shape;
    ++evaluations;
  }
  return out;
}

template <SphKernel K>
FieldSums gradient_at(std::span<const VolumeParticle> particles,
                      const std::vector<glm::dvec3>& centres,
                      const std::vector<Crossing>& crossings, glm::dvec3 point) {
  FieldSums out;
  for (const Crossing& c : crossings) {
    const VolumeParticle& p = particles[c.index];
    const glm::dvec3 d = point - centres[c.index];
    const double h = p.h, dist = std::sqrt(glm::dot(d, d)), q = dist / h;
    if (q >= kernel_support(K)) continue;
    const double shape = kernel_shape<K>(q);
    const glm::dvec3 g = dist > 0 ? (kernel_slope<K>(q) / (h * dist)) * d : glm::dvec3(0);
    out.s += double(p.weight) * double(p.value) * shape;
    out.w += double(p.weight) * shape;
    out.grad_s += double(p.weight) * double(p.value) * g;
    out.grad_w += double(p.weight) * g;
  }
  return out;
}

}  // namespace

VolumeCounts volume_reference(const Camera& camera, std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, VolumeFrame& out) {
  validate(camera);
  validate(options);
  const ViewFrame f(camera);
  const VolumeLattice lattice = volume_lattice(f.tan_half_y, f.height, options);
  const double near_clip = options.anchor;  // as the renderers clip
  const double support = kernel_support(options.kernel);
  VolumeCounts counts;
  counts.particles = std::int64_t(particles.size());
  std::vector<glm::dvec3> centres(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!usable(particles[i])) {
      ++counts.particles_invalid;
      continue;
    }
    centres[i] = f.to_view(glm::dvec3(particles[i].x, particles[i].y, particles[i].z));
  }
  out.reset(camera.width, camera.height);
  tbb::enumerable_thread_specific<model::VolumeHost> hosts(options);
  tbb::combinable<VolumeCounts> tallies;
  with_kernel(options.kernel, [&]<SphKernel K>() {
    tbb::parallel_for(0, camera.height, [&](int y) {
      model::VolumeHost& host = hosts.local();
      VolumeCounts& t = tallies.local();
      std::vector<Crossing> crossings;
      for (int x = 0; x < camera.width; ++x) {
        const glm::dvec3 dir = f.view_ray(x, y);
        const double a = glm::dot(dir, dir), scale = std::sqrt(a);
        crossings.clear();
        std::int64_t first = std::numeric_limits<std::int64_t>::max(), last = 0;
        for (std::size_t i = 0; i < particles.size(); ++i) {
          if (!usable(particles[i])) continue;
          const glm::dvec3& c = centres[i];
          const double r = support * particles[i].h;
          const double b = glm::dot(dir, c), disc = b * b - a * (glm::dot(c, c) - r * r);
          if (!(disc > 0)) continue;
          const double root = std::sqrt(disc);
          const double d0 = std::max((b - root) / a, near_clip), d1 = (b + root) / a;
          if (d1 < d0) continue;
          // A chord between two samples adds to none, but to an iso hit's gradient between them.
          crossings.push_back({i, d0, d1});
          const std::int64_t i0 = lattice.first_at_or_after(d0);
          const std::int64_t i1 = lattice.last_at_or_before(d1);
          if (i1 < i0) continue;
          first = std::min(first, i0);
          last = std::max(last, i1);
        }
        model::RayHits hits;
        host.record_into(&hits);
        model::VolumeHost::VolumeRay ray = host.vx_ray_start();
        float first_depth = 0;
        bool first_is_hit = false;
        for (std::int64_t i = first; !crossings.empty() && i <= last; ++i) {
          const double z = lattice.depth(i);
          const Sums sum = sums_at<K>(particles, centres, crossings, dir, z, t.kernel_evaluations);
          const bool defined = sum.w > 0 && (!options.shepard || sum.w >= options.weight_floor);
          const double q = !defined ? 0.0 : options.shepard ? sum.s / sum.w : sum.s;
          t.samples += defined ? 1 : 0;
          const float before = ray.transmittance;
          const int had = hits.count;
          ray = host.vx_sample(ray, float(q), defined ? 1u : 0u, float(z),
                               float(lattice.extent(z) * scale));
          if (first_depth == 0 && had == 0 && hits.count > 0) {
            first_depth = hits.hit[0].depth * float(scale);
            first_is_hit = true;
          }
          if (first_depth == 0 && before >= 0.5f && ray.transmittance < 0.5f)
            first_depth = float(z * float(scale));
          if (ray.transmittance < options.termination) {
            ++t.rays_stopped;
            break;
          }
        }
        t.iso_hits += hits.count + hits.unlit_count;
        t.iso_hits_unlit += hits.unlit_count;
        for (int h = 0; h < hits.count; ++h) {
          model::IsoHit& hit = hits.hit[std::size_t(h)];
          const FieldSums g =
              gradient_at<K>(particles, centres, crossings, double(hit.depth) * dir);
          host.refine_hit(hit, g, dir, options.shepard, lattice.k * double(hit.depth));
          ray.color += host.hit_light(hit, field_gradient(g, options.shepard), f, x, y);
        }
        if (first_is_hit) first_depth = hits.hit[0].depth * float(scale);
        out.picture.set(x, y, host.pixel_color(ray, hits.unlit, options.background, f, x, y));
        out.depth[std::size_t(x) + std::size_t(y) * std::size_t(camera.width)] = first_depth;
      }
    });
  });
  tallies.combine_each([&](const VolumeCounts& t) { counts += t; });
  return counts;
}

FieldValue volume_field(std::span<const VolumeParticle> particles, const VolumeOptions& options,
                        glm::dvec3 point) {
  double s = 0, w = 0;
  with_kernel(options.kernel, [&]<SphKernel K>() {
    for (const VolumeParticle& p : particles) {
      if (!usable(p)) continue;
      const double shape = kernel_shape<K>(glm::length(point - glm::dvec3(p.x, p.y, p.z)) / p.h);
      s += double(p.weight) * double(p.value) * shape;
      w += double(p.weight) * shape;
    }
  });
  FieldValue f;
  f.w = w;
  f.defined = w > 0 && (!options.shepard || w >= options.weight_floor);
  if (f.defined) f.q = options.shepard ? s / w : s;
  return f;
}

VolumeFrame converged_volume(const Camera& camera, std::span<const VolumeParticle> particles,
                             const VolumeOptions& options, double tolerance, int max_doublings,
                             int* doublings) {
  VolumeOptions o = options;
  VolumeFrame last, next;
  volume_reference(camera, particles, o, last);
  int k = 0;
  for (; k < max_doublings; ++k) {
    o.sampling *= 2;
    volume_reference(camera, particles, o, next);
    double change = 0;
    for (std::size_t i = 0; i < next.picture.rgba.size(); ++i)
      change = std::max(change, double(std::abs(next.picture.rgba[i] - last.picture.rgba[i])));
    std::swap(last, next);
    if (change <= tolerance) {
      ++k;
      break;
    }
  }
  if (doublings != nullptr) *doublings = k;
  return last;
}

}  // namespace voxspan
