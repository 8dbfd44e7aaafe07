#include "render/cpu/volume_supports.h"

#include <algorithm>
#include <array>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace voxspan::volume_cast {

void project(const PerspectiveGrid& view_grid, const Samples& s,
             std::span<const VolumeParticle> particles, double support, VolumeCounts& counts,
             std::vector<Support>& out) {
  const ViewFrame& f = view_grid.view();
  out.assign(particles.size(), Support{});
  tbb::combinable<std::array<std::int64_t, 2>> tally([] { return std::array<std::int64_t, 2>{}; });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, particles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::array<std::int64_t, 2>& t = tally.local();
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const VolumeParticle& p = particles[i];
                        Support& o = out[i];
                        if (!drawable(p)) {
                          ++t[0];
                          continue;
                        }
                        o.c = f.to_view(glm::dvec3(p.x, p.y, p.z));
                        o.radius = support * p.h;
                        o.rect = view_grid.sphere_pixels(o.c, o.radius);
                        const double lo = std::max(o.c.z - o.radius, s.near);
                        const double hi = o.c.z + o.radius;
                        if (o.rect.empty() || !(hi > lo)) {
                          o.rect = {};  // not binned
                          ++t[1];
                          continue;
                        }
                        o.first = s.lattice.first_at_or_after(lo);
                        o.last = s.lattice.last_at_or_before(hi);
                        if (o.last < o.first) {
                          o.rect = {};
                          ++t[1];
                          continue;
                        }
                        o.inv_h = 1 / double(p.h);
                        o.v = double(p.weight);
                        o.vq = o.v * double(p.value);
                      }
                    });
  tally.combine_each([&](const std::array<std::int64_t, 2>& t) {
    counts.particles_invalid += t[0];
    counts.particles_culled += t[1];
  });
}

void sort_supports(const std::vector<Support>& supports, std::int64_t base,
                   std::vector<std::uint64_t>& keys, std::vector<Support>& sorted) {
  keys.clear();
  for (std::size_t i = 0; i < supports.size(); ++i)
    if (!supports[i].rect.empty())
      keys.push_back(std::uint64_t(supports[i].first - base) << 32 | std::uint64_t(i));
  tbb::parallel_sort(keys.begin(), keys.end());
  sorted.resize(keys.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keys.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k)
                        sorted[k] = supports[keys[k] & 0xffffffffu];
                    });
}

void bin_supports(const Tiles& screen, const std::vector<Support>& sorted, Bins& bins,
                  std::vector<std::uint32_t>& lists) {
  const auto tiles_of = [&](std::size_t k, auto&& f) { screen.each(sorted[k].rect, f); };
  bins.count(screen.count(), sorted.size(), tiles_of);
  lists.resize(bins.size());
  bins.place(tiles_of, [&](std::size_t k, std::uint32_t slot) { lists[slot] = std::uint32_t(k); });
}

}  // namespace voxspan::volume_cast
