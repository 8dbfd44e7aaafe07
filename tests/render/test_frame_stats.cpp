// The one stats record every pass reports into: times add up per pass, counts and figures by
// name, one JSON line.
#include <gtest/gtest.h>

#include "render/frame_stats.h"

namespace voxspan {
namespace {

TEST(FrameStats, TimesCountsAndFiguresByName) {
  FrameStats s;
  s.add_time("splat", 2.0);
  s.add_time("compress", 1.0);
  s.add_time("splat", 3.0);
  s.add_count("spans", 5);
  s.add_count("spans", 6);
  s.set_count("tiles", 4);
  s.set_count("tiles", 3);
  s.set_figure("grid.near", 0.25);
  EXPECT_DOUBLE_EQ(s.ms("splat"), 5.0);
  EXPECT_EQ(s.runs("splat"), 2);
  EXPECT_DOUBLE_EQ(s.ms("missing"), 0.0);
  EXPECT_DOUBLE_EQ(s.total_ms(), 6.0);
  EXPECT_EQ(s.count("spans"), 11);
  EXPECT_EQ(s.count("tiles"), 3);
  EXPECT_TRUE(s.has_count("tiles"));
  EXPECT_FALSE(s.has_count("missing"));
  EXPECT_DOUBLE_EQ(s.figure("grid.near"), 0.25);
  s.gpu_bytes = 10;
  s.gpu_peak_bytes = 20;
  EXPECT_EQ(s.json(),
            "{\"passes\":{\"splat\":{\"ms\":5,\"runs\":2},\"compress\":{\"ms\":1,\"runs\":1}},"
            "\"counts\":{\"spans\":11,\"tiles\":3},\"figures\":{\"grid.near\":0.25},"
            "\"gpu_bytes\":10,\"gpu_peak_bytes\":20}");
  s.clear();
  EXPECT_TRUE(s.passes.empty());
}

}  // namespace
}  // namespace voxspan
