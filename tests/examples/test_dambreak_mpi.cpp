// The dam break as an MPI job (examples/dambreak/decomposition.h), run under mpiexec on any
// number of ranks. First the exchange on hand-made particles: migration into the next slab
// and across several, ghosts within a width (from the neighbours and from farther), a rank
// that owns nothing. Then the solver: on one rank it is the serial solver bit for bit; a small
// dam break keeps every particle on exactly one rank on every step, its ghosts are exact copies
// of their owners, a rank left without fluid takes part, and the surge front matches the
// serial run's at T = 1 and T = 2.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "decomposition.h"
#include "tests/support/mpi_tests.h"

// The dam break's size (the sanitizer build, where the solver runs some ten times slower, asks
// for a smaller one).
#ifndef DAMBREAK_MPI_TEST_PARTICLES
#define DAMBREAK_MPI_TEST_PARTICLES 5000
#endif

namespace dambreak {
namespace {

using Packed = Decomposition::Packed;

using voxspan::test::world_rank;
using voxspan::test::world_size;

// Rank r's slab is [r, r + 1) (rank 0's from -inf, the last rank's to +inf).
std::vector<double> unit_slabs() {
  std::vector<double> b(std::size_t(world_size()) + 1);
  for (std::size_t r = 0; r < b.size(); ++r) b[r] = double(r);
  return b;
}

// A particle whose state is told by its id, so that a copy can be checked exactly.
Packed particle(double x, std::uint32_t id) {
  const float s = float(id);
  return {float(x), s, 2 * s, s + 0.5f, -s, 3 * s, 1000 + s, id};
}

void add(Fluid& f, const Packed& p) {
  const std::size_t i = f.size();
  f.resize(i + 1);
  f.x[i] = p.x, f.y[i] = p.y, f.z[i] = p.z, f.vx[i] = p.vx, f.vy[i] = p.vy, f.vz[i] = p.vz;
  f.rho[i] = p.rho, f.id[i] = p.id;
}

Packed at(const Fluid& f, std::size_t i) {
  return {f.x[i], f.y[i], f.z[i], f.vx[i], f.vy[i], f.vz[i], f.rho[i], f.id[i]};
}

bool same(const Packed& a, const Packed& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.vx == b.vx && a.vy == b.vy && a.vz == b.vz &&
         a.rho == b.rho && a.id == b.id;
}

// The particles [first, first + count) of every rank, on every rank.
std::vector<Packed> gather_all(const Fluid& f, std::size_t first, std::size_t count) {
  std::vector<Packed> mine;
  for (std::size_t i = first; i < first + count; ++i) mine.push_back(at(f, i));
  const int bytes = int(mine.size() * sizeof(Packed));
  std::vector<int> counts(static_cast<std::size_t>(world_size())), offsets(counts.size());
  MPI_Allgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r] = total, total += counts[r];
  std::vector<Packed> all(std::size_t(total) / sizeof(Packed));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  return all;
}

std::set<std::uint32_t> ids(const Fluid& f, std::size_t first, std::size_t end) {
  return {f.id.begin() + std::ptrdiff_t(first), f.id.begin() + std::ptrdiff_t(end)};
}

// x's distance to rank r's slab (0 inside it).
double distance_to_slab(const std::vector<double>& bounds, int r, double x) {
  const double lo = bounds[std::size_t(r)], hi = bounds[std::size_t(r) + 1];
  return x < lo ? lo - x : x >= hi ? x - hi : 0;
}

TEST(Decomposition, OwnerOfFollowsTheBounds) {
  Decomposition d(MPI_COMM_WORLD, 0);
  d.set_bounds(unit_slabs());
  const int last = world_size() - 1;
  EXPECT_EQ(d.owner_of(-1e30), 0);
  EXPECT_EQ(d.owner_of(0.999), 0);
  EXPECT_EQ(d.owner_of(double(last)), last);
  EXPECT_EQ(d.owner_of(1e30), last);
  EXPECT_EQ(d.owner_of(std::numeric_limits<double>::quiet_NaN()), last);
  if (last >= 1) {
    EXPECT_EQ(d.owner_of(1.0), 1);
  }
}

TEST(Decomposition, MigrationTakesEachParticleToTheRankThatOwnsItsX) {
  const int rank = world_rank(), size = world_size();
  const auto r = std::uint32_t(rank);
  Decomposition d(MPI_COMM_WORLD, 0);
  d.set_bounds(unit_slabs());
  // Rank r's particles: one that stays, one that crossed into the next slab (the last rank's
  // stays: its slab reaches +inf), and on rank 0 one that went past every other slab.
  Fluid f;
  add(f, particle(rank + 0.5, 10 * r));
  add(f, particle(rank + 1.2, 10 * r + 1));
  if (rank == 0) add(f, particle(size + 5.0, 99));
  d.migrate(f);

  std::set<std::uint32_t> expected{10 * r};
  if (rank > 0) expected.insert(10 * (r - 1) + 1);
  if (rank == size - 1) expected.insert({10 * r + 1, 99});
  EXPECT_EQ(ids(f, 0, f.size()), expected) << "rank " << rank;
  for (std::size_t i = 0; i < f.size(); ++i) {
    EXPECT_EQ(d.owner_of(f.x[i]), rank);
    EXPECT_TRUE(same(at(f, i), particle(f.x[i], f.id[i]))) << "particle " << f.id[i];
  }
}

TEST(Decomposition, GhostsAreTheOtherRanksParticlesWithinTheWidth) {
  const int rank = world_rank();
  Decomposition d(MPI_COMM_WORLD, 0);
  d.set_bounds(unit_slabs());
  // 0.3 reaches into the neighbours' slabs only, 1.3 past them (with 3 ranks or more).
  for (const double width : {0.3, 1.3}) {
    Fluid f;
    for (std::uint32_t k = 0; k < 8; ++k)
      add(f, particle(rank + k / 8.0, 8 * std::uint32_t(rank) + k));
    const std::vector<Packed> everyone = gather_all(f, 0, f.size());
    d.append_ghosts(f, float(width));

    ASSERT_GE(f.size(), 8u);
    std::set<std::uint32_t> expected;
    for (const Packed& p : everyone)
      if (d.owner_of(p.x) != rank && distance_to_slab(d.bounds(), rank, p.x) < width)
        expected.insert(p.id);
    EXPECT_EQ(ids(f, 8, f.size()), expected) << "rank " << rank << ", width " << width;
    for (std::size_t i = 0; i < f.size(); ++i)
      EXPECT_TRUE(same(at(f, i), particle(f.x[i], f.id[i]))) << "particle " << f.id[i];
  }
}

TEST(Decomposition, ARankThatOwnsNothingStillExchanges) {
  // Rank 0 owns two particles, every other rank none: migration moves nothing, rank 1 gets the
  // particle near its slab as a ghost, the others nothing, and the maximum is rank 0's.
  const int rank = world_rank();
  Decomposition d(MPI_COMM_WORLD, 0);
  d.set_bounds(unit_slabs());
  Fluid f;
  if (rank == 0) add(f, particle(0.25, 1)), add(f, particle(0.75, 2));
  d.migrate(f);
  EXPECT_EQ(f.size(), rank == 0 ? 2u : 0u);
  d.append_ghosts(f, 0.5f);
  std::set<std::uint32_t> expected;
  if (rank == 0) expected = {1, 2};
  if (rank == 1) expected = {2};
  EXPECT_EQ(ids(f, 0, f.size()), expected) << "rank " << rank;
  float m = rank == 0 ? 3.0f : 0.0f;
  d.max_over_ranks({&m, 1});
  EXPECT_EQ(m, 3.0f);
}

TEST(Decomposition, RebalancingCutsAtEqualCounts) {
  // 1000 particles at distinct x, all on rank 0 at first.
  const int rank = world_rank(), size = world_size();
  Decomposition d(MPI_COMM_WORLD, 1);  // every migration re-balances
  Fluid f;
  if (rank == 0)
    for (std::uint32_t i = 0; i < 1000; ++i) add(f, particle(std::sqrt(double(i)), i));
  d.migrate(f);
  const std::uint64_t share = 1000 / std::uint64_t(size);
  EXPECT_NEAR(double(f.size()), double(share), 0.01 * 1000) << "rank " << rank;
  EXPECT_EQ(sum_over_ranks(f.size(), MPI_COMM_WORLD), 1000u);
  EXPECT_TRUE(ids_complete(f, f.size(), 1000, MPI_COMM_WORLD));
}

Config small_config() {
  Config c;
  c.particles = DAMBREAK_MPI_TEST_PARTICLES;
  return c;
}

TEST(DistributedDamBreak, OnOneRankIsTheSerialSolverBitForBit) {
  // Every rank alone (MPI_COMM_SELF): the decomposition's calls change nothing.
  Config c;
  c.particles = 3200;
  c.depth_particles = 4;
  DamBreak serial(c);
  Decomposition alone(MPI_COMM_SELF, 1);
  DamBreak distributed(c, &alone);
  for (int s = 0; s < 60; ++s) serial.step(), distributed.step();
  const Fluid &a = serial.fluid(), &b = distributed.fluid();
  EXPECT_EQ(distributed.owned_count(), b.size());
  EXPECT_EQ(serial.time(), distributed.time());
  EXPECT_EQ(serial.dt(), distributed.dt());
  EXPECT_EQ(a.id, b.id);
  for (auto member : {&Fluid::x, &Fluid::y, &Fluid::z, &Fluid::vx, &Fluid::vy, &Fluid::vz,
                      &Fluid::rho, &Fluid::ax, &Fluid::drho})
    EXPECT_TRUE(a.*member == b.*member);
}

// One distributed run of the small dam break to T = 2, with what the tests below check.
struct DamBreakRun {
  std::size_t count = 0;
  long steps = 0, steps_conserved = 0, steps_ids_complete = 0;
  double front_1 = 0, front_2 = 0;  // x/a on the first steps at T >= 1 and T >= 2
  double support = 0;
  bool ghosts_exact = true, ghosts_complete = true;

  DamBreakRun() {
    Decomposition domain(MPI_COMM_WORLD);
    DamBreak sim(small_config(), &domain);
    count = sum_over_ranks(sim.owned_count(), MPI_COMM_WORLD);
    support = 2 * sim.smoothing_length();
    const double a = sim.config().column_width;
    while (sim.nondimensional_time() < 2) {
      sim.step();
      ++steps;
      steps_conserved += sum_over_ranks(sim.owned_count(), MPI_COMM_WORLD) == count;
      steps_ids_complete += ids_complete(sim.fluid(), sim.owned_count(), count, MPI_COMM_WORLD);
      const double front = combine_over_ranks(sim.diagnostics(), MPI_COMM_WORLD).front / a;
      if (front_1 == 0 && sim.nondimensional_time() >= 1) front_1 = front;
      if (steps % 200 == 0) check_ghosts(sim, domain);
    }
    front_2 = combine_over_ranks(sim.diagnostics(), MPI_COMM_WORLD).front / a;
    check_ghosts(sim, domain);
  }

  // Every ghost is a copy of its owner's particle, and every particle of another rank within
  // two kernel supports of this rank's slab is one.
  void check_ghosts(const DamBreak& sim, const Decomposition& domain) {
    const Fluid& f = sim.fluid();
    const std::size_t owned = sim.owned_count();
    std::map<std::uint32_t, Packed> owners;
    for (const Packed& p : gather_all(f, 0, owned)) owners[p.id] = p;
    std::set<std::uint32_t> ghost_ids;
    for (std::size_t i = owned; i < f.size(); ++i) {
      const auto it = owners.find(f.id[i]);
      ghosts_exact = ghosts_exact && it != owners.end() && same(it->second, at(f, i));
      ghost_ids.insert(f.id[i]);
    }
    for (const auto& [id, p] : owners)
      if (domain.owner_of(p.x) != domain.rank() &&
          distance_to_slab(domain.bounds(), domain.rank(), p.x) < 2 * support)
        ghosts_complete = ghosts_complete && ghost_ids.count(id) == 1;
  }
};

const DamBreakRun& run() {
  static const DamBreakRun r;
  return r;
}

TEST(DistributedDamBreak, EveryParticleIsOwnedByExactlyOneRankOnEveryStep) {
  const DamBreakRun& r = run();
  EXPECT_EQ(r.count, make_lattice(small_config()).fluid_count());
  EXPECT_GT(r.steps, 500);
  EXPECT_EQ(r.steps_conserved, r.steps);
  EXPECT_EQ(r.steps_ids_complete, r.steps);
}

TEST(DistributedDamBreak, GhostsAreExactCopiesOfEveryNearbyParticle) {
  EXPECT_TRUE(run().ghosts_exact);
  EXPECT_TRUE(run().ghosts_complete);
}

TEST(DistributedDamBreak, FrontMatchesTheSerialRunAtOneAndTwoTimeUnits) {
  const DamBreakRun& r = run();
  double serial[2] = {0, 0};
  if (world_rank() == 0) {  // the others wait for its figures
    DamBreak sim(small_config());
    const double a = sim.config().column_width;
    while (sim.nondimensional_time() < 2) {
      sim.step();
      if (serial[0] == 0 && sim.nondimensional_time() >= 1) serial[0] = sim.diagnostics().front / a;
    }
    serial[1] = sim.diagnostics().front / a;
  }
  MPI_Bcast(serial, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  // 2 % is what the distributed run must meet. It meets it by far (about 1e-6): the same
  // neighbours, only summed in another order. Left out of the forces, the ghosts cost 2 to 3 %,
  // so the test holds the runs to 0.5 %.
  EXPECT_NEAR(r.front_1, serial[0], 0.005 * serial[0]);
  EXPECT_NEAR(r.front_2, serial[1], 0.005 * serial[1]);
  if (world_rank() == 0)
    std::printf("front x/a on %d ranks (serial): T = 1 %.6f (%.6f), T = 2 %.6f (%.6f)\n",
                world_size(), r.front_1, serial[0], r.front_2, serial[1]);
}

TEST(DistributedDamBreak, ARankWithoutFluidTakesPart) {
  // Two columns of particles (a thin tank, 16 particles): on three ranks or more, one rank
  // owns nothing.
  Config c;
  c.particles = 16;
  c.depth_particles = 2;
  Decomposition domain(MPI_COMM_WORLD);
  DamBreak sim(c, &domain);
  const std::uint64_t count = sum_over_ranks(sim.owned_count(), MPI_COMM_WORLD);
  const std::uint64_t empty = sum_over_ranks(sim.owned_count() == 0 ? 1 : 0, MPI_COMM_WORLD);
  if (world_size() > 2) {
    EXPECT_GE(empty, 1u);
  }
  for (int s = 0; s < 100; ++s) {
    sim.step();
    ASSERT_EQ(sum_over_ranks(sim.owned_count(), MPI_COMM_WORLD), count);
  }
  const Diagnostics d = combine_over_ranks(sim.diagnostics(), MPI_COMM_WORLD);
  EXPECT_EQ(d.nonfinite, 0u);
  EXPECT_EQ(d.fluid, count);
  EXPECT_TRUE(ids_complete(sim.fluid(), sim.owned_count(), count, MPI_COMM_WORLD));
}

}  // namespace
}  // namespace dambreak

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
