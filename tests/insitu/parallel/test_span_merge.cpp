// Exact compositing (insitu/parallel/span_merge.h) in one process: the particles split into
// parts as ranks would hold them (slabs, interleaved, one part empty), each part voxelized in
// the grid all of them fit (the DepthRangeCombine of an MPI job, here over the parts), the
// parts' span images merged by bands: the same spans as voxelizing everything at once, bit for
// bit, with and without gap bridging and a span cap; a merged pixel's `inside` (summed again)
// within float rounding.
#include <algorithm>

#include "insitu/parallel/span_merge.h"
#include "tests/render/gl/render_fixture.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"
#include "voxspan/classify.h"

namespace voxspan {
namespace {

// The depth range of every part, as the ranks of a job combine theirs.
DepthRangeCombine over_parts(const std::vector<test::Particles>& parts, const Camera& camera,
                             const GridOptions& grid) {
  DepthRange all;
  for (const test::Particles& p : parts) {
    CullCounts counts;
    const PerspectiveGrid g = PerspectiveGrid::fit(camera, p, grid, &counts);
    if (g.empty()) continue;
    all.lo = std::min(all.lo, g.near());
    all.hi = std::max(all.hi, g.far());
    all.counts.visible += counts.visible;
  }
  return [all](const DepthRange&) { return all; };
}

// The ranks' span images merged as direct send merges them: each band of rows from every
// image, then the bands put together.
SpanImage composite(const std::vector<SpanImage>& images, const MergeSettings& merge) {
  const int ranks = int(images.size());
  std::vector<std::vector<std::byte>> bands;
  for (int r = 0; r < ranks; ++r) {
    const RowBand band = band_of(r, ranks, images[0].height());
    std::vector<std::vector<std::byte>> received;
    for (const SpanImage& image : images)
      received.push_back(encode_rows(image, band.begin, band.end));
    bands.push_back(merge_rows(images[0].grid, received, merge));
  }
  return decode_image(images[0].grid, bands);
}

// Each part voxelized alone, its bands exchanged and merged as SpanCompositor does.
SpanImage composite(const std::vector<test::Particles>& parts, const Camera& camera,
                    VoxelizeOptions options) {
  const MergeSettings merge{options.gap_bridging, options.max_spans};
  options.max_spans = 0;  // the ranks keep every span; the merge caps
  options.combine_ranks = over_parts(parts, camera, options.grid);
  std::vector<SpanImage> images;
  for (const test::Particles& p : parts) images.push_back(test::voxelize(camera, p, options));
  return composite(images, merge);
}

struct Case {
  const char* name;
  double gap;
  std::uint32_t cap;
};

TEST(SpanMerge, EverySplitGivesTheSpansOfOneProcess) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  shape.spray_fraction = 0.01;
  const test::Particles all = test::dam_break(shape, 0.3);
  const Camera camera = test::frame_scene(all, {0.4, -0.5, -1}, 160, 96);
  // Slabs along x with an empty part, and parts interleaved all over the fluid.
  std::vector<test::Particles> slabs(4), interleaved(3);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const float x = all[i].x;
    slabs[x < 0.15f ? 0 : x < 0.3f ? 1 : x < 10.0f ? 3 : 2].push_back(all[i]);
    interleaved[i % 3].push_back(all[i]);
  }
  ASSERT_TRUE(slabs[2].empty());
  for (const Case& c : {Case{"no bridging, no cap", 0, 0}, Case{"bridging 1.5 dx", 0.03, 0},
                        Case{"bridging, cap 2", 0.03, 2}}) {
    VoxelizeOptions options;
    options.gap_bridging = c.gap;
    options.max_spans = c.cap;
    const SpanImage one = test::voxelize(camera, all, options);
    for (const auto& [split, parts] :
         {std::pair{"slabs", &slabs}, std::pair{"interleaved", &interleaved}}) {
      const SpanImage merged = composite(*parts, camera, options);
      EXPECT_TRUE(test::same_spans(merged, one, 1e-5))
          << c.name << ", " << split << ": " << test::compare_spans(merged, one).summary()
          << test::describe_mismatches(merged, one, 6);
    }
  }
}

// As the offline renderer's ranks do: each owns a slab and has the particles within two cells
// of it as ghosts, classifies its cells with them (so that its border cells classify as in one
// process) and voxelizes its own boundary particles with its own cell states.
TEST(SpanMerge, RanksWithGhostsAndTheirOwnCellStatesGiveTheSpansOfOneProcess) {
  test::DamBreak shape;
  shape.spacing = test::dam_break_spacing(shape, 20000);
  shape.radius = shape.spacing;
  const test::Particles all = test::dam_break(shape, 0.25);
  // From the side: rays through the column cross the slabs' borders inside the fluid, where a
  // rank's inner-full cells end at another rank's particles, not at its own boundary ones.
  const Camera camera = test::frame_scene(all, {-1, 2, -0.8}, 320, 180);
  ClassifyOptions classify;
  classify.particle_spacing = shape.spacing;
  classify.include_ghosts = false;
  auto classified = [&](const test::Particles& owned, const test::Particles& ghosts) {
    std::vector<double> x, y, z;
    for (const test::Particles* set : {&owned, &ghosts})
      for (const ParticleSphere& p : *set) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
    Classifier c;
    c.run(ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_owned(owned.size()),
          GridView(), classify);
    return c.take_result();
  };
  VoxelizeOptions options;
  options.gap_bridging = shape.spacing;
  const Classification whole = classified(all, {});
  ASSERT_GT(whole.counts.cells_inner_full, 0u);
  const SpanImage one = test::voxelize(camera, whole.boundary, options, whole.cell_states());
  // Two slabs of equal counts, as the offline renderer splits.
  std::vector<float> xs;
  for (const ParticleSphere& p : all) xs.push_back(p.x);
  std::nth_element(xs.begin(), xs.begin() + std::ptrdiff_t(xs.size() / 2), xs.end());
  const int ranks = 2;
  const double margin = 4 * shape.spacing, x_split = xs[xs.size() / 2];
  std::vector<Classification> parts;
  for (int r = 0; r < ranks; ++r) {
    const double lo = r == 0 ? -1e9 : x_split, hi = r == 0 ? x_split : 1e9;
    test::Particles owned, ghosts;
    for (const ParticleSphere& p : all) {
      const bool mine = (p.x >= lo || r == 0) && (p.x < hi || r == ranks - 1);
      if (mine) owned.push_back(p);
      else if (p.x >= lo - margin && p.x < hi + margin) ghosts.push_back(p);
    }
    parts.push_back(classified(owned, ghosts));
  }
  const MergeSettings merge{options.gap_bridging, 0};
  std::vector<test::Particles> boundaries;
  for (const Classification& c : parts) boundaries.push_back(c.boundary);
  options.combine_ranks = over_parts(boundaries, camera, options.grid);
  std::vector<SpanImage> images;
  for (const Classification& c : parts)
    images.push_back(test::voxelize(camera, c.boundary, options, c.cell_states()));
  const SpanImage merged = composite(images, merge);
  EXPECT_TRUE(test::same_spans(merged, one, 1e-5))
      << test::compare_spans(merged, one).summary() << test::describe_mismatches(merged, one, 6);
}

}  // namespace
}  // namespace voxspan
