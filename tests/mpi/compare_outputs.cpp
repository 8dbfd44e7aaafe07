// compare_outputs REFERENCE OTHER [--png-tolerance N] [--depth-layers L]: the pictures and
// depth images of a run (OTHER: frames/*.png, depth/*.exr, the Cinema database's
// cinema.cdb/<step>/*.png and *.exr, its data.csv byte for byte) against those of another
// (REFERENCE): every PNG within N/255 per channel (default 1), every depth image with the same
// pixels hit and each distance within L depth layers (default 1; a layer is `--layer F` of the
// distance, default 0.0025). Prints one line per file; exit status 1 when any is outside.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "insitu/outputs/formats/png_image.h"
#include "tests/support/depth_exr_reader.h"

namespace fs = std::filesystem;

namespace {

bool compare_png(const fs::path& a, const fs::path& b, int tolerance) {
  const voxspan::ImageRGBA8 x = voxspan::read_png(a), y = voxspan::read_png(b);
  if (x.width != y.width || x.height != y.height) {
    std::printf("FAIL %s: %dx%d against %dx%d\n", b.c_str(), y.width, y.height, x.width, x.height);
    return false;
  }
  int worst = 0;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < x.pixels.size(); ++i) {
    const int d = std::abs(int(x.pixels[i]) - int(y.pixels[i]));
    worst = std::max(worst, d);
    differing += d > 0;
  }
  const bool ok = worst <= tolerance;
  std::printf("%s %s: largest difference %d/255, %zu channel values differ\n", ok ? "ok  " : "FAIL",
              b.c_str(), worst, differing);
  return ok;
}

bool compare_depth(const fs::path& a, const fs::path& b, double layers, double layer) {
  const voxspan::test::DepthExr x = voxspan::test::read_depth_exr(a),
                                y = voxspan::test::read_depth_exr(b);
  if (x.width != y.width || x.height != y.height) {
    std::printf("FAIL %s: %dx%d against %dx%d\n", b.c_str(), y.width, y.height, x.width, x.height);
    return false;
  }
  std::size_t mask = 0, exact = 0, hits = 0;
  double worst = 0;
  for (std::size_t i = 0; i < x.z.size(); ++i) {
    if ((x.z[i] > 0) != (y.z[i] > 0)) ++mask;
    if (x.z[i] > 0 && y.z[i] > 0) {
      ++hits;
      exact += x.z[i] == y.z[i];
      worst = std::max(worst, std::abs(double(x.z[i]) - y.z[i]) / (layer * double(x.z[i])));
    }
  }
  const bool ok = mask == 0 && worst <= layers;
  std::printf(
      "%s %s: %zu pixels hit, %zu bit for bit, worst %.3g layers, %zu pixels hit in one only\n",
      ok ? "ok  " : "FAIL", b.c_str(), hits, exact, worst, mask);
  return ok;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: compare_outputs REFERENCE OTHER [--png-tolerance N] "
                 "[--depth-layers L] [--layer F]\n");
    return 2;
  }
  int tolerance = 1;
  double layers = 1, layer = 0.0025;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--png-tolerance") tolerance = std::atoi(argv[i + 1]);
    else if (k == "--depth-layers") layers = std::atof(argv[i + 1]);
    else if (k == "--layer") layer = std::atof(argv[i + 1]);
  }
  const fs::path ref = argv[1], other = argv[2];
  bool ok = true;
  int files = 0;
  for (const char* sub : {"frames", "depth", "cinema.cdb"}) {
    if (!fs::is_directory(ref / sub)) continue;
    for (const auto& e : fs::recursive_directory_iterator(ref / sub)) {
      if (!e.is_regular_file()) continue;
      const fs::path b = other / fs::relative(e.path(), ref);
      ++files;
      if (!fs::exists(b)) {
        std::printf("FAIL %s: missing\n", b.c_str());
        ok = false;
      } else if (e.path().extension() == ".png") {
        ok = compare_png(e.path(), b, tolerance) && ok;
      } else if (e.path().extension() == ".exr") {
        ok = compare_depth(e.path(), b, layers, layer) && ok;
      } else if (e.path().extension() == ".csv") {
        const bool same = read_text(e.path()) == read_text(b);
        std::printf("%s %s: %s\n", same ? "ok  " : "FAIL", b.c_str(),
                    same ? "the same rows" : "rows differ");
        ok = same && ok;
      }
    }
  }
  if (files == 0) {
    std::printf("FAIL %s: no pictures or depth images to compare\n", ref.c_str());
    return 1;
  }
  return ok ? 0 : 1;
}
