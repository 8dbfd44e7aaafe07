// The whole path a solver takes, through the shared library as a solver links it: the dam
// break of examples/dambreak runs a few dozen steps with the in-situ runtime behind its
// adapter (two views, OpenVDB and VTK snapshots, stats), and every file the config asks for
// must exist, be complete, and open with the readers users have (libpng, VTK, OpenVDB); the
// level set of the snapshot must hold the fluid's volume.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>

#include "dambreak_run.h"
#include "output_files.h"
#include "tests/support/temp_folder.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"
#include "voxspan/voxspan.h"

namespace voxspan {
namespace {

constexpr int kSteps = 30;
const std::vector<std::int64_t> kRenderSteps = {1, 10, 20, 30};  // first, every 10, last
const std::vector<std::int64_t> kSnapshotSteps = {20, 30};       // every 20, last

std::string config_for(const std::filesystem::path& folder) {
  return "output_folder: " + folder.string() + R"(
trigger: {every_steps: 10, first: true, last: true}
views:
  - {name: glass, width: 160, height: 90, shading: translucent, absorption: [60, 30, 15]}
  - name: water
    width: 120
    height: 96
    shading: refractive
    absorption: [40, 20, 10]
    camera: {direction: [1, 1.5, -0.7], framing: each_step}
outputs:
  vdb: {enabled: true, trigger: {every_steps: 20, last: true}, attributes: [velocity, density]}
  vtk: {enabled: true, trigger: {every_steps: 20, last: true}, attributes: [velocity]}
writer: {fsync: false}
)";
}

std::string numbered(const std::string& prefix, std::int64_t step, const std::string& ext) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%08lld", static_cast<long long>(step));
  return prefix + "_" + digits + "." + ext;
}

std::int64_t counter(const std::string& line, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(line, m, std::regex("\"" + name + "\":([0-9]+)"))) return -1;
  return std::stoll(m[1]);
}

class DamBreakRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempFolder;
    sim_ = new dambreak::DamBreak(test::small_dambreak());
    Adapter adapter = adapter_from_config_text(config_for(dir_->path()),
                                               test::solver_options(*sim_), "test.yaml");
    result_ = test::run_dambreak(*sim_, adapter, kSteps);
    summary_ = adapter.summary();
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete dir_;
  }
  static std::filesystem::path out(const std::string& sub) { return dir_->path() / sub; }

  static test::TempFolder* dir_;
  static dambreak::DamBreak* sim_;
  static test::RunResult result_;
  static std::string summary_;
};
test::TempFolder* DamBreakRun::dir_ = nullptr;
dambreak::DamBreak* DamBreakRun::sim_ = nullptr;
test::RunResult DamBreakRun::result_;
std::string DamBreakRun::summary_;

TEST_F(DamBreakRun, EveryStepSucceeds) {
  EXPECT_EQ(result_.steps, kSteps);
  EXPECT_EQ(result_.failed, 0) << result_.first_failure;
  EXPECT_NE(summary_.find("4 render steps, 8 views rendered"), std::string::npos) << summary_;
  EXPECT_NE(summary_.find("8 PNG, 2 VDB, 2 VTK sets, 4 stats lines"), std::string::npos)
      << summary_;
  EXPECT_TRUE(test::temporaries_under(dir_->path()).empty());
}

TEST_F(DamBreakRun, FramesOfEveryViewAreCompletePictures) {
  std::vector<std::string> expected;
  for (const char* view : {"glass", "water"})
    for (std::int64_t step : kRenderSteps) expected.push_back(numbered(view, step, "png"));
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(test::files_in(out("frames")), expected);
  for (const std::string& name : expected) {
    const test::DecodedPng png = test::read_png_file(out("frames") / name);
    ASSERT_TRUE(png.ok) << name << ": " << png.error;
    const bool glass = name.rfind("glass", 0) == 0;
    EXPECT_EQ(png.width, glass ? 160 : 120) << name;
    EXPECT_EQ(png.height, glass ? 90 : 96) << name;
    // The fluid fills a good part of the picture, and the background shows around it.
    const double fluid = png.fraction_unlike_row_background();
    EXPECT_GT(fluid, 0.05) << name;
    EXPECT_LT(fluid, 0.95) << name;
  }
}

TEST_F(DamBreakRun, StatsHaveOneCompleteLinePerRenderStep) {
  bool complete = false;
  const std::vector<std::string> lines = test::read_lines(out("stats.jsonl"), &complete);
  EXPECT_TRUE(complete);
  ASSERT_EQ(lines.size(), kRenderSteps.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    EXPECT_EQ(counter(l, "step"), kRenderSteps[i]);
    EXPECT_EQ(l.back(), '}');
    EXPECT_EQ(counter(l, "particles"), std::int64_t(sim_->fluid().size()));
    EXPECT_GT(counter(l, "boundary"), 0);
    EXPECT_EQ(counter(l, "dropped"), 0);
    EXPECT_EQ(counter(l, "culled"), 0);  // automatic framing sees every particle
    for (const char* key : {"\"classify\":", "\"host_rss\":", "\"gpu\":", "\"glass\":",
                            "\"water\":", "\"spans.stored\":", "\"connect\":", "\"shade\":"})
      EXPECT_NE(l.find(key), std::string::npos) << key << " missing in " << l;
    // The renderer's own passes: the GL one voxelizes, the CPU one casts.
    const bool gl = l.find("\"splat\":") != std::string::npos;
    EXPECT_EQ(l.find("\"compress\":") != std::string::npos, gl) << l;
    EXPECT_EQ(l.find("\"cast\":") != std::string::npos, !gl) << l;
  }
}

TEST_F(DamBreakRun, SnapshotsOpenWithOpenVdbAndHoldTheFluidsVolume) {
  const double particle_volume = double(sim_->fluid().size()) * std::pow(sim_->dx(), 3);
  for (std::int64_t step : kSnapshotSteps) {
    const std::string name = numbered("fluid", step, "vdb");
    const test::VdbContents vdb = test::read_vdb(out("snapshots") / name);
    ASSERT_TRUE(vdb.ok) << name << ": " << vdb.error;
    EXPECT_EQ(vdb.step, step);
    EXPECT_EQ(vdb.fluid_class, "level set");
    for (const char* grid : {"fluid", "velocity", "density", "cell_state"})
      EXPECT_NE(std::find(vdb.grids.begin(), vdb.grids.end(), grid), vdb.grids.end()) << grid;
    // The interior comes from the filled inner-full cells: the boundary particles alone
    // would hold far less than the fluid.
    std::printf("%s: level-set volume / particle volume = %.4f\n", name.c_str(),
                vdb.fluid_volume / particle_volume);
    EXPECT_NEAR(vdb.fluid_volume / particle_volume, 1.0, 0.10)
        << name << ": level set " << vdb.fluid_volume << ", particles " << particle_volume;
  }
  EXPECT_EQ(test::files_in(out("snapshots")).size(), kSnapshotSteps.size());
}

TEST_F(DamBreakRun, VtkFilesOpenWithVtkAndTheSeriesListsThem) {
  const std::vector<std::string> stats = test::read_lines(out("stats.jsonl"));
  std::vector<std::string> vtp_names, vti_names;
  for (std::int64_t step : kSnapshotSteps) {
    vtp_names.push_back(numbered("particles", step, "vtp"));
    vti_names.push_back(numbered("cells", step, "vti"));
    const test::VtpContents vtp = test::read_vtp(out("vtk") / vtp_names.back());
    ASSERT_TRUE(vtp.ok) << vtp_names.back();
    EXPECT_FALSE(vtp.appended_data) << vtp_names.back() << ": ParaView 5.11 cannot read it";
    EXPECT_GT(vtp.points, 0);
    // The boundary particles of that step, as the stats line of the same step counts them.
    for (const std::string& line : stats)
      if (counter(line, "step") == step) {
        EXPECT_EQ(vtp.points, counter(line, "boundary"));
      }
    EXPECT_NE(std::find(vtp.arrays.begin(), vtp.arrays.end(), "radius"), vtp.arrays.end());
    EXPECT_NE(std::find(vtp.arrays.begin(), vtp.arrays.end(), "velocity"), vtp.arrays.end());
    const test::VtiContents vti = test::read_vti(out("vtk") / vti_names.back());
    ASSERT_TRUE(vti.ok) << vti_names.back();
    EXPECT_FALSE(vti.appended_data) << vti_names.back() << ": ParaView 5.11 cannot read it";
    EXPECT_TRUE(vti.has_state);
    const dambreak::GridShape& g = sim_->fluid_grid().shape();
    EXPECT_EQ(vti.dims[0], g.dims[0] + 1);
    EXPECT_EQ(vti.dims[2], g.dims[2] + 1);
  }
  EXPECT_EQ(test::pvd_files(out("vtk") / "particles.pvd"), vtp_names);
  EXPECT_EQ(test::pvd_files(out("vtk") / "cells.pvd"), vti_names);
}

// A C or Fortran solver's way in: the config file by path, the last step marked, the files
// waited for, the summary read back.
TEST(CApi, RunsTheRuntimeFromAConfigFile) {
  test::TempFolder dir;
  const std::filesystem::path file = dir / "insitu.yaml";
  std::ofstream(file) << "output_folder: " << (dir / "out").string() << "\n"
                      << "trigger: {last: true}\nviews: [{width: 64, height: 48}]\n";
  dambreak::DamBreak sim(test::small_dambreak());
  voxspan_adapter_options o;
  voxspan_adapter_options_init(&o);
  o.particle_spacing = sim.dx();
  voxspan_adapter* a = voxspan_adapter_create_from_config(&o, file.c_str());
  ASSERT_NE(a, nullptr) << voxspan_last_error();
  voxspan_particles* p = voxspan_particles_create();
  for (int step = 1; step <= 3; ++step) {
    sim.step();
    const dambreak::Fluid& f = sim.fluid();
    voxspan_particles_set_soa(p, VOXSPAN_FLOAT32, f.x.data(), f.y.data(), f.z.data(), f.size());
    const int rc = step < 3 ? voxspan_adapter_execute(a, step, sim.time(), p, nullptr)
                            : voxspan_adapter_execute_last(a, step, sim.time(), p, nullptr);
    EXPECT_EQ(rc, VOXSPAN_OK) << voxspan_last_error();
  }
  EXPECT_EQ(voxspan_adapter_finish(a), VOXSPAN_OK);
  char summary[512];
  const std::size_t length = voxspan_adapter_summary(a, summary, sizeof summary);
  EXPECT_GT(length, 0u);
  EXPECT_NE(std::string(summary).find("1 render steps, 1 views rendered; written: 1 PNG"),
            std::string::npos)
      << summary;
  EXPECT_EQ(test::files_in(dir / "out" / "frames"), std::vector<std::string>{"view0_00000003.png"});
  voxspan_particles_destroy(p);
  voxspan_adapter_destroy(a);
}

}  // namespace
}  // namespace voxspan
