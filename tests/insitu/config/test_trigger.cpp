// Triggers and the per-step schedule.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "insitu/config/trigger.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/schedule.h"

namespace voxspan {
namespace {

std::vector<std::int64_t> fired_steps(TriggerSpec spec, const std::vector<std::int64_t>& steps,
                                      std::int64_t last = -1) {
  Trigger t(spec);
  std::vector<std::int64_t> fired;
  for (std::int64_t s : steps)
    if (t.is_due(s, double(s), s == last)) fired.push_back(s);
  return fired;
}

std::vector<std::int64_t> range(std::int64_t from, std::int64_t to, std::int64_t by = 1) {
  std::vector<std::int64_t> v;
  for (std::int64_t s = from; s <= to; s += by) v.push_back(s);
  return v;
}

TEST(Trigger, EveryNStepsFiresOnMultiples) {
  EXPECT_EQ(fired_steps({10, 0, false, false}, range(0, 35)),
            (std::vector<std::int64_t>{0, 10, 20, 30}));
  // A run restarted at step 13 fires at the next multiple, not at once.
  EXPECT_EQ(fired_steps({10, 0, false, false}, range(13, 35)), (std::vector<std::int64_t>{20, 30}));
}

TEST(Trigger, EveryNStepsNeverMissesAMultipleWhenCalledSparsely) {
  // Called every 3 steps: fires at the first call at or past each multiple of 10.
  EXPECT_EQ(fired_steps({10, 0, false, false}, range(0, 40, 3)),
            (std::vector<std::int64_t>{0, 12, 21, 30}));
}

TEST(Trigger, FirstAndLast) {
  EXPECT_EQ(fired_steps({0, 0, true, false}, range(5, 9)), (std::vector<std::int64_t>{5}));
  EXPECT_EQ(fired_steps({0, 0, false, true}, range(5, 9), 9), (std::vector<std::int64_t>{9}));
  EXPECT_EQ(fired_steps({4, 0, true, true}, range(1, 10), 10),
            (std::vector<std::int64_t>{1, 4, 8, 10}));
  EXPECT_TRUE(fired_steps({0, 0, false, false}, range(0, 100)).empty());
  EXPECT_TRUE((TriggerSpec{0, 0, false, false}).never_fires());
}

// With a variable time step, "every T" fires exactly once per multiple of T crossed, at the
// first step whose time reaches it: checked against a brute-force count.
TEST(Trigger, EveryTimeIsRobustToVariableTimeSteps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dt(1e-4, 0.03);
  const double period = 0.05;
  Trigger t({0, period, false, false});
  double time = 0;
  int fires = 0;
  double previous = -1;
  for (std::int64_t step = 0; step < 5000; ++step) {
    bool due = t.is_due(step, time);
    // Multiples of the period in (previous, time]; time 0 is itself a multiple.
    long crossed = step == 0 ? 1
                             : long(std::floor(time / period + 1e-9)) -
                                   long(std::floor(previous / period + 1e-9));
    EXPECT_EQ(due, crossed > 0) << "step " << step << " time " << time;
    fires += due;
    previous = time;
    time += dt(rng);
  }
  EXPECT_EQ(fires, int(std::floor(previous / period + 1e-9)) + 1);
}

TEST(Trigger, TimeSumsJustBelowAMultipleStillFire) {
  Trigger t({0, 1.0, false, false});
  double time = 0;
  int fires = 0;
  for (int step = 0; step <= 30; ++step) {  // 0.1 summed ten times is 0.9999999999999999
    fires += t.is_due(step, time);
    time += 0.1;
  }
  EXPECT_EQ(fires, 4);  // at 0, 1, 2 and 3 (time ends at 3.0000000000000013)
}

TEST(Trigger, NonFiniteTimeNeverFiresTheTimeTrigger) {
  Trigger t({0, 0.5, false, false});
  EXPECT_FALSE(t.is_due(0, std::nan("")));
  EXPECT_FALSE(t.is_due(1, std::nan("")));
  // The first finite time starts the schedule, as a first call would.
  EXPECT_FALSE(t.is_due(2, 0.6));
  EXPECT_TRUE(t.is_due(3, 1.0));
}

TEST(Trigger, CombinedConditionsFireWhenAnyIsDue) {
  Trigger t({100, 0.5, false, false});
  std::vector<std::int64_t> fired;
  for (std::int64_t s = 1; s <= 300; ++s)
    if (t.is_due(s, 0.01 * double(s))) fired.push_back(s);
  EXPECT_EQ(fired, (std::vector<std::int64_t>{50, 100, 150, 200, 250, 300}));
}

TEST(Trigger, AStepBackwardsRestartsTheSchedule) {
  Trigger t({10, 0, true, false});
  EXPECT_TRUE(t.is_due(0, 0));
  EXPECT_FALSE(t.is_due(5, 0));
  EXPECT_TRUE(t.is_due(10, 0));
  EXPECT_TRUE(t.is_due(3, 0));  // restarted from a checkpoint: "first" again
  EXPECT_FALSE(t.is_due(7, 0));
  EXPECT_TRUE(t.is_due(10, 0));
}

TEST(Schedule, PngImpliesRenderAndDisabledOutputsNeverRun) {
  Config c = load_config_string(R"(
trigger: {every_steps: 10}
outputs:
  png: {trigger: {every_steps: 4}}
  stats: {enabled: false}
  vdb: {enabled: true, trigger: {every_steps: 6}}
)");
  const std::size_t png = c.output_index("png"), vdb = c.output_index("vdb");
  const std::size_t stats_out = c.output_index("stats"), vtk = c.output_index("vtk");
  Schedule s(c);
  int renders = 0, pngs = 0, vdbs = 0, stats = 0, vtks = 0;
  for (std::int64_t step = 1; step <= 24; ++step) {
    StepPlan p = s.plan(step, 0);
    EXPECT_EQ(p.outputs[png], step % 4 == 0) << step;
    EXPECT_EQ(p.render, step % 10 == 0 || step % 4 == 0) << step;
    EXPECT_EQ(p.outputs[vdb], step % 6 == 0) << step;
    renders += p.render, pngs += p.outputs[png], vdbs += p.outputs[vdb];
    stats += p.outputs[stats_out], vtks += p.outputs[vtk];
  }
  EXPECT_EQ(renders, 7);  // 4 8 10 12 16 20 24
  EXPECT_EQ(pngs, 6);
  EXPECT_EQ(vdbs, 4);
  EXPECT_EQ(stats, 0);
  EXPECT_EQ(vtks, 0);
}

TEST(Schedule, NoViewsMeansNoRendering) {
  Config c =
      load_config_string("views: []\noutputs: {vdb: {enabled: true, trigger: {every_steps: 1}}}\n");
  Schedule s(c);
  StepPlan p = s.plan(10, 0);
  EXPECT_FALSE(p.render);
  EXPECT_FALSE(p.outputs[c.output_index("png")]);
  EXPECT_TRUE(p.outputs[c.output_index("vdb")]);
}

TEST(Schedule, NothingDueOnOrdinarySteps) {
  const Config c = default_config();
  Schedule s{c};
  EXPECT_TRUE(s.plan(0, 0).render);  // first
  EXPECT_FALSE(s.plan(1, 0.1).any());
  EXPECT_TRUE(s.plan(10, 1).outputs[c.output_index("png")]);
  EXPECT_TRUE(s.plan(11, 1.1, true).render);  // last
}

}  // namespace
}  // namespace voxspan
