// outputs.cinema through the runtime: a Cinema specification D database (data.csv's header,
// FILE columns last, one type per column, every file there), the (0, 0) picture the view's own
// PNG byte for byte, the other angles different, and bad settings refused at start-up.
// The same database from MPI ranks as from one process: tests/mpi/views.yaml.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/view_tests.h"

namespace voxspan {
namespace {

namespace fs = std::filesystem;

constexpr double kSpacing = 0.05;

test::ParticleBlock block() {
  return {kSpacing, "speed", [](int, double x) { return x; }};
}

std::string config(const std::string& folder, const std::string& cinema) {
  return "output_folder: " + testing::TempDir() + folder +
         "\n"
         "trigger: {every_steps: 1}\n"
         "writer: {fsync: false}\n"
         "views:\n"
         "  - {name: water, width: 96, height: 54, shading: translucent}\n"
         "  - {name: dots, kind: particles, width: 80, height: 60, color_by: speed}\n"
         "outputs:\n"
         "  png: {enabled: true, folder: frames, trigger: {every_steps: 1}}\n"
         "  stats: {enabled: false}\n"
         "  cinema: {enabled: true, trigger: {every_steps: 2}, " +
         cinema + "}\n";
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string>& row = rows.emplace_back();
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(cell);
  }
  return rows;
}

std::string bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

fs::path run(const std::string& folder, const std::string& cinema, int steps) {
  const fs::path out = fs::path(testing::TempDir()) / folder;
  fs::remove_all(out);
  const test::ParticleBlock b = block();
  Adapter a = adapter_from_config_text(config(folder, cinema), test::spaced(b.spacing));
  for (int step = 0; step < steps; ++step) EXPECT_TRUE(a.execute(step, 0.01 * step, b.view()).ok());
  a.finish();
  return out;
}

TEST(Cinema, WritesASpecificationDDatabase) {
  const fs::path out = run("cinema_db", "phi: [-30, 0, 30], theta: [0, 20], depth: true", 5);
  const fs::path db = out / "cinema.cdb";
  const auto rows = read_csv(db / "data.csv");
  ASSERT_FALSE(rows.empty());
  const std::vector<std::string> header{"time",  "step", "view",      "phi",
                                        "theta", "FILE", "FILE_depth"};
  EXPECT_EQ(rows[0], header);
  // Steps 0, 2, 4; two views; six angles each.
  ASSERT_EQ(rows.size(), 1u + 3 * 2 * 6);
  std::set<std::string> distinct;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), header.size()) << r;
    for (std::size_t c : {0, 1, 3, 4}) EXPECT_TRUE(is_number(rows[r][c])) << rows[r][c];
    EXPECT_FALSE(is_number(rows[r][2]));
    for (std::size_t c : {5, 6}) {
      EXPECT_TRUE(fs::is_regular_file(db / rows[r][c])) << rows[r][c];
      EXPECT_GT(fs::file_size(db / rows[r][c]), 0u);
    }
    EXPECT_TRUE(distinct.insert(rows[r][5]).second) << "listed twice: " << rows[r][5];
  }
  EXPECT_EQ(rows[1][2], "water");
  EXPECT_EQ(rows[1][5], "00000000/water_p-30_t0.png");
  EXPECT_EQ(rows.back()[1], "4");
  EXPECT_EQ(rows.back()[0], "0.040000000000000001");  // the solver's time, all its digits
}

TEST(Cinema, TheViewsOwnAngleIsTheViewsPictureAndTheOthersDiffer) {
  const fs::path out = run("cinema_same", "phi: [0, 45], theta: [0, 30]", 3);
  for (const std::string view : {"water", "dots"})
    for (const std::string step : {"00000000", "00000002"}) {
      const std::string own = bytes(out / "frames" / (view + "_" + step + ".png"));
      const fs::path folder = out / "cinema.cdb" / step;
      ASSERT_FALSE(own.empty());
      EXPECT_EQ(bytes(folder / (view + "_p0_t0.png")), own) << view << " " << step;
      for (const std::string other : {"_p45_t0.png", "_p0_t30.png", "_p45_t30.png"})
        EXPECT_NE(bytes(folder / (view + other)), own) << view << other;
    }
}

TEST(Cinema, BadSettingsAreRefusedAtStartUp) {
  const test::ParticleBlock b = block();
  for (const auto& [cinema, words] : std::vector<std::pair<std::string, std::string>>{
           {"views: [nowhere]", ":10:61: outputs.cinema.views: there is no view \"nowhere\""},
           {"phi: []", "needs at least one angle"},
           {"theta: [90]", "theta"},
           {"phi: [0, 0]", "phi"},
           {"phi: [-180, 0, 180]", "-180 and 180 are the same angle"},
           {"folder: pictures", "ends in .cdb"}}) {
    try {
      Adapter a = adapter_from_config_text(config("cinema_bad", cinema), test::spaced(kSpacing));
      ADD_FAILURE() << cinema << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace voxspan
