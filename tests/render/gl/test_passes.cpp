// The building blocks of the voxelization on the GPU: the prefix sum, the binning of spheres
// into tiles (every tile gets exactly the spheres that touch it, large spheres their own list),
// the GL recorder, the GPU memory tally and the read-back through a staging buffer.
#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <thread>

#include "render/gl/gpu_recorder.h"
#include "render/gl/passes/bin.h"
#include "render/gl/passes/prefix_sum.h"
#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scenes.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

TEST(PrefixSum, MatchesTheCpuAtEveryLevel) {
  PrefixSumPass scan(test::shaders());
  std::mt19937 rng(5);
  for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1023), std::size_t(1024),
                        std::size_t(1025), std::size_t(70001), std::size_t(1100000)}) {
    std::vector<std::uint32_t> values(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) values[i] = rng() % 50;
    gl::Buffer buffer(values.size() * 4, values.data());
    scan.run(buffer, n);
    const std::vector<std::uint32_t> got = buffer.read<std::uint32_t>(n + 1);
    std::vector<std::uint32_t> want(n + 1, 0);
    std::exclusive_scan(values.begin(), values.end(), want.begin(), 0u);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i <= n; ++i) wrong += got[i] != want[i];
    EXPECT_EQ(wrong, 0u) << n << " values";
  }
}

TEST(BinPass, EveryTileListsTheSmallSpheresTouchingIt) {
  test::context();
  const Camera camera = test::look_at({0, 0, 6}, {0, 0, 0}, 160, 96);
  test::Particles p = test::random_cloud(5000, {-3, -2, -1}, {3, 2, 1}, 0.01, 0.08, 12);
  p.push_back({0, 0, 5.5f, 1.0f});  // around the eye: large
  p.push_back({0, 0, -1, 2.5f});    // big on screen: large
  const PerspectiveGrid grid = PerspectiveGrid::fit(camera, p, GridOptions{});
  const TileLayout tiles =
      plan_tiles(160, 96, grid.layers(), 8, {std::size_t(1) << 30, 40, 24}, std::size_t(1) << 30);
  ASSERT_EQ(tiles.count(), 16);
  gl::Buffer particles(p.size() * 16, p.data());
  PrefixSumPass scan(test::shaders());
  BinPass bin(test::shaders());
  const Bins bins = bin.run(particles, p.size(), grid, tiles, scan, true);
  const std::vector<std::uint32_t> lists = bin.lists().read<std::uint32_t>(bins.offsets.back());
  const std::vector<std::uint32_t> large = bin.large_list().read<std::uint32_t>(bins.large);
  EXPECT_EQ(std::set<std::uint32_t>(large.begin(), large.end()),
            (std::set<std::uint32_t>{std::uint32_t(p.size() - 2), std::uint32_t(p.size() - 1)}));
  // Against the CPU's footprints (double): a listed sphere's footprint grown by a pixel meets the
  // tile; a sphere whose footprint shrunk by a pixel meets the tile is listed; no duplicates.
  for (int t = 0; t < tiles.count(); ++t) {
    const TileRect r = tiles.tile(t);
    std::set<std::uint32_t> listed(lists.begin() + bins.offsets[t],
                                   lists.begin() + bins.offsets[t + 1]);
    EXPECT_EQ(listed.size(), bins.offsets[t + 1] - bins.offsets[t]) << "duplicates in tile " << t;
    for (std::uint32_t i = 0; i + 2 < p.size(); ++i) {
      const PixelRect f =
          grid.sphere_pixels(grid.view().to_view({p[i].x, p[i].y, p[i].z}), p[i].radius);
      if (f.empty()) {
        EXPECT_FALSE(listed.count(i)) << "culled sphere " << i << " in tile " << t;
        continue;
      }
      const auto meets = [&](int grow) {
        return f.x0 - grow <= r.x0 + r.width - 1 && f.x1 + grow >= r.x0 &&
               f.y0 - grow <= r.y0 + r.height - 1 && f.y1 + grow >= r.y0;
      };
      if (listed.count(i)) {
        EXPECT_TRUE(meets(1)) << "sphere " << i << " tile " << t;
      } else if (f.x1 - f.x0 > 2 && f.y1 - f.y0 > 2) {
        EXPECT_FALSE(meets(-1)) << "sphere " << i << " tile " << t;
      }
    }
  }
}

TEST(GpuRecorder, TimesDeviceAndHostScopesIntoFrameStats) {
  test::context();
  constexpr StatName clear{"clear"}, sleep{"sleep"}, outer{"outer"}, inner{"inner"};
  FrameStats stats;
  gl::GpuRecorder recorder(stats, test::context().has_gpu_timers());
  gl::Buffer buffer(std::size_t(16) << 20);
  {
    auto t = recorder.device(clear);
    buffer.clear();
  }
  {
    auto t = recorder.host(sleep);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  {
    auto t = recorder.device(clear);
    buffer.clear();
  }
  EXPECT_THROW(
      {
        auto o = recorder.device(outer);
        auto i = recorder.device(inner);
      },
      Error);
  recorder.collect();
  EXPECT_EQ(stats.runs("clear"), 2);
  EXPECT_GT(stats.ms("clear"), 0.0);
  EXPECT_GE(stats.ms("sleep"), 4.0);
  EXPECT_GE(stats.gpu_bytes, std::int64_t(16) << 20);
  EXPECT_GE(stats.gpu_peak_bytes, stats.gpu_bytes);
}

TEST(GpuMemory, BuffersAndTexturesAreTallied) {
  test::context();
  const gl::MemoryUsage before = gl::memory_usage();
  gl::reset_memory_peak();
  {
    gl::Buffer a(std::size_t(3) << 20);
    gl::Texture3D t(GL_R8UI, {64, 32, 16});
    EXPECT_EQ(gl::memory_usage().current_bytes, before.current_bytes + (3 << 20) + 64 * 32 * 16);
    gl::Buffer moved = std::move(a);
    EXPECT_EQ(gl::memory_usage().current_bytes, before.current_bytes + (3 << 20) + 64 * 32 * 16);
    moved.reserve(std::size_t(5) << 20);  // grows: a new buffer, then the old one goes
  }
  EXPECT_EQ(gl::memory_usage().current_bytes, before.current_bytes);
  EXPECT_GE(gl::memory_usage().peak_bytes, before.current_bytes + (8 << 20) + 64 * 32 * 16);
}

// A GPU reads back through its own mapped buffer (render/gl/objects.h); llvmpipe directly. Both
// give the same values, whatever the size (the staging grows) and offset, after a shader wrote
// them.
TEST(Readback, ThroughStagingAsDirect) {
  gl::ReadbackStaging& staging = test::context().staging();
  const bool was = staging.in_use();
  PrefixSumPass scan(test::shaders());
  for (std::size_t n : {std::size_t(5), std::size_t(70001), std::size_t(300000)}) {
    std::vector<std::uint32_t> values(n + 1, 3);
    gl::Buffer buffer(values.size() * 4, values.data());
    scan.run(buffer, n);
    staging.set_in_use(false);
    const std::vector<std::uint32_t> direct = buffer.read<std::uint32_t>(n, 1);
    staging.set_in_use(true);
    const std::vector<std::uint32_t> staged = buffer.read<std::uint32_t>(n, 1);
    EXPECT_EQ(staged, direct) << n;
    EXPECT_EQ(staged.back(), 3 * n);
  }
  staging.set_in_use(was);
}

}  // namespace
}  // namespace voxspan
