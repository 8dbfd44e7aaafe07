// Triggers on conditions: the expression (reductions, words, constants), its mistakes as the
// config reports them (file:line:col, the names that exist), the rising edge with once and the
// cool-downs, the reductions against brute force (boxes, vectors, NaN values, ghosts, nothing
// to reduce) and the schedule that joins them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "insitu/config/condition.h"
#include "insitu/config/trigger.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/particle_reductions.h"
#include "insitu/runtime/schedule.h"
#include "tests/support/error_message.h"
#include "tests/support/log_capture.h"

namespace voxspan {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const std::map<std::string, ConditionBox> kBoxes = {
    {"right", {{0.5, -kInf, -kInf}, {kInf, kInf, kInf}}}};

std::string error_of(const std::string& yaml) {
  return test::error_message([&] { load_config_string(yaml, "test.yaml"); });
}

// ---- the expression

TEST(Condition, NamesEachReductionOnceAndReadsTheWords) {
  Condition c(
      "max(velocity) > 2.5 and time > 0.3 or not (count(right) < tank * 2) or "
      "max(velocity) < min(x, right) ",
      {{"tank", 1.5}}, kBoxes);
  const std::vector<Reduction> expected = {{ReductionOp::max, "velocity", ""},
                                           {ReductionOp::count, "", "right"},
                                           {ReductionOp::min, "x", "right"}};
  ASSERT_EQ(std::vector<Reduction>(c.reductions().begin(), c.reductions().end()), expected);
  EXPECT_EQ(c.reductions()[1].text(), "count(right)");
  auto holds = [&](double vmax, double count, double xmin, double time) {
    c.inputs()[0] = vmax, c.inputs()[1] = count, c.inputs()[2] = xmin;
    return c.holds(7, time);
  };
  EXPECT_TRUE(holds(3, 0, 0, 0.5));   // the first clause
  EXPECT_FALSE(holds(3, 0, 0, 0.2));  // ... not yet in time
  EXPECT_TRUE(holds(1, 3, 0, 0.2));   // not (3 < 3)
  EXPECT_FALSE(holds(1, 2, 0, 0.2));
  EXPECT_TRUE(holds(1, 2, 1.5, 0.2));     // the last clause
  EXPECT_FALSE(holds(kNaN, 2, kNaN, 1));  // NaN compares false
}

TEST(Condition, SeesTheStepAndMuparsersFunctions) {
  Condition c("step >= 10 && abs(sum(pressure)) > sqrt(16) ? 1 : 0", {}, {});
  c.inputs()[0] = -5;
  EXPECT_TRUE(c.holds(10, 0));
  EXPECT_FALSE(c.holds(9, 0));
  c.inputs()[0] = 3;
  EXPECT_FALSE(c.holds(10, 0));
  // A value that is NaN is false, and so is 0.
  Condition nan("mean(p)", {}, {});
  nan.inputs()[0] = kNaN;
  EXPECT_FALSE(nan.holds(0, 0));
  nan.inputs()[0] = 0;
  EXPECT_FALSE(nan.holds(0, 0));
}

TEST(Condition, MistakesSayWhatAndWhere) {
  auto error = [](const std::string& text) -> std::pair<std::string, std::size_t> {
    try {
      Condition c(text, {{"tank_length", 1.6}}, kBoxes);
    } catch (const ConditionError& e) {
      return {e.what(), e.position};
    }
    return {"", 0};
  };
  auto [m, at] = error("max(x) > 0.8 * tank_lenght");
  EXPECT_EQ(at, 15u);
  EXPECT_NE(m.find("unknown name \"tank_lenght\" (did you mean \"tank_length\"? names: time, "
                   "step, tank_length"),
            std::string::npos)
      << m;
  std::tie(m, at) = error("max(velocity) >> 2");
  EXPECT_EQ(m, "unexpected operator \">\"");
  EXPECT_EQ(at, 15u);
  std::tie(m, at) = error("maxx(velocity) > 2");
  EXPECT_EQ(at, 0u);
  EXPECT_NE(m.find("unknown function \"maxx\""), std::string::npos) << m;
  EXPECT_NE(m.find("reductions: min(a), max(a)"), std::string::npos) << m;
  std::tie(m, at) = error("max(velocity, left) > 2");
  EXPECT_EQ(at, 14u);
  EXPECT_NE(m.find("unknown box \"left\" (boxes: right)"), std::string::npos) << m;
  std::tie(m, at) = error("mean(right) > 2");  // a box where the attribute goes
  EXPECT_EQ(at, 5u);
  EXPECT_EQ(m, "\"right\" is a box, not an attribute: mean(attribute) or mean(attribute, box)");
  std::tie(m, at) = error("max(2 * velocity) > 2");
  EXPECT_NE(m.find("expected max(attribute) or max(attribute, box)"), std::string::npos) << m;
  std::tie(m, at) = error("count(x) > 2");  // count takes a box only
  EXPECT_NE(m.find("unknown box \"x\""), std::string::npos) << m;
  std::tie(m, at) = error("time = 2");
  EXPECT_EQ(at, 5u);
  EXPECT_NE(m.find("write \"==\""), std::string::npos) << m;
  std::tie(m, at) = error("(max(x) > 1");
  EXPECT_NE(m.find("parenthes"), std::string::npos) << m;
  EXPECT_EQ(error("max(x) > 1 and (time >= 0.5 or step == 3)").first, "");
}

// ---- the config

TEST(ConditionConfig, ReadsWhenOnceCooldownsConstantsAndBoxes) {
  const Config c = load_config_string(R"(
constants: {tank_length: 1.6, v_max: 2.5}
boxes: {outlet: [[1.2, -.inf, 0], [1.6, .inf, 0.3]]}
trigger: {every_steps: 50, when: "max(x) > 0.8 * tank_length", once: true}
outputs:
  vtk: {enabled: true, trigger: {when: "max(velocity, outlet) > v_max", cooldown_steps: 20, cooldown_time: 0.1}}
)",
                                      "test.yaml");
  EXPECT_EQ(c.trigger.when, "max(x) > 0.8 * tank_length");
  EXPECT_TRUE(c.trigger.once);
  EXPECT_EQ(c.trigger.every_steps, 50);
  EXPECT_EQ(c.constants.at("v_max"), 2.5);
  EXPECT_EQ(c.boxes.at("outlet"), (ConditionBox{{1.2, -kInf, 0}, {1.6, kInf, 0.3}}));
  const TriggerSpec& vtk = c.output("vtk").trigger;
  EXPECT_EQ(vtk.when, "max(velocity, outlet) > v_max");
  EXPECT_EQ(vtk.cooldown_steps, 20);
  EXPECT_EQ(vtk.cooldown_time, 0.1);
  EXPECT_EQ(vtk.source.where, "test.yaml:6:40: outputs.vtk.trigger.when");
  // Written and read again: the same config.
  EXPECT_EQ(load_config_string(to_yaml(c), "again.yaml"), c);
}

TEST(ConditionConfig, MistakesAreStartUpErrorsAtTheirCharacter) {
  // Plain and quoted: the column is the offending character's.
  EXPECT_NE(error_of("trigger: {when: max(x) > tank}\n")
                .find("test.yaml:1:26: trigger.when: unknown name \"tank\""),
            std::string::npos);
  EXPECT_NE(error_of("constants: {tank: 1}\noutputs:\n  stats:\n    trigger:\n"
                     "      when: \"max(velocty) >> 1\"\n")
                .find("test.yaml:5:28: outputs.stats.trigger.when: unexpected operator \">\" in "
                      "\"max(velocty) >> 1\""),
            std::string::npos);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"trigger: {every_steps: 5, once: true}\n",
       "test.yaml:1:33: trigger.once: is for a condition: set `when` or remove it"},
      {"trigger: {when: \"\"}\n", "trigger.when: must not be empty"},
      {"constants: {time: 3}\n", "constants.time: is a name the conditions have already"},
      {"constants: {2pi: 6.28}\n", "constants.2pi: must be a letter"},
      {"constants: {g: fast}\n", "constants.g: expected a finite number; got \"fast\""},
      {"boxes: {a: [[0, 0, 0], [1, 0, 1]]}\n", "boxes.a: expected [[x0, y0, z0], [x1, y1, z1]]"},
      {"trigger: {when: count(inlet) > 3}\n",
       "trigger.when: unknown box \"inlet\" (the config names none in `boxes`)"},
      {"boxes: {outlet: [[0, 0, 0], [1, 1, 1]]}\ntrigger: {when: max(velocity, outlet) > 1}\n",
       "(in a {...} map, quote an expression that has commas)"},
      {"trigger: {every_steps: 0, first: false, last: false}\n",
       "never fires: set every_steps, every_time, first, last or when"}};
  for (const auto& [yaml, expected] : cases)
    EXPECT_NE(error_of(yaml).find(expected), std::string::npos) << yaml << error_of(yaml);
}

// ---- the edge

// The steps where a condition that holds on `holding` steps fires, checked on steps 1..20.
std::vector<std::int64_t> fired(TriggerSpec spec, const std::set<std::int64_t>& holding,
                                double dt = 0.1) {
  spec.when = "1";
  Trigger t(spec);
  std::vector<std::int64_t> steps;
  for (std::int64_t s = 1; s <= 20; ++s) {
    t.is_due(s, dt * double(s));
    if (t.checks_condition() && t.condition_fires(s, dt * double(s), holding.count(s) > 0))
      steps.push_back(s);
  }
  return steps;
}

TEST(ConditionTrigger, FiresOnTheRisingEdgeOnly) {
  EXPECT_EQ(fired({}, {3, 4, 5, 9, 12, 13}), (std::vector<std::int64_t>{3, 9, 12}));
  // True from the first check: that is a rising edge.
  EXPECT_EQ(fired({}, {1, 2, 3}), (std::vector<std::int64_t>{1}));
  EXPECT_TRUE(fired({}, {}).empty());
}

TEST(ConditionTrigger, OnceFiresTheFirstTimeAndThenIsNotChecked) {
  TriggerSpec spec;
  spec.when = "1";
  spec.once = true;
  Trigger t(spec);
  EXPECT_TRUE(t.checks_condition());
  EXPECT_FALSE(t.condition_fires(1, 0, false));
  EXPECT_TRUE(t.condition_fires(2, 0, true));
  EXPECT_FALSE(t.checks_condition());
  EXPECT_EQ(fired(spec, {3, 9, 12}), (std::vector<std::int64_t>{3}));
}

TEST(ConditionTrigger, CooldownsLoseTheEdgesInsideThem) {
  TriggerSpec steps;
  steps.cooldown_steps = 5;
  // 3 fires; 6 rises inside 3..7 and is lost; 8 is held since 6: no edge; 11 rises again.
  EXPECT_EQ(fired(steps, {3, 6, 7, 8, 11}), (std::vector<std::int64_t>{3, 11}));
  EXPECT_EQ(fired(steps, {3, 5, 8}), (std::vector<std::int64_t>{3, 8}));
  TriggerSpec time;
  time.cooldown_time = 0.5;  // 5 steps of 0.1: step 8 is at 0.8 = 0.3 + 0.5, up to rounding
  EXPECT_EQ(fired(time, {3, 5, 8}), (std::vector<std::int64_t>{3, 8}));
  EXPECT_EQ(fired(time, {3, 5, 7}), (std::vector<std::int64_t>{3}));
}

TEST(ConditionTrigger, ARestartForgetsTheEdgeAndOnce) {
  TriggerSpec spec;
  spec.when = "1";
  spec.once = true;
  Trigger t(spec);
  t.is_due(10, 1);
  EXPECT_TRUE(t.condition_fires(10, 1, true));
  t.is_due(5, 0.5);  // back to an earlier checkpoint
  EXPECT_TRUE(t.checks_condition());
  EXPECT_TRUE(t.condition_fires(5, 0.5, true));
}

// ---- the reductions

struct Particles {
  std::vector<double> x, y, z;
  std::vector<float> p, v;  // pressure; velocity, xyz interleaved
  std::size_t owned = 0;

  explicit Particles(std::size_t n, unsigned seed = 3) : owned(n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::size_t i = 0; i < n; ++i) {
      x.push_back(u(rng)), y.push_back(u(rng)), z.push_back(u(rng));
      p.push_back(float(1000 * u(rng)));
      for (int a = 0; a < 3; ++a) v.push_back(float(u(rng) - 0.5));
    }
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size())
        .with_owned(owned)
        .with_scalar("pressure", p.data())
        .with_vector("velocity", v.data());
  }
};

// Every reduction of every pair, by brute force over the owned particles.
double brute(const Particles& ps, const Reduction& r) {
  double lo = kInf, hi = -kInf, sum = 0, n = 0;
  for (std::size_t i = 0; i < ps.owned; ++i) {
    if (!r.box.empty() && !(ps.x[i] >= 0.5)) continue;
    double value = 1;
    if (r.attribute == "x") value = ps.x[i];
    if (r.attribute == "pressure") value = ps.p[i];
    if (r.attribute == "velocity") {
      const double a = ps.v[3 * i], b = ps.v[3 * i + 1], c = ps.v[3 * i + 2];
      value = std::sqrt(a * a + b * b + c * c);
    }
    if (std::isnan(value)) continue;
    lo = std::min(lo, value), hi = std::max(hi, value), sum += value, n += 1;
  }
  switch (r.op) {
    case ReductionOp::min: return lo;
    case ReductionOp::max: return hi;
    case ReductionOp::sum: return sum;
    case ReductionOp::mean: return n > 0 ? sum / n : kNaN;
    case ReductionOp::count: return n;
  }
  return kNaN;
}

std::vector<Reduction> every_reduction() {
  std::vector<Reduction> all;
  for (const auto& [name, op] : {std::pair{"min", ReductionOp::min},
                                 {"max", ReductionOp::max},
                                 {"sum", ReductionOp::sum},
                                 {"mean", ReductionOp::mean}})
    for (const char* a : {"x", "pressure", "velocity"})
      for (const char* box : {"", "right"}) all.push_back({op, a, box});
  all.push_back({ReductionOp::count, "", ""});
  all.push_back({ReductionOp::count, "", "right"});
  return all;
}

void expect_brute(const Particles& ps) {
  const std::vector<Reduction> all = every_reduction();
  ParticleReductions reductions(all, kBoxes, nullptr);
  const std::vector<char> wanted(all.size(), 1);
  reductions.run(ps.view(), wanted);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const double expected = brute(ps, all[i]), got = reductions.value(i);
    if (std::isnan(expected)) EXPECT_TRUE(std::isnan(got)) << all[i].text();
    else if (std::isinf(expected)) EXPECT_EQ(got, expected) << all[i].text();
    else EXPECT_NEAR(got, expected, 1e-9 * std::max(1.0, std::abs(expected))) << all[i].text();
    EXPECT_FALSE(reductions.missing(i));
  }
}

TEST(ParticleReductions, EqualBruteForceOverOwnedParticlesAndBoxes) {
  Particles ps(100000);  // several tasks of the parallel pass
  ps.owned = 99000;      // the rest are ghosts: left out
  expect_brute(ps);
  // Exact for min, max and count, whatever the split.
  const std::vector<Reduction> all = every_reduction();
  ParticleReductions reductions(all, kBoxes, nullptr);
  reductions.run(ps.view(), std::vector<char>(all.size(), 1));
  EXPECT_EQ(reductions.value(all.size() - 2), 99000);
  EXPECT_EQ(reductions.value(1), brute(ps, all[1]));
}

TEST(ParticleReductions, NaNValuesAreLeftOutAndNaNPositionsAreInNoBox) {
  Particles ps(1000);
  for (std::size_t i = 0; i < 1000; i += 7) ps.p[i] = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 3; i < 1000; i += 11) ps.x[i] = kNaN;
  expect_brute(ps);
  // Every value NaN: no value, as for no particle.
  for (float& v : ps.p) v = std::numeric_limits<float>::quiet_NaN();
  expect_brute(ps);
}

TEST(ParticleReductions, NothingToReduceGivesTheIdentitiesAndAMeanOfNaN) {
  const Particles none(0);
  const std::vector<Reduction> all = {{ReductionOp::min, "pressure", ""},
                                      {ReductionOp::max, "velocity", ""},
                                      {ReductionOp::sum, "x", ""},
                                      {ReductionOp::mean, "x", ""},
                                      {ReductionOp::count, "", "right"}};
  ParticleReductions reductions(all, kBoxes, nullptr);
  reductions.run(none.view(), std::vector<char>(all.size(), 1));
  EXPECT_EQ(reductions.value(0), kInf);
  EXPECT_EQ(reductions.value(1), -kInf);
  EXPECT_EQ(reductions.value(2), 0);
  EXPECT_TRUE(std::isnan(reductions.value(3)));
  EXPECT_EQ(reductions.value(4), 0);
  // A default view (no arrays at all) too.
  reductions.run(ParticleView(), std::vector<char>(all.size(), 1));
  EXPECT_EQ(reductions.value(4), 0);
  EXPECT_TRUE(reductions.missing(0));  // no attribute of that name: missing, NaN
  EXPECT_TRUE(std::isnan(reductions.value(0)));
}

TEST(ParticleReductions, OnlyTheWantedAreComputedAndAMissingAttributeIsSaid) {
  const Particles ps(100);
  const std::vector<Reduction> all = {{ReductionOp::max, "pressure", ""},
                                      {ReductionOp::max, "density", ""}};
  ParticleReductions reductions(all, {}, nullptr);
  reductions.run(ps.view(), std::vector<char>{0, 1});
  EXPECT_TRUE(std::isnan(reductions.value(0)));
  EXPECT_TRUE(reductions.missing(1));
  reductions.run(ps.view(), std::vector<char>{1, 0});
  EXPECT_EQ(reductions.value(0), brute(ps, all[0]));
  EXPECT_FALSE(reductions.missing(1));
}

// ---- the schedule

Config config_of(const std::string& yaml) { return load_config_string(yaml, "run.yaml"); }

TEST(ConditionSchedule, PlansWaitForTheParticlesAndTheEdgeFiresTheOutput) {
  Config c = config_of(R"(
trigger: {every_steps: 4}
outputs:
  stats: {trigger: {when: max(x) > 0.5}}
)");
  Schedule schedule(c);
  const std::size_t stats = c.output_index("stats");
  std::vector<double> x = {0.1, 0.2}, yz = {0, 0};
  auto step = [&](std::int64_t s, double front) {
    x[1] = front;
    StepPlan p = schedule.blank();
    schedule.plan(s, 0.1 * double(s), false, p);
    EXPECT_TRUE(p.conditions);
    schedule.decide(s, 0.1 * double(s), ParticleView::soa(x.data(), yz.data(), yz.data(), 2), p);
    EXPECT_FALSE(p.conditions);
    return std::pair<bool, bool>{p.render, p.outputs[stats]};
  };
  EXPECT_EQ(step(1, 0.3), (std::pair{false, false}));
  EXPECT_EQ(step(2, 0.6), (std::pair{false, true}));  // stats needs no render
  EXPECT_EQ(step(3, 0.7), (std::pair{false, false}));
  EXPECT_EQ(step(4, 0.7), (std::pair{true, false}));  // the render trigger's own step
  EXPECT_EQ(step(5, 0.4), (std::pair{false, false}));
  EXPECT_EQ(step(6, 0.9), (std::pair{false, true}));
}

TEST(ConditionSchedule, AMissingAttributeIsSaidOnceAndTheConditionIsFalse) {
  Config c = config_of("trigger: {when: max(velocty) > 1}\n");
  Schedule schedule(c);
  Particles ps(10);
  test::LogCapture log;
  for (std::int64_t s = 1; s <= 3; ++s) {
    StepPlan p = schedule.blank();
    schedule.plan(s, 0, false, p);
    schedule.decide(s, 0, ps.view(), p);
    EXPECT_FALSE(p.render);
  }
  const std::vector<std::string> errors = log.at(LogLevel::error);
  ASSERT_EQ(errors.size(), 1u) << log.all();
  EXPECT_NE(
      errors[0].find("run.yaml:1:17: trigger.when \"velocty\": the solver passes no "
                     "attribute of that name (did you mean \"velocity\"? it passes: pressure, "
                     "velocity)"),
      std::string::npos)
      << errors[0];
}

TEST(ConditionSchedule, ACondtionMadeInCodeIsCheckedWhenTheScheduleIsMade) {
  Config c = default_config();
  c.trigger.when = "max(x) >";
  EXPECT_NE(test::error_message([&] {
              Schedule s(c);
            }).find("trigger.when \"max(x) >\": unexpected end of expression (at character 9)"),
            std::string::npos);
}

}  // namespace
}  // namespace voxspan
