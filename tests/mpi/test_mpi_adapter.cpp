// The adapter inside an MPI job (run under mpiexec on 3 ranks): bad input on one rank fails the
// step on all with one error line, and the run goes on; a rank's config that differs from rank
// 0's is refused at start-up, naming the rank and the key; NaN positions, an empty rank and
// every rank empty still give a picture, and an empty rank the snapshots that name attributes.
// Every rank runs every test, in the same order (the runtime's collectives need them all); only
// rank 0 prints.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "output_files.h"
#include "tests/support/log_capture.h"
#include "voxspan/error.h"
#include "tests/support/mpi_tests.h"
#include "voxspan/mpi.h"

namespace voxspan {
namespace {

int rank() { return test::world_rank(); }
int ranks() { return test::world_size(); }

// A folder every rank names alike, made new by rank 0.
std::filesystem::path shared_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("voxspan-mpi-test-" + name);
  if (rank() == 0) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return folder;
}

std::string config_for(const std::filesystem::path& folder, int width = 96,
                       const std::string& more = {}) {
  return "output_folder: " + folder.string() + "\ntrigger: {every_steps: 1}\nviews:\n" +
         "  - {name: v, width: " + std::to_string(width) + ", height: 64, shading: translucent}\n" +
         "writer: {fsync: false}\n" + more;
}

// A block of fluid cut into slabs along x, one per rank; `count` particles per side.
struct Block {
  std::vector<double> x, y, z;
  explicit Block(int count, bool mine = true) {
    if (!mine) return;
    const double dx = 0.01;
    for (int k = 0; k < count; ++k)
      for (int j = 0; j < count; ++j)
        for (int i = 0; i < count; ++i) {
          if (i * ranks() / count != rank()) continue;
          x.push_back((i + 0.5) * dx), y.push_back((j + 0.5) * dx), z.push_back((k + 0.5) * dx);
        }
  }
  ParticleView view() const { return ParticleView::soa(x.data(), y.data(), z.data(), x.size()); }
};

AdapterOptions options() {
  AdapterOptions o;
  o.classify.particle_spacing = 0.01;
  return o;
}

TEST(MpiAdapter, ARankWhoseConfigDiffersIsRefusedNamingItAndTheKey) {
  const auto folder = shared_folder("config");
  const std::string yaml = config_for(folder, rank() == 1 ? 640 : 96);
  try {
    adapter_from_config_text(yaml, options(), MPI_COMM_WORLD, "mpi.yaml");
    FAIL() << "no error on rank " << rank();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rank 1's config differs from rank 0's at views[0].width"),
              std::string::npos)
        << e.what();
  }
}

// What one rank alone cannot use at start-up (a typo in its copy of the config, a config file
// missing on its node, an option its part of the particles gives wrong) is refused on every
// rank, naming that rank: the others had waited for it for ever in the pipeline's first
// collective.
TEST(MpiAdapter, WhatOneRankCannotUseAtStartUpIsRefusedOnEveryRank) {
  const auto folder = shared_folder("one-rank");
  const bool last = rank() == ranks() - 1;
  const auto refusal = [](const auto& make) {
    try {
      make();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string typo = refusal([&] {
    adapter_from_config_text(config_for(folder, 96, last ? "writer_typo: 1\n" : ""), options(),
                             MPI_COMM_WORLD, "mpi.yaml");
  });
  const std::string prefix = "rank " + std::to_string(ranks() - 1) + ": ";
  EXPECT_EQ(typo.rfind(prefix, 0), 0u) << typo;
  EXPECT_NE(typo.find("writer_typo: unknown key"), std::string::npos) << typo;

  if (rank() == 0) std::ofstream(folder / "insitu.yaml") << config_for(folder);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string missing = refusal([&] {
    adapter_from_config_file((folder / (last ? "missing.yaml" : "insitu.yaml")).string(), options(),
                             MPI_COMM_WORLD);
  });
  EXPECT_EQ(missing.rfind(prefix, 0), 0u) << missing;
  EXPECT_NE(missing.find("missing.yaml"), std::string::npos) << missing;

  AdapterOptions spacing = options();
  if (last) spacing.classify.particle_spacing = std::numeric_limits<double>::quiet_NaN();
  const std::string option = refusal(
      [&] { adapter_from_config_text(config_for(folder), spacing, MPI_COMM_WORLD, "mpi.yaml"); });
  EXPECT_EQ(option.rfind(prefix, 0), 0u) << option;
  EXPECT_NE(option.find("particle_spacing"), std::string::npos) << option;
}

TEST(MpiAdapter, BadInputOnOneRankFailsTheStepOnAllWithOneErrorLine) {
  const auto folder = shared_folder("bad-input");
  test::LogCapture log;
  Adapter adapter = adapter_from_config_text(config_for(folder), options(), MPI_COMM_WORLD);
  const Block block(12);
  // Rank 1 hands over a grid whose cell offsets run backwards: invalid input there.
  const std::vector<std::uint32_t> offsets = {5, 0};
  const GridView bad = GridView::offsets(GridGeometry{{0, 0, 0}, 1.0, {1, 1, 1}}, offsets.data());
  const Status failed = adapter.execute(1, 0.1, block.view(), rank() == 1 ? bad : GridView());
  EXPECT_FALSE(failed.ok());
  if (rank() != 1) {
    EXPECT_NE(failed.message.find("step abandoned: rank 1: "), std::string::npos) << failed.message;
  }
  const std::size_t errors = log.at(LogLevel::error).size();
  EXPECT_EQ(errors, rank() == 0 ? 1u : 0u) << log.all();
  // The run goes on: the next step renders on every rank.
  EXPECT_TRUE(adapter.execute(2, 0.2, block.view()).ok());
  adapter.finish();
  if (rank() == 0) {
    EXPECT_TRUE(test::read_png_file(folder / "frames" / "v_00000002.png").ok);
  }
}

// An attribute one rank's solver does not pass, named by any kind of view: every rank's step
// fails with the rank and its reason (the key, the attribute, what that rank passes), and rank 0
// logs it once.
TEST(MpiAdapter, AnAttributeOneRankLacksIsNamedWithTheRankByEveryViewKind) {
  const std::vector<std::string> views = {
      "{name: s, kind: slice, width: 64, height: 48, quantity: p}",
      "{name: c, width: 64, height: 48, color_by: p}",
      "{name: g, kind: particles, width: 64, height: 48, color_by: p}",
      "{name: d, kind: volume, width: 64, height: 48, quantity: p}"};
  for (const std::string& view : views) {
    const auto folder = shared_folder("lacks-p");
    test::LogCapture log;
    const std::string yaml = "output_folder: " + folder.string() +
                             "\ntrigger: {every_steps: 1}\nviews: [" + view + "]\n";
    Adapter adapter = adapter_from_config_text(yaml, options(), MPI_COMM_WORLD);
    const Block block(12);
    const std::vector<double> p(block.x.size(), 1.0), q(block.x.size(), 1.0);
    ParticleView particles = block.view();
    if (rank() == 1) particles.with_scalar("q", q.data());
    else particles.with_scalar("p", p.data());
    const Status failed = adapter.execute(1, 0.1, particles);
    EXPECT_FALSE(failed.ok()) << view;
    EXPECT_NE(failed.message.find("rank 1: "), std::string::npos) << view << ": " << failed.message;
    EXPECT_NE(failed.message.find("\"p\": the solver passes no attribute of that name (did you "
                                  "mean \"q\"? it passes: q)"),
              std::string::npos)
        << view << ": " << failed.message;
    EXPECT_EQ(log.at(LogLevel::error).size(), rank() == 0 ? 1u : 0u) << view << ": " << log.all();
    adapter.finish();
  }
}

// A rank one step ahead of the others (it skipped a call) fails the step on every rank, naming
// both steps, instead of compositing two steps' particles; once they meet again they render.
TEST(MpiAdapter, RanksAtDifferentStepsAreSaidNotComposited) {
  const auto folder = shared_folder("steps-apart");
  test::LogCapture log;
  Adapter adapter = adapter_from_config_text(config_for(folder), options(), MPI_COMM_WORLD);
  const Block block(12);
  EXPECT_TRUE(adapter.execute(1, 0.1, block.view()).ok());
  const Status apart = adapter.execute(rank() == 1 ? 3 : 2, 0.2, block.view());
  EXPECT_FALSE(apart.ok());
  EXPECT_NE(apart.message.find("the ranks are at different steps (2 to 3)"), std::string::npos)
      << apart.message;
  EXPECT_EQ(log.at(LogLevel::error).size(), rank() == 0 ? 1u : 0u) << log.all();
  EXPECT_TRUE(adapter.execute(4, 0.4, block.view()).ok());
  adapter.finish();
}

// A rank that throws in the middle of the step, after every rank has classified and while the
// others voxelize: its grid is longer than a GL 3D texture may be, so the GL renderer's
// cell-state upload fails inside its render pass. Every rank abandons the step, one line names
// the rank, and the next step renders.
TEST(MpiAdapter, ARankThatThrowsMidStepFailsTheStepOnAllAndTheRunGoesOn) {
  const auto folder = shared_folder("throws");
  test::LogCapture log;
  Adapter adapter = adapter_from_config_text(config_for(folder, 96, "renderer: {backend: gl}\n"),
                                             options(), MPI_COMM_WORLD);
  const Block block(12);
  // 20 000 cells along x: more than any GL's 3D texture side (16 384 on NVIDIA, 2 048 on Mesa).
  const GridView too_long = GridView::geometry_only(GridGeometry{{0, 0, 0}, 0.01, {20000, 12, 12}});
  const Status failed = adapter.execute(1, 0.1, block.view(), rank() == 1 ? too_long : GridView());
  EXPECT_FALSE(failed.ok());
  EXPECT_NE(failed.message.find("rank 1: cell states: grid of 20000x12x12 cells"),
            std::string::npos)
      << failed.message;
  const std::vector<std::string> errors = log.at(LogLevel::error);
  EXPECT_EQ(errors.size(), rank() == 0 ? 1u : 0u) << log.all();
  EXPECT_TRUE(adapter.execute(2, 0.2, block.view()).ok());
  adapter.finish();
  if (rank() == 0) {
    EXPECT_FALSE(std::filesystem::exists(folder / "frames" / "v_00000001.png"));
    EXPECT_TRUE(test::read_png_file(folder / "frames" / "v_00000002.png").ok);
  }
}

TEST(MpiAdapter, NanPositionsEmptyRanksAndNoFluidAtAllStillRender) {
  const auto folder = shared_folder("empty");
  Adapter adapter = adapter_from_config_text(config_for(folder), options(), MPI_COMM_WORLD);
  Block nan(12);
  if (!nan.x.empty()) nan.x[0] = std::nan("");
  EXPECT_TRUE(adapter.execute(1, 0.1, nan.view()).ok());
  EXPECT_EQ(adapter.last_stats().counts.dropped_nonfinite, nan.x.empty() ? 0u : 1u);
  const Block last_empty(12, rank() != ranks() - 1);
  EXPECT_TRUE(adapter.execute(2, 0.2, last_empty.view()).ok());
  const Block none(12, false);
  EXPECT_TRUE(adapter.execute(3, 0.3, none.view()).ok());
  adapter.finish();
  if (rank() != 0) return;
  for (int step = 1; step <= 3; ++step) {
    const auto png =
        test::read_png_file(folder / "frames" / ("v_0000000" + std::to_string(step) + ".png"));
    EXPECT_TRUE(png.ok) << step;
    if (step < 3) {
      EXPECT_GT(png.fraction_unlike_row_background(), 0.05) << step;
    }
  }
}

// A rank with no particles names no attribute values: the snapshot and the mesh that ask for
// the velocity are still written from the other ranks (they were a deadlock: the empty rank's
// copy failed before the gather the others waited in).
TEST(MpiAdapter, AnEmptyRankWithSnapshotAttributesStillWritesThem) {
  const auto folder = shared_folder("empty-attributes");
  const std::string outputs =
      "outputs:\n"
      "  vdb: {enabled: true, trigger: {every_steps: 1}, attributes: [velocity]}\n"
      "  mesh: {enabled: true, trigger: {every_steps: 1}, attributes: [velocity]}\n";
  Adapter adapter =
      adapter_from_config_text(config_for(folder, 96, outputs), options(), MPI_COMM_WORLD);
  const Block block(12, rank() != 1);
  const std::vector<double> velocity(3 * block.x.size(), 0.5);
  const Status s = adapter.execute(1, 0.1, block.view().with_vector("velocity", velocity.data()));
  EXPECT_TRUE(s.ok()) << s.message;
  adapter.finish();
  if (rank() != 0) return;
  EXPECT_TRUE(std::filesystem::exists(folder / "snapshots" / "fluid_00000001.vdb"));
  EXPECT_TRUE(std::filesystem::exists(folder / "mesh" / "fluid_00000001.ply"));
}

TEST(MpiAdapter, StatsLineHasTheJobsCountsTheSlowestRankAndTheBytesEachSent) {
  const auto folder = shared_folder("stats");
  Adapter adapter = adapter_from_config_text(config_for(folder), options(), MPI_COMM_WORLD);
  const Block block(12);
  ASSERT_TRUE(adapter.execute(1, 0.1, block.view()).ok());
  adapter.finish();
  if (rank() != 0) return;
  const std::vector<std::string> lines = test::read_lines(folder / "stats.jsonl");
  ASSERT_EQ(lines.size(), 1u);
  const std::string& line = lines[0];
  // Every rank's particles counted: the whole block.
  EXPECT_NE(line.find("\"particles\":1728"), std::string::npos) << line;
  EXPECT_NE(line.find("\"ranks\":{\"count\":3,\"bytes_sent\":["), std::string::npos) << line;
  EXPECT_NE(line.find("\"timings_ms_mean\":{"), std::string::npos) << line;
  EXPECT_NE(line.find("\"composite\":"), std::string::npos) << line;
}

}  // namespace
}  // namespace voxspan

int main(int argc, char** argv) { return voxspan::test::run_mpi_tests(argc, argv); }
