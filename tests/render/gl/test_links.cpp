// Surface links ([ZD15] sec. 3.3, Listing 1) on the GPU, checked exactly against links
// worked out by hand on hand-made span images: a bubble, two touching blobs, an overhang, image
// borders and a column with more spans than a link byte can name; and the CPU's implementation
// of the rule (the reference's) against the GPU's on voxelized scenes.
#include <algorithm>
#include <cstdio>

#include "render/model/host.h"
#include "render/reference/reference_shading.h"
#include "tests/render/gl/render_fixture.h"
#include "tests/render/gl/shading_fixture.h"
#include "tools/scenes/scenes.h"

namespace voxspan {
namespace {

constexpr std::uint32_t F = 253;  // FOLD: an entry's link cut at a fold
constexpr std::uint32_t S = 254;  // SELF: entry and exit linked to each other
constexpr std::uint32_t O = 255;  // OWN: bubble wall, to the adjacent point of the own column

// One link word from its bytes: left, right, up, down.
std::uint32_t word(std::uint32_t left, std::uint32_t right, std::uint32_t up, std::uint32_t down) {
  return left | right << 8 | up << 16 | down << 24;
}

// The links the GPU made for a hand-made image (filter off, opaque shading: links only matter).
std::vector<glm::uvec2> gpu_links(const SpanImage& spans) {
  return test::shade_on_gpu(spans, {}, ShadeOptions{}).links;
}

std::string show(std::uint32_t w) {
  char text[32];
  std::snprintf(text, sizeof text, "[%u %u %u %u]", w & 255, w >> 8 & 255, w >> 16 & 255, w >> 24);
  return text;
}

void expect_links(const SpanImage& spans, const std::vector<glm::uvec2>& want) {
  const std::vector<glm::uvec2> got = gpu_links(spans);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t s = 0; s < want.size(); ++s) {
    EXPECT_EQ(got[s].x, want[s].x)
        << "entry of span " << s << ": got " << show(got[s].x) << ", want " << show(want[s].x);
    EXPECT_EQ(got[s].y, want[s].y)
        << "exit of span " << s << ": got " << show(got[s].y) << ", want " << show(want[s].y);
  }
  EXPECT_EQ(reference_links(spans), got) << "the CPU's rule disagrees with the GPU's";
}

TEST(Links, Bubble) {
  // A holds a bubble between depths 2 and 3 that its right neighbour B does not see: A's inner
  // exit and entry are bubble walls linked in their own column; B's exit links A's last exit.
  const SpanImage spans = test::hand_made(2, 1, {{{1, 2}, {3, 4}}, {{1, 4}}});
  expect_links(spans, {
                          {word(S, 0, S, S), word(S, O, S, S)},  // A span 0
                          {word(S, O, S, S), word(S, 0, S, S)},  // A span 1
                          {word(0, S, S, S), word(1, S, S, S)},  // B span 0
                      });
}

TEST(Links, TwoTouchingBlobs) {
  // Blob a at depth [1, 2] over pixels 0-2, blob b behind it over pixels 1-2: they touch in
  // pixel 1 (one span [1, 3]) and are apart in pixel 2 (air between 2 and 2.5), so the air
  // pocket closes between pixels 1 and 2.
  const SpanImage spans = test::hand_made(3, 1, {{{1, 2}}, {{1, 3}}, {{1, 2}, {2.5f, 3}}});
  expect_links(
      spans,
      {
          {word(S, 0, S, S), word(S, 0, S, S)},  // pixel 0
          {word(0, 0, S, S), word(0, 1, S, S)},  // pixel 1: exit to pixel 2's second exit
          {word(0, S, S, S), word(O, S, S, S)},  // pixel 2, span 0: exit is the pocket's wall
          {word(O, S, S, S), word(0, S, S, S)},  // pixel 2, span 1: entry is the pocket's wall
      });
}

TEST(Links, Overhang) {
  // A column of three pixels: a thick block at the top, below it the block's front part and
  // back part with air between, at the bottom only the back part: the front part overhangs.
  const SpanImage spans = test::hand_made(1, 3, {{{1, 5}}, {{1, 2}, {4, 5}}, {{4, 5}}});
  expect_links(spans,
               {
                   {word(S, S, S, 0), word(S, S, S, 1)},  // top
                   {word(S, S, 0, S), word(S, S, O, S)},  // middle, front part: nothing below it
                   {word(S, S, O, 0), word(S, S, 0, 0)},  // middle, back part
                   {word(S, S, 1, S), word(S, S, 1, S)},  // bottom: up to the middle's back part
               });
}

TEST(Links, NoOverlapAndEmptyNeighbours) {
  // Spans that do not overlap in depth, an empty pixel and spans touching at one depth (which
  // overlap: Listing 1 compares with <=).
  const SpanImage spans = test::hand_made(2, 2, {{{1, 2}}, {{3, 4}}, {}, {{2, 3}}});
  expect_links(spans,
               {
                   {word(S, S, S, S), word(S, S, S, S)},  // (0,0): (1,0) is deeper, (0,1) empty
                   {word(S, S, S, 0), word(S, S, S, 0)},  // (1,0): touches (1,1) at depth 3
                   {word(S, S, 0, S), word(S, S, 0, S)},  // (1,1)
               });
}

TEST(Links, SpansPastByteRangeReadAsSurfaceEnds) {
  // 300 thin spans in both pixels: spans 0..252 link across, the rest cannot be named.
  std::vector<Span> column;
  for (int k = 0; k < 300; ++k) column.push_back({1.0f + 0.01f * k, 1.005f + 0.01f * k});
  const SpanImage spans = test::hand_made(2, 1, {column, column});
  const test::GpuResult r = test::shade_on_gpu(spans, {}, ShadeOptions{});
  EXPECT_EQ(r.stats.count("links.unlinkable_spans"), 2 * (300 - 253));
  EXPECT_EQ(r.links[10].x, word(S, 10, S, S));
  EXPECT_EQ(r.links[252].y, word(S, 252, S, S));
  EXPECT_EQ(r.links[253].y, word(S, S, S, S));
  EXPECT_EQ(r.links[260].x, word(S, S, S, S));
  EXPECT_EQ(r.links[300 + 260].x, word(S, S, S, S));
  EXPECT_EQ(reference_links(spans), r.links);
}

std::uint32_t byte_of(std::uint32_t word, int dir) { return word >> (8 * dir) & 255; }

TEST(Links, AFoldIsNotLinkedAcrossAndItsTwoSheetsKeepTheirNormals) {
  // A crest hiding the water behind it, in a column 3 pixels wide: rows 0-3 see the water
  // behind (entry at depth 4), rows 4-7 the crest's front (entry at depth 1) on a span that goes
  // on into that water. Listing 1 links rows 3 and 4 (their spans overlap); with a fold step
  // of 2 their entries are not linked, their exits still are.
  std::vector<std::vector<Span>> columns;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 3; ++x) columns.push_back({{y < 4 ? 4.0f : 1.0f, 6.0f}});
  const SpanImage spans = test::hand_made(3, 8, columns);
  const auto span_at = [&](int y) { return spans.pixel(1, y).offset; };
  enum { kUp = 2, kDown = 3 };
  SurfaceOptions folds;
  folds.fold_step = 2;
  const test::GpuResult linked = test::shade_on_gpu(spans, {}, ShadeOptions{});
  const test::GpuResult cut = test::shade_on_gpu(spans, folds, ShadeOptions{});
  EXPECT_EQ(byte_of(linked.links[span_at(3)].x, kDown), 0u);
  EXPECT_EQ(byte_of(linked.links[span_at(4)].x, kUp), 0u);
  EXPECT_EQ(byte_of(cut.links[span_at(3)].x, kDown), F);
  EXPECT_EQ(byte_of(cut.links[span_at(4)].x, kUp), F);
  EXPECT_EQ(byte_of(cut.links[span_at(3)].y, kDown), 0u);
  EXPECT_EQ(byte_of(cut.links[span_at(4)].y, kUp), 0u);
  EXPECT_EQ(reference_links(spans), linked.links) << "the CPU's rule disagrees with the GPU's";
  EXPECT_EQ(reference_links(spans, 2), cut.links) << "the CPU's rule disagrees with the GPU's";
  EXPECT_EQ(reference_normals(spans, cut.links, 2), cut.normals);
  // Both sheets are flat and face the eye: the rows beside the fold take their sheet's normal
  // (a one-sided difference), where the step, linked, tilted them.
  EXPECT_EQ(cut.normals[span_at(3)].x, cut.normals[span_at(2)].x);
  EXPECT_EQ(cut.normals[span_at(4)].x, cut.normals[span_at(5)].x);
  EXPECT_NE(linked.normals[span_at(3)].x, linked.normals[span_at(2)].x);
  EXPECT_NE(linked.normals[span_at(4)].x, linked.normals[span_at(5)].x);
}

TEST(Links, APointBesideACapUnderTheFoldStepTakesItsNeighboursNormals) {
  // A flat sheet (entries at depth 4) with one particle's cap at pixel (3, 3) standing 1.8 in
  // front of it: under the fold step of 2 it is linked all round, but past the crest's share of
  // it (0.8) the step is finer than a pixel, as where a wave's lip is beaded with caps. The
  // Sobel normal of the point above the cap took the step for a slope (turned away from the
  // sheet's: a bright dot at grazing angles); on the crest it is the mean of its neighbours' off
  // the crest.
  std::vector<std::vector<Span>> columns;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 7; ++x) columns.push_back({{x == 3 && y == 3 ? 2.2f : 4.0f, 6.0f}});
  const SpanImage spans = test::hand_made(7, 7, columns);
  SurfaceOptions folds;
  folds.fold_step = 2;
  const test::GpuResult plain = test::shade_on_gpu(spans, {}, ShadeOptions{});
  const test::GpuResult crest = test::shade_on_gpu(spans, folds, ShadeOptions{});
  EXPECT_EQ(crest.links, plain.links);
  EXPECT_EQ(reference_normals(spans, crest.links, 2), crest.normals);
  model::Host host(spans, {});
  const auto degrees_off_sheet = [&](const test::GpuResult& r, int x, int y) {
    const auto normal = [&](int px, int py) {
      return host.decode_normal(r.normals[spans.pixel(px, py).offset].x);
    };
    return test::degrees_between(normal(x, y), normal(1, 5));
  };
  std::printf("above the cap: %.1f degrees off the sheet, %.1f on the crest\n",
              degrees_off_sheet(plain, 3, 2), degrees_off_sheet(crest, 3, 2));
  EXPECT_GT(degrees_off_sheet(plain, 3, 2), 40);  // 43.6
  EXPECT_LT(degrees_off_sheet(crest, 3, 2), 20);  // 16.5: its neighbours' corners see the cap
}

// The largest angle between two lists of encoded normals, word by word, degrees.
double worst_degrees(const std::vector<glm::uvec2>& a, const std::vector<glm::uvec2>& b) {
  const SpanImage none;
  model::Host host(none, {});
  double worst = a.size() == b.size() ? 0 : 180;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    for (int end = 0; end < 2; ++end)
      worst = std::max(worst, test::degrees_between(host.decode_normal(a[i][end]),
                                                    host.decode_normal(b[i][end])));
  return worst;
}

TEST(Links, CpuRuleMatchesGpuOnVoxelizedScenes) {
  test::DamBreak shape;
  shape.spacing = 0.02;
  shape.radius = 0.02;
  const test::Particles dam = test::dam_break(shape, 0.2);
  const test::Particles cloud = test::random_cloud(400, {0, 0, 0}, {1, 1, 1}, 0.02, 0.1, 3);
  for (const test::Particles* particles : {&dam, &cloud}) {
    VoxelizeOptions options;
    options.gap_bridging = 0.02;
    const Camera camera = test::frame_scene(*particles, {0.4, -0.5, -1}, 160, 96);
    const SpanImage spans = test::voxelize(camera, *particles, options);
    const test::GpuResult r = test::shade_on_gpu(spans, {}, ShadeOptions{});
    ASSERT_GT(spans.spans.size(), 1000u);
    EXPECT_EQ(reference_links(spans), r.links);
    // With folds at 2.5 spacings, many points lie on a crest: the GPU's second normals dispatch
    // (rewriting crest points in place) and the CPU's loop agree up to rounding, as the Sobel
    // normals do (a few words in a thousand differ, by 0.03 degrees at most, folds or not).
    SurfaceOptions folds;
    folds.fold_step = 2.5 * shape.spacing;
    const test::GpuResult folded = test::shade_on_gpu(spans, folds, ShadeOptions{});
    EXPECT_EQ(reference_links(spans, folds.fold_step), folded.links);
    EXPECT_NE(folded.normals, r.normals);
    EXPECT_LT(worst_degrees(reference_normals(spans, r.links, 0), r.normals), 0.1);
    EXPECT_LT(
        worst_degrees(reference_normals(spans, folded.links, folds.fold_step), folded.normals),
        0.1);
    // Every link across names a span that overlaps in depth (sec. 3.3's definition).
    std::size_t checked = 0;
    for (int y = 0; y < spans.height(); ++y)
      for (int x = 0; x < spans.width(); ++x)
        for (std::uint32_t k = 0; k < spans.pixel(x, y).count; ++k) {
          const std::uint32_t s = spans.pixel(x, y).offset + k;
          const int dx[4] = {-1, 1, 0, 0}, dy[4] = {0, 0, -1, 1};
          for (int d = 0; d < 4; ++d)
            for (int end = 0; end < 2; ++end) {
              const std::uint32_t b = (end == 0 ? r.links[s].x : r.links[s].y) >> (8 * d) & 255;
              if (b > 252) continue;
              const PixelSpans& q = spans.pixel(x + dx[d], y + dy[d]);
              ASSERT_LT(b, q.count);
              const Span& mine = spans.spans[s];
              const Span& theirs = spans.spans[q.offset + b];
              EXPECT_TRUE(theirs.entry <= mine.exit && theirs.exit >= mine.entry);
              ++checked;
            }
        }
    EXPECT_GT(checked, spans.spans.size());
  }
}

}  // namespace
}  // namespace voxspan
