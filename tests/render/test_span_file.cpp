// Span images in files (tools/scenes/span_compare.h), as bench_voxelize --save-spans and
// --compare-spans use them to compare two machines' voxelizations: a round trip is bit for
// bit, and a truncated file, a foreign file or one made for another image size is an error
// that names the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render/reference/exact_spans.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/span_compare.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

SpanImage cloud_spans(int width, int height) {
  const test::Particles p = test::random_cloud(300, {0, 0, 0}, {1, 1, 1}, 0.02, 0.1, 3);
  const Camera camera = test::frame_scene(p, {0.2, 0.3, -1}, width, height);
  return exact_spans(PerspectiveGrid::over(camera, 0.5, 5, GridOptions{}), p, {}, {0.01, 3});
}

std::string error_of(const std::filesystem::path& path, const PerspectiveGrid& grid) {
  try {
    test::load_spans(path, grid);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SpanFile, RoundTripIsBitForBitAndBadFilesAreErrors) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "voxspan-span-file";
  std::filesystem::create_directories(dir);
  const SpanImage image = cloud_spans(64, 48);
  ASSERT_GT(image.spans.size(), 100u);
  const std::filesystem::path file = dir / "spans.bin";
  test::save_spans(image, file);
  EXPECT_TRUE(test::identical(test::load_spans(file, image.grid), image));

  const std::string bytes = [&] {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const std::filesystem::path cut = dir / "cut.bin";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 5));
  EXPECT_NE(error_of(cut, image.grid).find("cut.bin: truncated"), std::string::npos);

  const std::filesystem::path foreign = dir / "foreign.bin";
  std::ofstream(foreign) << "P5\n64 48\n255\n";
  EXPECT_NE(error_of(foreign, image.grid).find("not a span file"), std::string::npos);

  const std::string other_size = error_of(file, cloud_spans(32, 24).grid);
  EXPECT_NE(other_size.find("3072 pixels, the grid has 768"), std::string::npos) << other_size;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxspan
