// A user's first picture of a solver no one here wrote: PySPH's own 3D dam break (Debian's
// python3-pysph, run live by tools/scripts/pysph_dambreak.sh), its last file rendered by
// render_particles with no config and no --arrays. The tool must pick the fluid array and leave
// the tank and the obstacle out, take the spacing from the particles' mass and density, and
// show the water clearly: tinted against the background and not black, measured as
// test_default_view measures our own dam break (water_contrast.h). Skipped without PySPH.
//
// VOXSPAN_KEEP_PICTURES=DIR keeps the picture (docs/images/default_view_pysph.png);
// VOXSPAN_PYSPH_OUTPUT=DIR runs PySPH into DIR and keeps its files there, or, when DIR already
// holds them, renders those without running PySPH again.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "output_files.h"
#include "tests/support/temp_folder.h"
#include "water_contrast.h"

namespace voxspan {
namespace {

struct CommandRun {
  int status = -1;
  std::string out;  // stdout and stderr
};

CommandRun run(const std::string& command, const std::filesystem::path& log) {
  CommandRun r;
  const int raw = std::system((command + " >" + log.string() + " 2>&1").c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  r.out.assign(std::istreambuf_iterator<char>(in), {});
  return r;
}

std::vector<std::filesystem::path> pysph_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".hdf5") files.push_back(e.path());
  // dam_break_3d_<iteration, zero-padded>.hdf5: the names sort in time order.
  std::sort(files.begin(), files.end());
  return files;
}

bool same_pixels(const test::DecodedPng& a, const test::DecodedPng& b) {
  return a.width == b.width && a.height == b.height && a.rgba == b.rgba;
}

TEST(DefaultViewPySPH, TheWaterOfPySPHsDamBreakIsClearlyVisibleWithNoConfig) {
  test::TempFolder dir;
  const char* kept = std::getenv("VOXSPAN_PYSPH_OUTPUT");
  const std::filesystem::path pysph = kept != nullptr ? kept : dir / "pysph";
  std::vector<std::filesystem::path> files = pysph_files(pysph);
  if (files.empty()) {
    const CommandRun r =
        run(std::string(PYSPH_DAMBREAK_SH) + " " + pysph.string(), dir / "pysph_dambreak.txt");
    if (r.status == 77) GTEST_SKIP() << "PySPH is not installed (python3-pysph): " << r.out;
    ASSERT_EQ(r.status, 0) << r.out;
    std::printf("%s", r.out.c_str());
    files = pysph_files(pysph);
  }
  // Step 0, the steps every --pfreq and the last: the column at rest and collapsing.
  ASSERT_GE(files.size(), 3u);
  const std::filesystem::path last = files.back();

  // The picture under test: no config, no --arrays, no --spacing.
  const std::filesystem::path plain = dir / "plain";
  const CommandRun r =
      run(std::string(RENDER_PARTICLES_EXE) + " --output " + plain.string() + " " + last.string(),
          dir / "render.txt");
  ASSERT_EQ(r.status, 0) << r.out;
  std::printf("%s", r.out.c_str());
  EXPECT_NE(r.out.find("reading PySPH arrays fluid (named like a fluid); scenery: boundary, "
                       "obstacle"),
            std::string::npos)
      << r.out;
  // dx = 0.05 (the script's default) with m = rho0 dx^3: the spacing comes back from m / rho,
  // up to the weak compressibility's per mille in the density.
  std::smatch spacing;
  ASSERT_TRUE(std::regex_search(
      r.out, spacing,
      std::regex("particle spacing ([0-9.e+-]+) \\(from the particles' mass and density")))
      << r.out;
  EXPECT_NEAR(std::stod(spacing[1]), 0.05, 0.0005) << r.out;
  // The frame is numbered by the file's own step, PySPH's iteration count (its name's number).
  std::smatch stepped;
  ASSERT_TRUE(std::regex_search(r.out, stepped, std::regex(": step ([0-9]+), 5016 particles")))
      << r.out;
  const std::string stem = last.stem().string();
  EXPECT_EQ(std::stoll(stepped[1]), std::stoll(stem.substr(stem.rfind('_') + 1))) << r.out;
  char frame[64];
  std::snprintf(frame, sizeof frame, "main_%08lld", std::stoll(stepped[1]));
  const std::filesystem::path picture = plain / "frames" / (std::string(frame) + ".png");
  const test::DecodedPng png = test::read_png_file(picture);
  ASSERT_TRUE(png.ok) << png.error;
  if (const char* keep = std::getenv("VOXSPAN_KEEP_PICTURES"); keep != nullptr)
    std::filesystem::copy_file(picture, std::filesystem::path(keep) / "default_view_pysph.png",
                               std::filesystem::copy_options::overwrite_existing);

  // The same render with the depth image added, to tell water pixels from background ones;
  // a depth output changes nothing in the picture (checked).
  std::ofstream(dir / "depth.yaml") << "outputs:\n"
                                       "  depth: {enabled: true, trigger: {every_steps: 1}}\n";
  const std::filesystem::path with_depth = dir / "depth";
  const CommandRun d =
      run(std::string(RENDER_PARTICLES_EXE) + " --config " + (dir / "depth.yaml").string() +
              " --output " + with_depth.string() + " " + last.string(),
          dir / "render_depth.txt");
  ASSERT_EQ(d.status, 0) << d.out;
  const test::DecodedPng png_d =
      test::read_png_file(with_depth / "frames" / (std::string(frame) + ".png"));
  ASSERT_TRUE(png_d.ok) << png_d.error;
  EXPECT_TRUE(same_pixels(png, png_d)) << "a depth output changed the picture";
  int w = 0, h = 0;
  const std::vector<float> depth =
      test::read_depth_exr(with_depth / "depth" / (std::string(frame) + ".exr"), w, h);
  ASSERT_EQ(w, png.width);
  ASSERT_EQ(h, png.height);

  const test::Contrast c = test::water_contrast(png, depth);
  std::printf(
      "PySPH dam break, %s: water tinted %+.3f against the background, luminance %.2f (%d "
      "water, %d background pixels)\n",
      last.filename().string().c_str(), c.tint, c.luminance, c.water, c.background);
  ASSERT_GT(c.water, 1000);
  ASSERT_GT(c.background, 1000);
  EXPECT_GT(c.tint, 0.08) << "the water should stand out, tinted";
  EXPECT_GT(c.luminance, 0.3) << "and not black";
}

}  // namespace
}  // namespace voxspan
