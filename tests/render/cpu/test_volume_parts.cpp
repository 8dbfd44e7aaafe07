// A volume frame split over simulated ranks (render/volume_parts.h: cover, shared ranges, the
// ranks' parts, the merge and its field sums, as insitu/parallel/volume_exchange.h runs them
// over MPI) against one process's frame of all the particles: slab, interleaved and uneven
// splits of 2 to 4 ranks, every mode, the picture (and the iso hits' depths) equal up to
// rounding with termination 0, and within the termination with it on; adaptive sampling over
// ranks within the tolerance of the merged full-rate picture; level of detail merging each
// rank's particles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "render/cpu/volume_caster.h"
#include "render/cpu/volume_lod.h"
#include "render/cpu/volume_renderer.h"
#include "render/volume_merge.h"
#include "tests/support/volume_cloud.h"
#include "tools/scenes/scenes.h"
#include "tests/support/image_difference.h"
#include "tests/support/sanitizers.h"

namespace voxspan {
namespace {

// Which rank particle i of n goes to.
using Split = std::function<int(std::size_t i, std::size_t n, const VolumeParticle& p)>;

struct Merged {
  VolumeFrame frame;
  std::int64_t raws = 0, segments = 0;
  VolumeCounts counts;  // the ranks' parts'
};

// The frame of `particles` cast by `ranks` casters, each over its share, and merged.
Merged split_frame(const Camera& camera, const std::vector<VolumeParticle>& particles,
                   const VolumeOptions& o, int rank_count, const Split& split) {
  const std::size_t ranks = std::size_t(rank_count);
  std::vector<std::vector<VolumeParticle>> shares(ranks);
  for (std::size_t i = 0; i < particles.size(); ++i)
    shares[std::size_t(split(i, particles.size(), particles[i]))].push_back(particles[i]);
  std::vector<VolumeCaster> casters(ranks);
  std::vector<std::vector<SampleRange>> hulls(ranks);
  for (std::size_t r = 0; r < ranks; ++r) casters[r].cover(camera, shares[r], o, hulls[r]);
  const std::size_t pixels = std::size_t(camera.width) * std::size_t(camera.height);
  std::vector<PixelRanges> shared(ranks);
  for (PixelRanges& s : shared) s.start.assign(pixels + 1, 0);
  std::vector<SampleRange> of_pixel(ranks);
  std::vector<std::vector<SampleRange>> cut(ranks);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::size_t r = 0; r < ranks; ++r) {
      of_pixel[r] = hulls[r][p];
      cut[r].clear();
    }
    shared_ranges(of_pixel, cut);
    for (std::size_t r = 0; r < ranks; ++r) {
      PixelRanges& s = shared[r];
      s.ranges.insert(s.ranges.end(), cut[r].begin(), cut[r].end());
      s.start[p + 1] = std::uint32_t(s.ranges.size());
    }
  }
  std::vector<VolumePart> parts(ranks);
  Merged out;
  for (std::size_t r = 0; r < ranks; ++r) {
    out.counts += casters[r].run_part(shared[r], parts[r]);
    out.raws += std::int64_t(parts[r].raws.size());
    out.segments += std::int64_t(parts[r].segments.size());
  }
  ParallelVolumeMerge merge(camera, o);
  merge.merge(0, pixels, ranks, [&](std::size_t p, auto& raws, auto& segments) {
    for (std::size_t r = 0; r < ranks; ++r) {
      raws[r] = parts[r].raws_of(p);
      segments[r] = parts[r].segments_of(p);
    }
  });
  const std::vector<HitQuery>& queries = merge.queries();
  std::vector<FieldSums> sums(queries.size());
  for (std::size_t r = 0; r < ranks; ++r) {
    std::vector<FieldSums> mine;
    casters[r].field_sums(queries, mine);
    for (std::size_t q = 0; q < queries.size(); ++q) sums[q] += mine[q];
  }
  std::vector<glm::vec4> colors;
  merge.finish(sums, colors, out.frame.depth);
  out.frame.picture = FloatImage(camera.width, camera.height);
  for (std::size_t p = 0; p < pixels; ++p)
    out.frame.picture.set(int(p % std::size_t(camera.width)), int(p / std::size_t(camera.width)),
                          colors[p]);
  return out;
}

using test::largest_difference;

struct NamedSplit {
  std::string name;
  Split split;
};

std::vector<NamedSplit> splits(int ranks, double lo, double hi) {
  return {{"slab",
           [=](std::size_t, std::size_t, const VolumeParticle& p) {
             return std::clamp(int((p.x - lo) / (hi - lo) * ranks), 0, ranks - 1);
           }},
          {"interleaved", [=](std::size_t i, std::size_t,
                              const VolumeParticle&) { return int(i % std::size_t(ranks)); }},
          {"uneven", [=](std::size_t i, std::size_t n, const VolumeParticle&) {
             // the first rank 70 %, the others the rest in blocks, the last none at 3 and more
             const std::size_t big = n * 7 / 10;
             if (i < big) return 0;
             const int others = std::max(1, ranks - (ranks >= 3 ? 2 : 1));
             return 1 + int((i - big) * std::size_t(others) / (n - big));
           }}};
}

TEST(VolumeParts, MergedFramesAreOneProcesssUpToRounding) {
  const test::Cloud c = test::cloud(10, 11);
  double lo = 1e30, hi = -1e30;
  for (const VolumeParticle& p : c.particles)
    lo = std::min(lo, double(p.x)), hi = std::max(hi, double(p.x));
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::iso, VolumeMode::mixed}) {
    VolumeOptions o = test::cloud_options(mode, c.spacing);
    o.termination = 0;
    VolumeCaster whole;
    VolumeFrame one;
    whole.run(c.camera, c.particles, o, one);
    for (int ranks : {2, 3, 4})
      for (const NamedSplit& s : splits(ranks, lo, hi)) {
        SCOPED_TRACE(std::string(name_of(kVolumeModeNames, mode)) + " " + s.name + " " +
                     std::to_string(ranks));
        const Merged m = split_frame(c.camera, c.particles, o, ranks, s.split);
        const double d = largest_difference(m.frame.picture.rgba, one.picture.rgba);
        std::printf(
            "%-5s %-11s %d ranks: largest channel difference %.1e (%lld shared sums, "
            "%lld segments)\n",
            name_of(kVolumeModeNames, mode).data(), s.name.c_str(), ranks, d,
            static_cast<long long>(m.raws), static_cast<long long>(m.segments));
        EXPECT_LT(d, 1e-5);
        // The depth output is the first iso hit's, exact, or the point of opacity 0.5, which a
        // segment behind other fluid places at its own (render/volume_parts.h).
        if (mode != VolumeMode::iso) continue;
        for (std::size_t i = 0; i < one.depth.size(); ++i)
          EXPECT_NEAR(m.frame.depth[i], one.depth[i], 1e-5 * one.depth[i] + 1e-7) << i;
      }
  }
}

TEST(VolumeParts, WallsEndEveryRanksRaysWhereOneProcessEndsThem) {
  // A wall through the block on the left half of the view (render/backdrop.h), none on the
  // right: each rank's rays end at it and the merge shows its colour behind the fluid.
  const test::Cloud c = test::cloud(10, 11);
  double lo = 1e30, hi = -1e30;
  for (const VolumeParticle& p : c.particles)
    lo = std::min(lo, double(p.x)), hi = std::max(hi, double(p.x));
  Backdrop walls;
  walls.width = c.camera.width;
  walls.height = c.camera.height;
  for (int y = 0; y < walls.height; ++y)
    for (int x = 0; x < walls.width; ++x)
      walls.pixels.push_back(x < walls.width / 2 ? glm::vec4(0.8f, 0.1f, 0.1f, 2.3f)
                                                 : glm::vec4(0.1f, 0.2f, 0.7f, Backdrop::kNoWall));
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::mixed}) {
    VolumeOptions o = test::cloud_options(mode, c.spacing);
    o.termination = 0;
    o.backdrop = &walls;
    VolumeCaster whole;
    VolumeFrame one;
    whole.run(c.camera, c.particles, o, one);
    for (const NamedSplit& s : splits(3, lo, hi)) {
      SCOPED_TRACE(std::string(name_of(kVolumeModeNames, mode)) + " " + s.name);
      const Merged m = split_frame(c.camera, c.particles, o, 3, s.split);
      EXPECT_LT(largest_difference(m.frame.picture.rgba, one.picture.rgba), 1e-5);
    }
  }
}

TEST(VolumeParts, WithLevelOfDetailEachRankDrawsItsOwnMergedParticles) {
  // Far particles, every h under half a pixel, merged at level 1 (render/cpu/volume_lod.h) on
  // each rank from its own: the merged frame is one process's frame of the ranks' merged
  // particles up to rounding. (Against one process merging all of them, the cells a split cuts
  // are merged on each side: a picture within level of detail's own error, not the same.)
  test::Cloud c = test::cloud(30, 13);
  const double mid = 0.5 * 29 * c.spacing;
  c.camera = test::look_at({mid + 6, mid + 8, mid + 30}, {mid, mid, mid}, 80, 60, 30);
  VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  o.termination = 0;
  o.level_of_detail = 1;
  for (const NamedSplit& s : splits(2, 0, 29 * c.spacing)) {
    if (s.name == "uneven") continue;
    SCOPED_TRACE(s.name);
    std::vector<VolumeParticle> merged;
    VolumeLod lod;
    for (int r = 0; r < 2; ++r) {
      std::vector<VolumeParticle> share;
      for (std::size_t i = 0; i < c.particles.size(); ++i)
        if (s.split(i, c.particles.size(), c.particles[i]) == r) share.push_back(c.particles[i]);
      LodCounts counts;
      const std::span<const VolumeParticle> drawn =
          lod.run(ViewFrame(c.camera), share, o.level_of_detail, counts);
      merged.insert(merged.end(), drawn.begin(), drawn.end());
    }
    VolumeOptions off = o;
    off.level_of_detail = 0;
    VolumeCaster whole;
    VolumeFrame one;
    whole.run(c.camera, merged, off, one);
    const Merged m = split_frame(c.camera, c.particles, o, 2, s.split);
    const double d = largest_difference(m.frame.picture.rgba, one.picture.rgba);
    std::printf("%-11s: %zu particles drawn of %zu; largest channel difference %.1e\n",
                s.name.c_str(), merged.size(), c.particles.size(), d);
    EXPECT_LT(merged.size() * 20, c.particles.size());
    EXPECT_LT(d, 1e-5);
  }
}

TEST(VolumeParts, WithEarlyTerminationTheyDifferByAtMostTheTermination) {
  const test::Cloud c = test::cloud(10, 12);
  VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  o.termination = 0.02;
  for (auto& e : o.transfer.rgba) e.a = std::min(1.0f, e.a * 4);  // rays that stop
  VolumeCaster whole;
  VolumeFrame one;
  const VolumeCounts counts = whole.run(c.camera, c.particles, o, one);
  EXPECT_GT(counts.rays_stopped, 100);
  const Merged m =
      split_frame(c.camera, c.particles, o, 3,
                  [](std::size_t i, std::size_t, const VolumeParticle&) { return int(i % 3); });
  EXPECT_LT(largest_difference(m.frame.picture.rgba, one.picture.rgba), o.termination);
}

TEST(VolumeParts, AdaptiveSamplingOverRanksStaysWithinTheTolerance) {
  // A block of two concentrations, one per half (flat: super-pixels), split over 1 and 3 ranks,
  // each rank with 1 / ranks of the tolerance (as insitu/views/volume_compositor.cpp gives it):
  // the merged picture within the tolerance of the merged full-rate picture, every channel, with
  // and without early termination and background. Interleaved, every sample is shared: nothing
  // to skip, and nothing moves.
  const double s = 0.05;
  const test::Particles block = test::lattice_block({0, 0, 0}, {20, 20, 20}, s, s);
  std::vector<VolumeParticle> particles;
  for (const ParticleSphere& b : block)
    particles.push_back(
        {b.x, b.y, b.z, float(1.3 * s), float(1 / std::pow(1.3, 3)), b.y < 10 * s ? 0.3f : 0.7f});
  const Camera camera = test::frame_scene(block, {-0.4, -0.5, -1}, 240, 160);
  VolumeOptions base = test::cloud_options(VolumeMode::dvr, s);
  base.transfer.lo = 0;
  base.transfer.hi = 1;
  for (int k = 0; k < kTransferEntries; ++k) {
    const float u = float(k) / (kTransferEntries - 1);
    base.transfer.rgba[std::size_t(k)] = {u, 0.6f - 0.4f * u, 1 - u, 0.03f + 0.15f * u};
  }
  std::int64_t skipped_on_3 = 0;
  // Under the sanitizers with early termination only (half the frames); Release runs both.
  const std::vector<double> terminations =
      test::kUnderSanitizers ? std::vector<double>{1e-3} : std::vector<double>{0.0, 1e-3};
  for (int ranks : {1, 3})
    for (const NamedSplit& split : splits(ranks, 0, 20 * s)) {
      if (split.name == "uneven" || (split.name == "interleaved" && ranks == 1)) continue;
      for (double termination : terminations)
        for (bool background : {true, false}) {
          VolumeOptions o = base;
          o.termination = termination;
          o.background = background;
          const Merged exact = split_frame(camera, particles, o, ranks, split.split);
          for (double tolerance : {0.004, 0.01}) {
            o.adaptive = {tolerance, 0, 1.0 / ranks};
            const Merged adaptive = split_frame(camera, particles, o, ranks, split.split);
            std::size_t over = 0;
            for (std::size_t i = 0; i < exact.frame.picture.rgba.size(); ++i)
              over += std::abs(adaptive.frame.picture.rgba[i] - exact.frame.picture.rgba[i]) >
                              tolerance + 1e-6
                          ? 1
                          : 0;
            std::printf(
                "%d ranks %-11s termination %g %-5s tolerance %.3f: largest %.2e, %zu channels "
                "over; %lld super-pixel cells, %lld samples skipped\n",
                ranks, split.name.c_str(), termination, background ? "sky" : "none", tolerance,
                largest_difference(adaptive.frame.picture.rgba, exact.frame.picture.rgba), over,
                static_cast<long long>(adaptive.counts.cells_super_pixel),
                static_cast<long long>(adaptive.counts.samples_skipped));
            EXPECT_EQ(over, 0u) << ranks << " ranks " << split.name << " tolerance " << tolerance;
            if (ranks == 3) skipped_on_3 += adaptive.counts.samples_skipped;
          }
        }
    }
  EXPECT_GT(skipped_on_3, 0);
}

TEST(VolumeParts, ARankWithNoParticlesChangesNothing) {
  const test::Cloud c = test::cloud(6, 13);
  VolumeOptions o = test::cloud_options(VolumeMode::mixed, c.spacing);
  o.termination = 0;
  VolumeCaster whole;
  VolumeFrame one;
  whole.run(c.camera, c.particles, o, one);
  const Merged m = split_frame(c.camera, c.particles, o, 2,
                               [](std::size_t, std::size_t, const VolumeParticle&) { return 1; });
  EXPECT_LT(largest_difference(m.frame.picture.rgba, one.picture.rgba), 1e-6);
  EXPECT_EQ(m.raws, 0);
}

TEST(VolumeParts, TheDeepImageFlattensToThePicture) {
  const test::Cloud c = test::cloud(9, 14);
  for (VolumeMode mode : {VolumeMode::dvr, VolumeMode::mixed}) {
    VolumeOptions o = test::cloud_options(mode, c.spacing);
    o.background = false;
    const std::unique_ptr<VolumeRenderer> renderer = make_cpu_volume_renderer();
    Recorder recorder;
    VolumeFrame one, merged;
    renderer->render(c.camera, c.particles, o, recorder, one);
    render_with_deep(*renderer, c.camera, c.particles, o, recorder, merged);
    EXPECT_LT(largest_difference(merged.picture.rgba, one.picture.rgba), 1e-5);
    // Over, front to back, as OpenEXR flattens deep samples.
    double worst = 0;
    std::size_t samples = 0;
    for (std::size_t p = 0; p < merged.depth.size(); ++p) {
      glm::vec4 flat(0.0f);
      float z = 0;
      for (const DeepSample& s : merged.deep.of(p)) {
        EXPECT_LT(s.z, s.z_back);
        EXPECT_GE(s.z, z);
        z = s.z_back;
        flat += (1 - flat.a) * s.rgba;
        ++samples;
      }
      for (int ch = 0; ch < 4; ++ch)
        worst =
            std::max(worst, double(std::abs(flat[ch] - one.picture.rgba[4 * p + std::size_t(ch)])));
    }
    std::printf("%s: %zu deep samples, flattened against the picture %.1e\n",
                name_of(kVolumeModeNames, mode).data(), samples, worst);
    EXPECT_GT(samples, merged.depth.size() / 4);
    EXPECT_LT(worst, 1e-5);
  }
}

}  // namespace
}  // namespace voxspan
