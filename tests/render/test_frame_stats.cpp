// The one stats record every pass reports into: times add up per pass, counts and figures by
// name, one JSON line; and the recorder the passes report through (the CPU renderer's, on the
// wall clock: the GL one is tested with the GL passes, tests/render/gl/test_passes.cpp).
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "render/frame_stats.h"
#include "render/recorder.h"

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

TEST(Recorder, ScopesAddTheirTimesWhenCollectedIntoTheStatsNamed) {
  constexpr StatName sleep{"sleep"}, device{"device"}, tiles{"tiles"}, near{"grid.near"};
  FrameStats first, second;
  Recorder recorder(first);
  {
    auto outer = recorder.host(sleep);
    auto inner = recorder.device(device);  // nests: no device timer here
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
  recorder.count(tiles, 4);
  recorder.add(tiles, 2);
  recorder.figure(near, 0.5);
  EXPECT_EQ(first.runs(sleep), 0) << "times arrive when collected";
  EXPECT_EQ(first.count(tiles), 6) << "counts arrive at once";
  recorder.collect();
  EXPECT_EQ(first.runs(sleep), 1);
  EXPECT_GE(first.ms(sleep), 2.5);
  EXPECT_GE(first.ms(device), 2.5);
  EXPECT_LE(first.ms(device), first.ms(sleep));
  EXPECT_DOUBLE_EQ(first.figure(near), 0.5);
  EXPECT_EQ(first.gpu_bytes, 0);

  recorder.record_into(second);
  { auto t = recorder.host(sleep); }
  recorder.collect();
  EXPECT_EQ(first.runs(sleep), 1) << "the first frame's stats are left alone";
  EXPECT_EQ(second.runs(sleep), 1);
  EXPECT_FALSE(second.has_count(tiles));
}

}  // namespace
}  // namespace voxspan
