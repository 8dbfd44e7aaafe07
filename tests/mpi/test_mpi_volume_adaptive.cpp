// Adaptive sampling of a volume view in an MPI job (run under mpiexec on 3 ranks; the job on its
// first rank alone and on all 3): with relax 0 no channel of the composited picture moves by
// more than the tolerance (1e-6 of slack for rounding) from the job's full-rate picture, each
// rank spending 1 / ranks of it (insitu/views/volume_compositor.cpp), with and without early
// termination and background; the ranks' super-pixels counted so that the check proves
// something. The ranks' own bounds (volume.error_bound) add up to at most the tolerance: each
// spends its share, where the whole tolerance each would let three ranks' errors reach three
// times it on one pixel. Only rank 0 prints.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/mpi_tests.h"
#include "voxspan/mpi.h"

namespace voxspan {
namespace {

using test::first_ranks;
using test::world_rank;

constexpr double kSpacing = 0.05;
constexpr int kSide = 20;

// The particles of `rank` of `ranks`: a lattice block in slabs along x, its value 0.3 in the
// lower half and 0.7 in the upper (flat regions, where super-pixels may be taken).
struct Slab {
  std::vector<double> x, y, z, p;
  Slab(int rank, int ranks) {
    for (int k = 0; k < kSide; ++k)
      for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
          if (i * ranks / kSide != rank) continue;
          x.push_back((i + 0.5) * kSpacing), y.push_back((j + 0.5) * kSpacing);
          z.push_back((k + 0.5) * kSpacing), p.push_back(j < kSide / 2 ? 0.3 : 0.7);
        }
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_scalar("p", p.data());
  }
};

std::string config(const std::string& name, const std::string& keys) {
  return "output_folder: " +
         (std::filesystem::temp_directory_path() / ("voxspan-mpi-volume-adaptive-" + name))
             .string() +
         "\noutputs: {png: {enabled: false}, stats: {enabled: false}}\n"
         "trigger: {every_steps: 1}\nwriter: {fsync: false}\n"
         "views:\n  - {name: v, kind: volume, width: 240, height: 160, quantity: p, legend: false, "
         "caption: '', camera: {direction: [-0.4, -0.5, -1], up: [0, 1, 0]}, " +
         keys + "}\n";
}

struct Frame {
  std::vector<float> rgba;
  std::int64_t super_pixels = 0, skipped = 0;  // this rank's
  double error_bound = 0;                      // this rank's
};

// The view's frame of this rank's slab in a job on `comm`.
Frame render(MPI_Comm comm, const std::string& name, const std::string& keys) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  AdapterOptions options;
  options.classify.particle_spacing = kSpacing;
  Adapter a = adapter_from_config_text(config(name, keys), options, comm);
  const Slab mine(rank, ranks);
  const Status s = a.execute(0, 0, mine.view());
  EXPECT_TRUE(s.ok()) << s.message;
  const ViewResult& r = dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
  Frame f;
  if (r.picture) f.rgba = r.picture->rgba;
  if (r.stats) {
    f.super_pixels = r.stats->count("volume.cells_super_pixel");
    f.skipped = r.stats->count("volume.samples_skipped");
    f.error_bound = r.stats->figure("volume.error_bound");
  }
  a.finish();
  return f;
}

TEST(MpiVolumeAdaptive, NoChannelMovesByMoreThanTheToleranceOn1And3Ranks) {
  std::int64_t super_pixels_on_3 = 0;
  for (int ranks : {1, 3}) {
    MPI_Comm comm = first_ranks(ranks);
    if (comm == MPI_COMM_NULL) continue;
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    for (const char* ending : {"termination: 0, background: sky", "background: none"}) {
      const std::string name = std::to_string(ranks) + (ending[0] == 't' ? "-t0" : "-none");
      const Frame exact = render(comm, name, ending);
      for (double tolerance : {0.001, 0.004, 0.01}) {
        const std::string keys = std::string(ending) +
                                 ", adaptive: {error_tolerance: " + std::to_string(tolerance) + "}";
        const Frame adaptive = render(comm, name + "-" + std::to_string(tolerance), keys);
        std::int64_t counts[2] = {adaptive.super_pixels, adaptive.skipped}, total[2] = {0, 0};
        MPI_Reduce(counts, total, 2, MPI_INT64_T, MPI_SUM, 0, comm);
        double bound = 0;
        MPI_Reduce(&adaptive.error_bound, &bound, 1, MPI_DOUBLE, MPI_SUM, 0, comm);
        if (rank != 0) continue;
        ASSERT_EQ(adaptive.rgba.size(), exact.rgba.size());
        std::size_t over = 0;
        double largest = 0;
        for (std::size_t i = 0; i < exact.rgba.size(); ++i) {
          const double d = std::abs(double(adaptive.rgba[i]) - double(exact.rgba[i]));
          largest = std::max(largest, d);
          over += d > tolerance + 1e-6 ? 1 : 0;
        }
        std::printf(
            "%d rank(s), %-31s tolerance %.3f: largest %.2e, %zu channels over, ranks' bounds "
            "%.2e; %lld super-pixel cells, %lld samples skipped\n",
            ranks, ending, tolerance, largest, over, bound, static_cast<long long>(total[0]),
            static_cast<long long>(total[1]));
        EXPECT_EQ(over, 0u) << ranks << " ranks, " << ending << ", tolerance " << tolerance;
        EXPECT_LE(bound, tolerance) << ranks << " ranks, " << ending << ", tolerance " << tolerance;
        if (ranks == 3) super_pixels_on_3 += total[0];
      }
    }
    MPI_Comm_free(&comm);
  }
  if (world_rank() == 0) {
    EXPECT_GT(super_pixels_on_3, 0);
  }
}

}  // namespace
}  // namespace voxspan

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
