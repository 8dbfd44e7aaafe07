// Volume views in an MPI job (run under mpiexec on 4 ranks, the tests on the first 2, 3 and 4):
// the picture of every split (slabs, interleaved, uneven with an empty rank) in every mode equal
// to one process's up to rounding (1e-5 per linear channel; the iso hits' depths too), within
// the termination with early termination on; the job's deep EXR image flattens into one
// process's picture; a rank that fails fails the step on all, naming it, and the next step
// renders. Prints the bytes each rank sent. Only rank 0 prints.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/deep_exr_reader.h"
#include "voxspan/error.h"
#include "tests/support/mpi_tests.h"
#include "voxspan/mpi.h"
#include "tests/support/image_difference.h"

namespace voxspan {
namespace {

using test::first_ranks;
using test::world_rank;
using test::world_size;

constexpr double kSpacing = 0.05;

// A jittered block of 12^3 particles with a field varying in space, the same on every rank.
struct Cloud {
  std::vector<double> x, y, z, p;
  std::vector<int> slab, index;  // per particle: its slab along x (of 12 columns), its number
  Cloud() {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int k = 0; k < 12; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          const double px = (i + jitter(rng)) * kSpacing, py = (j + jitter(rng)) * kSpacing,
                       pz = (k + jitter(rng)) * kSpacing;
          x.push_back(px), y.push_back(py), z.push_back(pz);
          p.push_back(std::sin(3 * px / (12 * kSpacing) * 3) + py * py * 50 + 10 * pz);
          slab.push_back(i);
          index.push_back(int(index.size()));
        }
  }
};

// The particles of `rank` of `ranks` under `split`: slabs along x, interleaved, or uneven (the
// first rank 70 %, the last none).
struct Share {
  std::vector<double> x, y, z, p;
  Share(const Cloud& c, const std::string& split, int rank, int ranks) {
    const int n = int(c.x.size());
    for (int i = 0; i < n; ++i) {
      int owner = 0;
      if (split == "slabs") owner = c.slab[std::size_t(i)] * ranks / 12;
      else if (split == "interleaved") owner = i % ranks;
      else owner = i < n * 7 / 10 ? 0 : 1 + (i - n * 7 / 10) * (ranks - 2) / (n - n * 7 / 10);
      if (owner != rank) continue;
      x.push_back(c.x[std::size_t(i)]), y.push_back(c.y[std::size_t(i)]);
      z.push_back(c.z[std::size_t(i)]), p.push_back(c.p[std::size_t(i)]);
    }
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_scalar("p", p.data());
  }
};

std::string config(const std::string& name, const std::string& keys,
                   const std::string& output = "depth: {enabled: true, folder: depth}") {
  return "output_folder: " +
         (std::filesystem::temp_directory_path() / ("voxspan-mpi-volume-" + name)).string() +
         "\noutputs: {png: {enabled: false}, stats: {enabled: false}, " + output +
         "}\n"
         "trigger: {every_steps: 1}\nwriter: {fsync: false}\n"
         "views:\n  - {name: v, kind: volume, width: 72, height: 54, quantity: p, legend: false, "
         "caption: '',"
         " camera: {direction: [0.3, -1, -0.6], up: [0, 0, 1]}, " +
         keys + "}\n";
}

AdapterOptions options() {
  AdapterOptions o;
  o.classify.particle_spacing = kSpacing;
  return o;
}

const ViewResult& latest(const Adapter& a) {
  return dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
}

struct Frame {
  std::vector<float> rgba, depth;
  std::int64_t bytes_sent = 0;
};

Frame frame_of(const Adapter& a) {
  const ViewResult& r = latest(a);
  Frame f;
  if (r.picture) f.rgba = r.picture->rgba;
  if (r.first_hit_depth)
    for (std::size_t k = 0; k < r.first_hit_depth->rgba.size(); k += 4)
      f.depth.push_back(r.first_hit_depth->rgba[k]);
  if (r.stats) f.bytes_sent = r.stats->count("composite.bytes_sent");
  return f;
}

// One process's frame of the whole cloud, on rank 0 (empty elsewhere).
Frame one_process(const Cloud& cloud, const std::string& name, const std::string& keys) {
  if (world_rank() != 0) return {};
  const Share all(cloud, "slabs", 0, 1);
  Adapter a = adapter_from_config_text(config(name, keys), options());
  EXPECT_TRUE(a.execute(0, 0, all.view()).ok());
  return frame_of(a);
}

using test::largest_difference;

const char* const kModes[][2] = {
    {"dvr", "mode: dvr, termination: 0"},
    {"iso",
     "mode: iso, iso: [{value: 4}, {value: 7, color: [0.9, 0.4, 0.2], opacity: 0.6}],"
     " termination: 0"},
    {"mixed", "mode: mixed, iso: [{value: 6, opacity: 0.5}], termination: 0"}};

TEST(MpiVolume, EverySplitGivesOneProcesssPicture) {
  const Cloud cloud;
  for (const auto& [mode, keys] : kModes) {
    const Frame one = one_process(cloud, std::string("one-") + mode, keys);
    for (int ranks : {2, 3, 4})
      for (const char* split : {"slabs", "interleaved", "uneven"}) {
        MPI_Comm comm = first_ranks(ranks);
        if (comm == MPI_COMM_NULL) continue;
        int rank = 0;
        MPI_Comm_rank(comm, &rank);
        const Share mine(cloud, split, rank, ranks);
        Adapter a = adapter_from_config_text(
            config(std::string(mode) + "-" + split + std::to_string(ranks), keys), options(), comm);
        const Status s = a.execute(0, 0, mine.view());
        EXPECT_TRUE(s.ok()) << s.message;
        const Frame f = frame_of(a);
        std::vector<std::int64_t> bytes(static_cast<std::size_t>(ranks), 0);
        MPI_Gather(&f.bytes_sent, 1, MPI_INT64_T, bytes.data(), 1, MPI_INT64_T, 0, comm);
        a.finish();
        MPI_Comm_free(&comm);
        if (rank != 0) continue;
        const double d = largest_difference(f.rgba, one.rgba);
        std::printf("%-5s %-11s %d ranks: largest channel difference %.1e; bytes sent per rank:",
                    mode, split, ranks, d);
        for (std::int64_t b : bytes) std::printf(" %lld", static_cast<long long>(b));
        std::printf("\n");
        EXPECT_LT(d, 1e-5) << mode << " " << split << " " << ranks;
        if (std::string(mode) != "iso") continue;
        EXPECT_EQ(f.depth.size(), one.depth.size());
        for (std::size_t i = 0; i < std::min(f.depth.size(), one.depth.size()); ++i)
          EXPECT_NEAR(f.depth[i], one.depth[i], 1e-5 * one.depth[i] + 1e-7) << i;
      }
  }
}

TEST(MpiVolume, WithEarlyTerminationThePictureIsWithinTheTermination) {
  const Cloud cloud;
  const std::string keys = "mode: dvr, termination: 0.01, opacity: [[0, 0.5], [1, 0.9]]";
  const Frame one = one_process(cloud, "terminated-one", keys);
  const int ranks = world_size();
  const Share mine(cloud, "interleaved", world_rank(), ranks);
  Adapter a = adapter_from_config_text(config("terminated", keys), options(), MPI_COMM_WORLD);
  ASSERT_TRUE(a.execute(0, 0, mine.view()).ok());
  if (world_rank() == 0) {
    EXPECT_LT(largest_difference(frame_of(a).rgba, one.rgba), 0.01);
  }
}

// The deep EXR image of a job on every rank, read back with OpenEXR's deep reader, flattens
// into one process's picture (no background: premultiplied, alpha = 1 - transmittance).
TEST(MpiVolume, TheDeepImageOfTheJobFlattensIntoOneProcesssPicture) {
  const Cloud cloud;
  const std::string keys =
      "mode: mixed, iso: [{value: 6, opacity: 0.5}], termination: 0, background: none";
  const Frame one = one_process(cloud, "deep-one", keys);
  const int ranks = world_size();
  const Share mine(cloud, "slabs", world_rank(), ranks);
  const std::string yaml = config("deep", keys, "exr: {enabled: true, trigger: {every_steps: 1}}");
  Adapter a = adapter_from_config_text(yaml, options(), MPI_COMM_WORLD);
  EXPECT_TRUE(a.execute(5, 0, mine.view()).ok());
  a.finish();
  if (world_rank() != 0) return;
  const auto folder = std::filesystem::temp_directory_path() / "voxspan-mpi-volume-deep";
  const test::DeepExr deep = test::read_deep_exr(folder / "exr" / "v_00000005.exr");
  EXPECT_TRUE(deep.has_rgba);
  std::vector<float> flat;
  for (std::size_t p = 0; p < deep.z.size(); ++p) {
    float c[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < deep.z[p].size(); ++k) {
      const float behind = 1 - c[3];
      c[0] += behind * deep.r[p][k], c[1] += behind * deep.g[p][k];
      c[2] += behind * deep.b[p][k], c[3] += behind * deep.a[p][k];
    }
    flat.insert(flat.end(), c, c + 4);
  }
  EXPECT_LT(largest_difference(flat, one.rgba), 1e-5);
}

TEST(MpiVolume, ARankThatFailsFailsTheStepOnAllAndTheRunGoesOn) {
  const Cloud cloud;
  const Share mine(cloud, "slabs", world_rank(), world_size());
  Adapter a = adapter_from_config_text(config("fails", "mode: dvr"), options(), MPI_COMM_WORLD);
  // Rank 1 passes no `p`: its step fails there, and so on every rank.
  const ParticleView without_p =
      ParticleView::soa(mine.x.data(), mine.y.data(), mine.z.data(), mine.x.size());
  const Status failed = a.execute(1, 0.1, world_rank() == 1 ? without_p : mine.view());
  EXPECT_FALSE(failed.ok());
  EXPECT_NE(failed.message.find("rank 1: "), std::string::npos) << failed.message;
  EXPECT_TRUE(a.execute(2, 0.2, mine.view()).ok());
}

}  // namespace
}  // namespace voxspan

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
