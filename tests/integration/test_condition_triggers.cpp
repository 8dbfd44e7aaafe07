// Triggers on conditions on the dam break, end to end: the render trigger (PNG frames) on the
// maximum speed and the time, once; the stats on the front passing a mark, with a cool-down;
// the VTK snapshots on the particles in a box past the mark. Each output's steps are those its
// condition gives when computed here, by brute force over the solver's own arrays, with the
// rising edge, `once` and the cool-down as docs/runtime.md states them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <set>
#include <sstream>

#include "dambreak_run.h"
#include "output_files.h"
#include "tests/support/temp_folder.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

constexpr std::int64_t kSteps = 40;

// What the conditions read, by brute force.
struct Probe {
  double front = 0;        // max x
  double speed = 0;        // max |velocity|
  std::int64_t ahead = 0;  // particles with x >= the mark
  double time = 0;
};

Probe probe(const dambreak::Fluid& f, double mark) {
  Probe p{-INFINITY, 0, 0, 0};
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double vx = f.vx[i], vy = f.vy[i], vz = f.vz[i];
    p.front = std::max(p.front, double(f.x[i]));
    p.speed = std::max(p.speed, std::sqrt(vx * vx + vy * vy + vz * vz));
    p.ahead += double(f.x[i]) >= mark;
  }
  return p;
}

std::vector<Probe> dry_run(double mark) {
  dambreak::DamBreak sim(test::small_dambreak());
  std::vector<Probe> probes;
  for (std::int64_t s = 1; s <= kSteps; ++s) {
    sim.step();
    probes.push_back(probe(sim.fluid(), mark));
    probes.back().time = sim.time();
  }
  return probes;
}

// The rising edges of `holds` (steps 1..), with a cool-down in steps and `once`.
std::vector<std::int64_t> edges(const std::vector<bool>& holds, std::int64_t cooldown, bool once) {
  std::vector<std::int64_t> fired;
  bool before = false;
  for (std::size_t i = 0; i < holds.size(); ++i) {
    const std::int64_t step = std::int64_t(i) + 1;
    const bool rising = holds[i] && !before;
    before = holds[i];
    if (!rising || (once && !fired.empty())) continue;
    if (!fired.empty() && step < fired.back() + cooldown) continue;
    fired.push_back(step);
  }
  return fired;
}

std::string numbered(const std::string& prefix, std::int64_t step, const std::string& ext) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%08lld", static_cast<long long>(step));
  return prefix + "_" + digits + "." + ext;
}

std::vector<std::int64_t> stats_steps(const std::filesystem::path& file) {
  std::vector<std::int64_t> steps;
  std::smatch m;
  for (const std::string& line : test::read_lines(file))
    if (std::regex_search(line, m, std::regex("\"step\":([0-9]+)")))
      steps.push_back(std::stoll(m[1]));
  return steps;
}

TEST(ConditionTriggers, OutputsWriteOnTheStepsTheirConditionsGiveOnTheDamBreak) {
  // Marks half way through what the dry run's front and speed do, so that each is crossed.
  const dambreak::DamBreak start(test::small_dambreak());
  const double x0 = probe(start.fluid(), 0).front;
  const std::vector<Probe> dry = dry_run(x0);
  const double mark = 0.5 * (x0 + dry.back().front);
  const double speed = 0.5 * dry.back().speed, time_after = dry[kSteps / 4].time;
  ASSERT_GT(dry.back().front, x0) << "the front does not move in " << kSteps << " steps";

  test::TempFolder dir;
  std::ostringstream yaml;
  yaml.precision(17);
  yaml << "output_folder: " << dir.path().string() << "\n"
       << "constants: {mark: " << mark << ", speed: " << speed << ", after: " << time_after << "}\n"
       << "boxes: {ahead: [[" << mark << ", -.inf, -.inf], [.inf, .inf, .inf]]}\n"
       << R"(trigger: {when: "max(velocity) > speed and time > after", once: true}
views: [{name: v, width: 48, height: 32}]
outputs:
  stats: {trigger: {when: max(x) > mark, cooldown_steps: 4}}
  vtk: {enabled: true, trigger: {when: count(ahead) >= 3}, attributes: [velocity]}
writer: {fsync: false}
)";
  dambreak::DamBreak sim(test::small_dambreak());
  Adapter adapter = adapter_from_config_text(yaml.str(), test::solver_options(sim), "run.yaml");
  std::vector<bool> fast, past, three_ahead;
  for (std::int64_t step = 1; step <= kSteps; ++step) {
    sim.step();
    const dambreak::Fluid& f = sim.fluid();
    const Probe p = probe(f, mark);
    fast.push_back(p.speed > speed && sim.time() > time_after);
    past.push_back(p.front > mark);
    three_ahead.push_back(p.ahead >= 3);
    const auto particles = ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size())
                               .with_vector("velocity", f.vx.data(), f.vy.data(), f.vz.data());
    ASSERT_TRUE(adapter.execute(step, sim.time(), particles).ok());
  }
  adapter.finish();

  const std::vector<std::int64_t> renders = edges(fast, 0, true);
  const std::vector<std::int64_t> stats = edges(past, 4, false);
  const std::vector<std::int64_t> snapshots = edges(three_ahead, 0, false);
  ASSERT_EQ(renders.size(), 1u);
  ASSERT_FALSE(stats.empty());
  ASSERT_FALSE(snapshots.empty());
  EXPECT_EQ(test::files_in(dir.path() / "frames"),
            (std::vector<std::string>{numbered("v", renders[0], "png")}));
  EXPECT_EQ(stats_steps(dir.path() / "stats.jsonl"), stats);
  std::vector<std::string> vtp;
  for (std::int64_t s : snapshots) vtp.push_back(numbered("particles", s, "vtp"));
  EXPECT_EQ(test::pvd_files(dir.path() / "vtk" / "particles.pvd"), vtp);
}

// Stats lines on every step, pictures on every other: a line of a step that rendered nothing
// carries its views with every figure 0, not the last render step's figures again (which a
// sum over the file would count twice). A trigger that never fired is said in the summary.
TEST(StatsLines, AStepThatRenderedNothingHasNoViewFigures) {
  test::TempFolder dir;
  const std::string yaml = "output_folder: " + dir.path().string() + R"(
trigger: {every_steps: 2}
views: [{name: v, width: 48, height: 32}]
outputs:
  stats: {trigger: {every_steps: 1}}
  vtk: {enabled: true, trigger: {when: max(x) > 100}}
)";
  dambreak::DamBreak sim(test::small_dambreak());
  Adapter adapter = adapter_from_config_text(yaml, test::solver_options(sim), "run.yaml");
  for (std::int64_t step = 1; step <= 4; ++step) {
    sim.step();
    const dambreak::Fluid& f = sim.fluid();
    ASSERT_TRUE(adapter
                    .execute(step, sim.time(),
                             ParticleView::soa(f.x.data(), f.y.data(), f.z.data(), f.size()))
                    .ok());
  }
  adapter.finish();
  // An output whose trigger never fired is said in the summary, not only by its count of 0.
  EXPECT_NE(adapter.summary().find("outputs.vtk's trigger never fired"), std::string::npos)
      << adapter.summary();
  const std::vector<std::string> lines = test::read_lines(dir.path() / "stats.jsonl");
  ASSERT_EQ(lines.size(), 4u);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string views = lines[i].substr(lines[i].find("\"views\":"));
    const bool figures = std::regex_search(views, std::regex(":[0-9.e+-]*[1-9]"));
    EXPECT_EQ(figures, i % 2 == 1) << lines[i];  // steps 2 and 4 rendered
  }
}

}  // namespace
}  // namespace voxspan
