// Per-step stats: the JSON line format, accumulation, the append-only file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <thread>
#include <vector>

#include "insitu/outputs/formats/stats_log.h"
#include "insitu/outputs/formats/stats_record.h"
#include "insitu/runtime/host_memory.h"
#include "tests/support/temp_folder.h"
#include "voxspan/stopwatch.h"

namespace voxspan {
namespace {

TEST(Stats, JsonLineHasTotalsMemoryAndViews) {
  StatsRecord r;
  r.step = 120;
  r.time = 0.6;
  r.totals.add_time("classify", 3.25);
  r.totals.add_count("particles", 100000);
  r.totals.add_count("boundary", 31000);
  r.totals.add_count("dropped", 0);
  r.set_memory("host_rss", 812.5);
  r.view("main").add_time("splat", 40);
  r.view("main").add_time("splat", 2);  // per tile: accumulates
  r.view("main").add_count("spans", 1203311);
  r.view("side \"2\"").add_time("shade", std::nan(""));
  EXPECT_EQ(to_json_line(r),
            "{\"step\":120,\"time\":0.6,\"timings_ms\":{\"classify\":3.25},"
            "\"counters\":{\"particles\":100000,\"boundary\":31000,\"dropped\":0},"
            "\"memory_mib\":{\"host_rss\":812.5},"
            "\"views\":{\"main\":{\"timings_ms\":{\"splat\":42},\"counters\":{\"spans\":1203311}},"
            "\"side \\\"2\\\"\":{\"timings_ms\":{\"shade\":null},\"counters\":{}}}}\n");
  EXPECT_EQ(r.view("main").count("spans"), 1203311);
  EXPECT_EQ(r.totals.ms("nothing"), 0);
}

// A step that failed says why on its line (a view that failed used to leave no trace there).
TEST(Stats, AFailedStepSaysWhy) {
  StatsRecord r;
  r.step = 7;
  r.error = "view v: \"bad\" value";
  EXPECT_EQ(to_json_line(r),
            "{\"step\":7,\"time\":0,\"timings_ms\":{},\"counters\":{},\"memory_mib\":{},"
            "\"views\":{},\"error\":\"view v: \\\"bad\\\" value\"}\n");
  r.zero();
  EXPECT_EQ(to_json_line(r).find("error"), std::string::npos);
}

TEST(Stats, ClearKeepsViewsForTheNextStep) {
  StatsRecord r;
  r.view("main").add_count("spans", 5);
  r.clear();
  EXPECT_EQ(r.views.size(), 1u);
  EXPECT_TRUE(r.views[0].second.empty());
  EXPECT_TRUE(r.totals.empty());
}

TEST(Stats, StopwatchMeasuresItsWallTime) {
  const Stopwatch watch;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_GE(watch.ms(), 4.5);
}

// The peak is never below the resident size (the kernel's high-water mark lags: it read below
// it on most stats lines), and never falls from one read to the next.
TEST(Stats, HostMemoryIsReported) {
  const HostMemory m = host_memory();
  EXPECT_GT(m.rss_bytes, 1u << 20);
  EXPECT_GE(m.peak_bytes, m.rss_bytes);
  std::vector<char> grown(std::size_t(64) << 20, 1);  // resident, then freed
  const HostMemory with = host_memory();
  grown = {};
  const HostMemory after = host_memory();
  EXPECT_GE(with.peak_bytes, with.rss_bytes);
  EXPECT_GE(after.peak_bytes, with.peak_bytes);
  EXPECT_GE(after.peak_bytes, after.rss_bytes);
}

TEST(Stats, LogAppendsCompleteLines) {
  test::TempFolder dir;
  {
    StatsLog log(dir / "stats.jsonl");
    StatsRecord r;
    for (int i = 0; i < 3; ++i) {
      r.step = i;
      log.append(to_json_line(r));
    }
    log.sync();
    EXPECT_EQ(log.lines(), 3u);
  }
  {
    StatsLog more(dir / "stats.jsonl", /*append=*/true);
    more.append("{\"step\":3}\n");
  }
  std::ifstream in(dir / "stats.jsonl");
  int lines = 0;
  for (std::string line; std::getline(in, line);) {
    EXPECT_EQ(line.rfind("{\"step\":" + std::to_string(lines), 0), 0u) << line;
    ++lines;
  }
  EXPECT_EQ(lines, 4);
}

}  // namespace
}  // namespace voxspan
