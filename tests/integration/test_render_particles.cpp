// The offline renderer (tools/render_particles) on small particle files: a CSV block with
// attributes and an XYZ file with a broken particle, rendered with a YAML config the way an
// in-situ run renders; and its errors on a missing file and a bad option.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>

#include "output_files.h"
#include "tests/support/temp_folder.h"

namespace voxspan {
namespace {

struct ToolRun {
  int status = -1;
  std::string out, err;
};

ToolRun run_tool(const std::filesystem::path& dir, const std::string& arguments) {
  const std::string command = std::string(RENDER_PARTICLES_EXE) + " " + arguments + " >" +
                              (dir / "stdout.txt").string() + " 2>" + (dir / "stderr.txt").string();
  ToolRun r;
  const int raw = std::system(command.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream out(dir / "stdout.txt"), err(dir / "stderr.txt");
  r.out.assign(std::istreambuf_iterator<char>(out), {});
  r.err.assign(std::istreambuf_iterator<char>(err), {});
  return r;
}

// A 14^3 block at spacing 1 cm (2744 particles) with a velocity and a pressure column.
void write_block_csv(const std::filesystem::path& path) {
  std::ofstream f(path);
  f << "x,y,z,vx,vy,vz,pressure\n";
  for (int k = 0; k < 14; ++k)
    for (int j = 0; j < 14; ++j)
      for (int i = 0; i < 14; ++i)
        f << (i + 0.5) * 0.01 << ',' << (j + 0.5) * 0.01 << ',' << (k + 0.5) * 0.01 << ',' << i
          << ",0,0," << k << '\n';
}

// The same block, shifted, as XYZ with a radius column, and one particle at NaN.
void write_block_xyz(const std::filesystem::path& path) {
  std::ofstream f(path);
  f << 14 * 14 * 14 + 1 << "\nblock with a NaN\n";
  for (int k = 0; k < 14; ++k)
    for (int j = 0; j < 14; ++j)
      for (int i = 0; i < 14; ++i)
        f << (i + 0.5) * 0.01 + 0.02 << ' ' << (j + 0.5) * 0.01 << ' ' << (k + 0.5) * 0.01
          << " 0.01\n";
  f << "nan 0 0 0.01\n";
}

std::int64_t counter(const std::string& line, const std::string& name) {
  std::smatch m;
  return std::regex_search(line, m, std::regex("\"" + name + "\":([0-9]+)")) ? std::stoll(m[1])
                                                                             : -1;
}

TEST(RenderParticles, RendersEveryFileWithTheConfig) {
  test::TempFolder dir;
  write_block_csv(dir / "a.csv");
  write_block_xyz(dir / "b.xyz");
  std::ofstream(dir / "offline.yaml")
      << "views:\n"
         "  - {name: front, width: 128, height: 96, absorption: [80, 40, 20]}\n"
         "  - {name: side, width: 96, height: 96, shading: opaque, absorption: [80, 40, 20], "
         "camera: {direction: [1, 0.2, -0.3]}}\n"
         "outputs:\n  vtk: {enabled: true, trigger: {last: true}, attributes: [pressure]}\n";
  const std::filesystem::path out = dir / "out";
  const ToolRun r = run_tool(
      dir.path(), "--config " + (dir / "offline.yaml").string() + " --output " + out.string() +
                      " " + (dir / "a.csv").string() + " " + (dir / "b.xyz").string());
  // b.xyz has no pressure column: its step fails, named, and the run goes on.
  ASSERT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("particle spacing 0.01 (estimated"), std::string::npos) << r.out;
  // The library's line says why, the tool's which file (once each).
  EXPECT_NE(r.err.find("step 1: outputs.vtk: " + dir.path().string() +
                       "/offline.yaml:5:8: outputs.vtk.attributes \"pressure\": the solver "
                       "passes no attribute of that name (it passes none)\nrender_particles: " +
                       dir.path().string() + "/b.xyz: not rendered (the error above)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("a.csv: step 0, 2744 particles"), std::string::npos) << r.out;
  // A CSV holds no time: the caption's t is the file's index, and the tool says so once.
  EXPECT_NE(r.out.find("a.csv gives no time: the time (a caption's {time}) is the file's index"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("b.xyz gives no time"), std::string::npos) << r.out;

  // Attributes every file has (none): both files go through.
  std::ofstream(dir / "offline.yaml", std::ios::trunc)
      << "views:\n"
         "  - {name: front, width: 128, height: 96, absorption: [80, 40, 20]}\n"
         "  - {name: side, width: 96, height: 96, shading: opaque, absorption: [80, 40, 20], "
         "camera: {direction: [1, 0.2, -0.3]}}\n"
         "outputs:\n  vtk: {enabled: true, trigger: {first: true}}\n";
  std::filesystem::remove_all(out);
  const ToolRun ok =
      run_tool(dir.path(), "--config " + (dir / "offline.yaml").string() + " --output " +
                               out.string() + " --spacing 0.01 " + (dir / "a.csv").string() + " " +
                               (dir / "b.xyz").string());
  ASSERT_EQ(ok.status, 0) << ok.out << ok.err;
  EXPECT_EQ(test::files_in(out / "frames"),
            (std::vector<std::string>{"front_00000000.png", "front_00000001.png",
                                      "side_00000000.png", "side_00000001.png"}));
  for (const std::string& name : test::files_in(out / "frames")) {
    const test::DecodedPng png = test::read_png_file(out / "frames" / name);
    ASSERT_TRUE(png.ok) << name << ": " << png.error;
    EXPECT_GT(png.fraction_unlike_row_background(), 0.05) << name;
  }
  const std::vector<std::string> stats = test::read_lines(out / "stats.jsonl");
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(counter(stats[0], "particles"), 2744);
  EXPECT_EQ(counter(stats[1], "particles"), 2745);
  EXPECT_EQ(counter(stats[1], "dropped_nonfinite"), 1);  // the NaN particle, left out
  // The classifier left the block's interior out: a 14^3 block in 2 cm cells keeps its shell.
  EXPECT_LT(counter(stats[0], "boundary"), 2744);
  EXPECT_GT(counter(stats[0], "boundary"), 1000);
  const test::VtpContents vtp = test::read_vtp(out / "vtk" / "particles_00000000.vtp");
  ASSERT_TRUE(vtp.ok);
  EXPECT_FALSE(vtp.appended_data);
  EXPECT_EQ(vtp.points, counter(stats[0], "boundary"));
  EXPECT_NE(std::find(vtp.arrays.begin(), vtp.arrays.end(), "radius"), vtp.arrays.end());
}

TEST(RenderParticles, MissingFileAndBadOptionAreOneLineErrors) {
  test::TempFolder dir;
  ToolRun r = run_tool(dir.path(),
                       "--output " + (dir / "out").string() + " " + (dir / "none.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find((dir / "none.csv").string()), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_tool(dir.path(), "--spacing -1 x.csv");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--spacing expects a positive number"), std::string::npos) << r.err;
}

// A missing PySPH file says so (not "not an HDF5 file"), and --arrays on a file that has no
// arrays is an error, not a run that renders the whole file as if asked to.
TEST(RenderParticles, ReaderErrorsSayWhichFileAndWhy) {
  test::TempFolder dir;
  const std::string missing = (dir / "dam_break_100.hdf5").string();
  ToolRun r = run_tool(dir.path(), "--output " + (dir / "out").string() + " " + missing);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "render_particles: error: cannot read particles from " + missing + ": no such file\n");
  write_block_csv(dir / "a.csv");
  r = run_tool(dir.path(), "--arrays fluid --output " + (dir / "out").string() + " " +
                               (dir / "a.csv").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find((dir / "a.csv").string() +
                       ": particle arrays were named (fluid), but only HDF5 files"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// A file with no particles (an inlet's fluid before it flows in) is a step like the others: its
// pictures are written and the run succeeds, with a warning naming the file. Leading empty
// files leave the spacing to the first file with particles.
// An .xyz file's fourth column is its radius: a density there gives spheres a thousand times
// the spacing, which the tool says rather than drawing one giant blob silently.
TEST(RenderParticles, RadiiFarFromTheSpacingAreSaid) {
  test::TempFolder dir;
  {
    std::ofstream f(dir / "rho.xyz");
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i)
          f << i * 0.01 << ' ' << j * 0.01 << ' ' << k * 0.01 << " 1000\n";
  }
  const ToolRun r =
      run_tool(dir.path(), "--output " + (dir / "out").string() + " " + (dir / "rho.xyz").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("rho.xyz: the particles' radii (median 1e+03) are far from their spacing "
                       "0.01: is another column read as radii"),
            std::string::npos)
      << r.err;
}

TEST(RenderParticles, AFileWithNoParticlesIsRenderedWithAWarning) {
  test::TempFolder dir;
  std::ofstream(dir / "empty.csv") << "x,y,z\n";
  write_block_csv(dir / "a.csv");
  const std::filesystem::path out = dir / "out";
  ToolRun r = run_tool(dir.path(), "--output " + out.string() + " " + (dir / "empty.csv").string() +
                                       " " + (dir / "a.csv").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.err, "render_particles: warning: " + (dir / "empty.csv").string() +
                       " holds no particles; its pictures show none\n");
  EXPECT_NE(r.out.find("particle spacing 0.01 (estimated from " + (dir / "a.csv").string()),
            std::string::npos)
      << r.out;
  EXPECT_EQ(test::files_in(out / "frames"),
            (std::vector<std::string>{"main_00000000.png", "main_00000001.png"}));

  // Alone, with no spacing anywhere: nothing is drawn, so the spacing does not matter.
  std::filesystem::remove_all(out);
  r = run_tool(dir.path(), "--output " + out.string() + " " + (dir / "empty.csv").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("empty.csv holds no particles"), std::string::npos) << r.err;
  EXPECT_EQ(test::files_in(out / "frames"), (std::vector<std::string>{"main_00000000.png"}));
}

// A series whose names end in their steps, unpadded and given in the shell's order (_10
// before _2): rendered in the order of the steps, each as its own step, and said.
TEST(RenderParticles, ASeriesTakesItsStepsAndOrderFromItsNames) {
  test::TempFolder dir;
  for (const char* name : {"fluid_1.csv", "fluid_10.csv", "fluid_2.csv"})
    write_block_csv(dir / name);
  const std::filesystem::path out = dir / "out";
  const ToolRun r = run_tool(
      dir.path(), "--output " + out.string() + " " + (dir / "fluid_1.csv").string() + " " +
                      (dir / "fluid_10.csv").string() + " " + (dir / "fluid_2.csv").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("the files are rendered in the order of the numbers that end their names "
                       "(fluid_10.csv was given before fluid_2.csv)"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(
      test::files_in(out / "frames"),
      (std::vector<std::string>{"main_00000001.png", "main_00000002.png", "main_00000010.png"}));
}

}  // namespace
}  // namespace voxspan
