// The smallest solver loop with in-situ visualization: hand your particles to the adapter
// every step; it does the work on render steps only.
#include <voxspan/adapter.h>

#include <cstdio>
#include <vector>

int main() {
  const int n = 20;  // a 20^3 block of particles, spacing 1
  std::vector<float> xyz;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) xyz.insert(xyz.end(), {i + 0.5f, j + 0.5f, k + 0.5f});

  voxspan::AdapterOptions options;
  options.render_every = 10;
  options.classify.particle_spacing = 1.0;
  voxspan::Adapter adapter(options);

  for (int step = 0; step <= 20; ++step) {
    for (std::size_t p = 2; p < xyz.size(); p += 3) xyz[p] -= 0.01f;  // your solver here
    const auto particles = voxspan::ParticleView::aos(xyz.data(), xyz.size() / 3);
    if (!adapter.execute(step, 0.01 * step, particles).ok()) return 1;
  }
  const voxspan::StepStats& s = adapter.last_stats();
  std::printf("step %lld: %zu of %zu particles on the boundary\n", (long long)s.step,
              s.counts.boundary, s.counts.particles);
  return 0;
}
