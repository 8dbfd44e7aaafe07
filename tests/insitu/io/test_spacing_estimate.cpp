// The spacing a particle file does not give: a lattice's exactly, sparse sets by a full search.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "insitu/io/spacing_estimate.h"

namespace voxspan {
namespace {

using Point = std::array<double, 3>;

TEST(SpacingEstimate, ALatticeGivesItsSpacing) {
  std::vector<Point> lattice;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) lattice.push_back({0.02 * i, 0.02 * j, 5 + 0.02 * k});
  EXPECT_NEAR(estimate_particle_spacing(lattice), 0.02, 1e-12);
}

TEST(SpacingEstimate, TwoParticlesGiveTheirDistance) {
  const std::vector<Point> two{{0, 0, 0}, {3, 4, 0}};
  EXPECT_DOUBLE_EQ(estimate_particle_spacing(two), 5.0);
}

TEST(SpacingEstimate, ASparseLineGivesItsStep) {
  // Ten points 1 apart and one 1000 away: every sample of the line has its neighbour at 1.
  std::vector<Point> line;
  for (int i = 0; i < 10; ++i) line.push_back({double(i), 0, 0});
  line.push_back({1000, 0, 0});
  EXPECT_DOUBLE_EQ(estimate_particle_spacing(line), 1.0);
}

TEST(SpacingEstimate, FewerThanTwoFinitePositionsGiveZero) {
  const double nan = std::nan("");
  EXPECT_EQ(estimate_particle_spacing(std::vector<Point>{{1, 2, 3}}), 0.0);
  EXPECT_EQ(estimate_particle_spacing(std::vector<Point>{{1, 2, 3}, {nan, 0, 0}}), 0.0);
  EXPECT_EQ(estimate_particle_spacing(std::vector<Point>{{1, 2, 3}, {1, 2, 3}}), 0.0);
}

}  // namespace
}  // namespace voxspan
