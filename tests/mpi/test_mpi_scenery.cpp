// The solver's scenery in an MPI job (run under mpiexec on 3 ranks): the tank's walls given in
// parts by two ranks and none by the third, the water interleaved over all three, make the
// same pictures as one process given everything (up to rounding), in every shading, in a
// particles view and in a volume view; walls given again later (moved) are drawn anew on every
// rank's frame. Only rank 0 checks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/image_difference.h"
#include "tests/support/mpi_tests.h"
#include "tests/support/tank.h"
#include "tests/support/view_tests.h"
#include "voxspan/mpi.h"

namespace voxspan {
namespace {

using test::world_rank;
using test::world_size;

constexpr double kSpacing = 0.05;
// Without early termination a volume frame over ranks is one process's up to rounding.
constexpr const char* kVolume = "kind: volume, legend: false, termination: 0";

std::string config(const std::string& name, const std::string& keys) {
  return test::one_view_config("mpi-scenery-" + name,
                               "name: v, caption: '', width: 80, height: 48, " + keys);
}

// Every `ranks`-th particle of the block's from `rank` on.
struct Share {
  std::vector<double> xyz, height;
  Share(const test::ParticleBlock& b, int rank, int ranks) {
    for (std::size_t i = std::size_t(rank); i < b.values.size(); i += std::size_t(ranks)) {
      xyz.insert(xyz.end(), b.xyz.begin() + std::ptrdiff_t(3 * i),
                 b.xyz.begin() + std::ptrdiff_t(3 * i + 3));
      height.push_back(b.values[i]);
    }
  }
  ParticleView view() const {
    return ParticleView::aos(xyz.data(), height.size()).with_scalar("height", height.data());
  }
};

std::vector<float> picture_of(const Adapter& a) {
  const ViewResult& r = test::latest_view(a);
  return r.picture != nullptr ? r.picture->rgba : std::vector<float>{};
}

TEST(MpiScenery, WallsGivenInPartsMakeOneProcesssPicture) {
  const test::ParticleBlock water(kSpacing, "height", [](int, double x) { return x; });
  const test::Tank tank(kSpacing);
  const std::pair<const char*, const char*> views[] = {{"opaque", "shading: opaque"},
                                                       {"translucent", "shading: translucent"},
                                                       {"refractive", "shading: refractive"},
                                                       {"particles", "kind: particles"},
                                                       {"volume", kVolume}};
  for (const auto& [shading, keys] : views) {
    std::vector<float> one;
    if (world_rank() == 0) {
      Adapter a = adapter_from_config_text(config(std::string("one-") + shading, keys),
                                           test::spaced(kSpacing));
      a.set_scenery(tank.view());
      EXPECT_TRUE(a.execute(0, 0, water.view()).ok());
      one = picture_of(a);
    }
    AdapterOptions options = test::spaced(kSpacing);
    options = with_communicator(std::move(options), MPI_COMM_WORLD);
    Adapter a = adapter_from_config_text(config(shading, keys), options);
    // Ranks 0 and 1 hold a part of the walls each (rank 0 the smaller), the others none.
    const std::size_t third = tank.size() / 3;
    if (world_rank() == 0) a.set_scenery(tank.view(0, third));
    if (world_rank() == 1) a.set_scenery(tank.view(third));
    const Share mine(water, world_rank(), world_size());
    const Status s = a.execute(0, 0, mine.view());
    EXPECT_TRUE(s.ok()) << s.message;
    if (world_rank() != 0) continue;
    const double d = test::largest_difference(picture_of(a), one);
    std::printf("%s on %d ranks: largest channel difference %.1e\n", shading, world_size(), d);
    EXPECT_LT(d, 1e-5) << shading;
  }
}

TEST(MpiScenery, WallsGivenAgainAreDrawnAnew) {
  const test::ParticleBlock water(kSpacing, "height", [](int, double x) { return x; });
  const test::Tank tank(kSpacing);
  for (const char* keys : {"shading: opaque", kVolume}) {
    AdapterOptions options = with_communicator(test::spaced(kSpacing), MPI_COMM_WORLD);
    const std::string name = keys == kVolume ? "again-volume" : "again";
    Adapter a = adapter_from_config_text(config(name, keys), options);
    const Share mine(water, world_rank(), world_size());
    if (world_rank() == 1) a.set_scenery(tank.view());
    ASSERT_TRUE(a.execute(0, 0, mine.view()).ok());
    const std::vector<float> first = picture_of(a);
    // Only the last rank gives new walls (half of them): every rank gathers them again.
    if (world_rank() == 1) a.set_scenery(tank.view(0, 0));
    if (world_rank() == world_size() - 1) a.set_scenery(tank.view(0, tank.size() / 2));
    ASSERT_TRUE(a.execute(1, 0, mine.view()).ok());
    if (world_rank() == 0) {
      EXPECT_GT(test::largest_difference(picture_of(a), first), 0.05) << keys;
    }
  }
}

}  // namespace
}  // namespace voxspan
int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
