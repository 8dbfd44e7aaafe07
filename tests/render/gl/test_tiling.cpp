// Tiles from a memory budget ([ZD15] sec. 3.1): as few tiles as fit, evened out, covering
// the image exactly once; a budget below one tile row is a clear error naming the budget needed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/gl/tiling.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr std::size_t kGiB = std::size_t(1) << 30;

void expect_exact_cover(const TileLayout& t) {
  std::vector<int> hits(static_cast<std::size_t>(t.image_width) * t.image_height, 0);
  for (int i = 0; i < t.count(); ++i) {
    const TileRect r = t.tile(i);
    ASSERT_GT(r.width, 0);
    ASSERT_GT(r.height, 0);
    ASSERT_LE(r.width, t.tile_width);
    ASSERT_LE(r.height, t.tile_height);
    for (int y = r.y0; y < r.y0 + r.height; ++y)
      for (int x = r.x0; x < r.x0 + r.width; ++x)
        ++hits[static_cast<std::size_t>(x + y * t.image_width)];
  }
  for (int h : hits) ASSERT_EQ(h, 1);
}

TEST(Tiling, TheWholeImageFitsABigBudget) {
  const TileLayout t = plan_tiles(960, 540, 2400, 8, {kGiB, 0, 0}, kGiB);
  EXPECT_EQ(t.count(), 1);
  EXPECT_EQ(t.column_bytes, std::size_t(19 * 16));  // 2400 layers in 19 uvec4s
  EXPECT_EQ(t.tile_bytes, t.column_bytes * 960 * 540);
  expect_exact_cover(t);
}

TEST(Tiling, BudgetSetsTheRowsAndTilesAreEvenedOut) {
  const std::size_t row = 1920 * (2048 + scratch_bytes_per_pixel(8));  // 16384 layers
  const TileLayout t = plan_tiles(1920, 1080, 16384, 8, {300 * row, 0, 0}, kGiB);
  EXPECT_EQ(t.rows, 4);  // 1080 rows in tiles of at most 300
  EXPECT_EQ(t.tile_height, 270);
  EXPECT_LE(t.tile_bytes + scratch_bytes_per_pixel(8) * 1920 * 270, 300 * row);
  expect_exact_cover(t);
}

TEST(Tiling, OneBindingLimitsATile) {
  // The paper's 1920x1080x16384 grid, 4.2 GB: with a 1 GiB binding, tiles of at most 1 GiB.
  const TileLayout t = plan_tiles(1920, 1080, 16384, 8, {8 * kGiB, 0, 0}, kGiB);
  EXPECT_LE(t.tile_bytes, kGiB);
  EXPECT_EQ(t.rows, 4);  // 270 rows of 3.9 MB: just under 1 GiB
  expect_exact_cover(t);
}

TEST(Tiling, TwoDimensionalTilesWithMaxWidthAndHeight) {
  const TileLayout t = plan_tiles(100, 70, 256, 4, {kGiB, 37, 13}, kGiB);
  EXPECT_EQ(t.columns, 3);
  EXPECT_EQ(t.rows, 6);
  EXPECT_EQ(t.tile_width, 34);
  EXPECT_EQ(t.tile_height, 12);
  expect_exact_cover(t);
}

TEST(Tiling, BudgetBelowOneRowNamesTheBudgetNeeded) {
  const std::size_t row = 640 * (8 * 16 + scratch_bytes_per_pixel(8));  // 1024 layers
  try {
    plan_tiles(640, 480, 1024, 8, {row - 1, 0, 0}, kGiB);
    FAIL() << "accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("at least " + std::to_string(row) + " bytes"), std::string::npos) << what;
  }
  EXPECT_EQ(plan_tiles(640, 480, 1024, 8, {row, 0, 0}, kGiB).rows, 480);
}

}  // namespace
}  // namespace voxspan
