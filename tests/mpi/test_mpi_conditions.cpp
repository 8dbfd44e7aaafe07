// Triggers on conditions in an MPI job (run under mpiexec on 1 and on 3 ranks): the reductions
// are over every rank's owned particles (ghosts left out, an empty rank taking part), so the
// stats output writes on the steps the conditions give over the whole fluid, computed here by
// brute force, and every rank decides alike (each counts the same steps with work). With 1
// and 3 ranks the same steps therefore fire.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "output_files.h"
#include "tests/support/mpi_tests.h"
#include "voxspan/mpi.h"

namespace voxspan {
namespace {

int rank() { return test::world_rank(); }
int ranks() { return test::world_size(); }

constexpr int kParticles = 4000;  // 20 x 20 x 10, spacing 0.01
constexpr int kGhosts = 50;
constexpr std::int64_t kSteps = 30;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Particle i at step s: the block stretched along x, moving along x, a pressure with holes.
struct Particle {
  double x, y, z, vx, vy, vz, p;
};
Particle particle(int i, std::int64_t s) {
  const double x0 = 0.01 * (i % 20), y = 0.01 * (i / 20 % 20), z = 0.01 * (i / 400);
  const double p = i % 13 == 0 ? kNaN : 1000 * z + double(s);
  return {x0 * (1 + 0.05 * double(s)), y, z, 0.1 * double(s) * x0, 0.01 * (i % 7), 0, p};
}

// This rank's particles: on 3 ranks the even ones on rank 0, the odd ones on rank 1, none on
// rank 2; on every rank ghosts far along x after them, which no reduction may see.
struct Part {
  std::vector<double> x, y, z, v, p;
  std::size_t owned = 0;
  explicit Part(std::int64_t s) {
    for (int i = 0; i < kParticles; ++i)
      if (ranks() == 1 || (rank() < 2 && i % 2 == rank())) add(particle(i, s));
    owned = x.size();
    for (int g = 0; g < kGhosts; ++g) add({10, 0, 0, 100, 0, 0, 1e6});
  }
  void add(const Particle& q) {
    x.push_back(q.x), y.push_back(q.y), z.push_back(q.z), p.push_back(q.p);
    v.insert(v.end(), {q.vx, q.vy, q.vz});
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size())
        .with_owned(owned)
        .with_vector("velocity", v.data())
        .with_scalar("pressure", p.data());
  }
};

// What the conditions read, over the whole fluid (every particle, one process).
struct Whole {
  double max_x = -INFINITY, max_speed = 0, pressure_right = 0, min_z = INFINITY;
  double count_right = 0, pressures_right = 0;
  explicit Whole(std::int64_t s) {
    for (int i = 0; i < kParticles; ++i) {
      const Particle q = particle(i, s);
      max_x = std::max(max_x, q.x);
      max_speed = std::max(max_speed, std::sqrt(q.vx * q.vx + q.vy * q.vy + q.vz * q.vz));
      min_z = std::min(min_z, q.z);
      if (q.x < 0.25) continue;
      count_right += 1;
      if (!std::isnan(q.p)) pressure_right += q.p, pressures_right += 1;
    }
    pressure_right /= pressures_right;
  }
};

struct Case {
  std::string trigger;                                    // the stats output's trigger
  std::function<bool(const Whole&, std::int64_t)> holds;  // the same, by brute force
  std::int64_t cooldown = 0;
  bool once = false;
};

std::vector<std::int64_t> expected_steps(const Case& c) {
  std::vector<std::int64_t> fired;
  bool before = false;
  for (std::int64_t s = 1; s <= kSteps; ++s) {
    const bool now = c.holds(Whole(s), s), rising = now && !before;
    before = now;
    if (!rising || (c.once && !fired.empty())) continue;
    if (!fired.empty() && s < fired.back() + c.cooldown) continue;
    fired.push_back(s);
  }
  return fired;
}

std::vector<std::int64_t> run(const Case& c, const std::filesystem::path& folder) {
  const std::string yaml = "output_folder: " + folder.string() +
                           "\nboxes: {right: [[0.25, -.inf, -.inf], [.inf, .inf, .inf]]}\n"
                           "views: []\noutputs:\n  stats: {trigger: " +
                           c.trigger + "}\nwriter: {fsync: false}\n";
  AdapterOptions o;
  o.classify.particle_spacing = 0.01;
  Adapter adapter = adapter_from_config_text(yaml, o, MPI_COMM_WORLD, "mpi.yaml");
  for (std::int64_t s = 1; s <= kSteps; ++s) {
    const Part part(s);
    EXPECT_TRUE(adapter.execute(s, 0.05 * double(s), part.view()).ok());
  }
  adapter.finish();
  // Every rank did work on the same number of steps: the steps the stats were due.
  EXPECT_EQ(adapter.render_steps(), std::int64_t(expected_steps(c).size())) << "rank " << rank();
  std::vector<std::int64_t> steps;
  std::smatch m;
  for (const std::string& line : test::read_lines(folder / "stats.jsonl"))
    if (std::regex_search(line, m, std::regex("\"step\":([0-9]+)")))
      steps.push_back(std::stoll(m[1]));
  return steps;
}

std::filesystem::path shared_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() /
                      ("voxspan-mpi-conditions-" + std::to_string(ranks()) + "-" + name);
  if (rank() == 0) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return folder;
}

TEST(MpiConditions, OutputsWriteOnTheStepsTheWholeFluidGives) {
  const std::vector<Case> cases = {
      // The front: max x = 0.19 (1 + 0.05 s) passes 0.3 at step 12; a ghost would at step 1.
      {"{when: \"max(x) > 0.3\"}", [](const Whole& w, std::int64_t) { return w.max_x > 0.3; }},
      // Rising and falling: each rise of sin(step), but none within 4 steps of the last.
      {"{when: \"sin(step) > 0 and max(velocity) > 0.05\", cooldown_steps: 4}",
       [](const Whole& w, std::int64_t s) { return std::sin(double(s)) > 0 && w.max_speed > 0.05; },
       4},
      // A box: the mean pressure (NaN left out) and the count past x = 0.25, once.
      {"{when: \"mean(pressure, right) > 50 and count(right) > 800\", once: true}",
       [](const Whole& w, std::int64_t) { return w.pressure_right > 50 && w.count_right > 800; }, 0,
       true},
      // The time and a minimum.
      {"{when: \"time > 0.52 and min(z) <= 0\"}",
       [](const Whole& w, std::int64_t s) { return 0.05 * double(s) > 0.52 && w.min_z <= 0; }}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::vector<std::int64_t> expected = expected_steps(cases[i]);
    ASSERT_FALSE(expected.empty()) << cases[i].trigger;
    const std::vector<std::int64_t> steps = run(cases[i], shared_folder(std::to_string(i)));
    if (rank() == 0) {
      EXPECT_EQ(steps, expected) << cases[i].trigger;
    }
  }
}

}  // namespace
}  // namespace voxspan

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
