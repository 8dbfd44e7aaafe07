#include "image_compare.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "insitu/png_image.h"
#include "voxspan/error.h"

namespace voxspan::test {

ImageDifference compare_images(const FloatImage& a, const FloatImage& b) {
  if (a.width != b.width || a.height != b.height)
    throw make_error("compare_images: ", a.width, "x", a.height, " against ", b.width, "x", b.height);
  const ImageRGBA8 ea = linear_to_srgb8(a.rgba, a.width, a.height);
  const ImageRGBA8 eb = linear_to_srgb8(b.rgba, b.width, b.height);
  double squares = 0, sum = 0;
  int most = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ea.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const int d = std::abs(int(ea.pixels[i]) - int(eb.pixels[i]));
    squares += double(d) * d;
    sum += d;
    most = std::max(most, d);
    ++n;
  }
  ImageDifference r;
  r.max_levels = most;
  r.mean_levels = n ? sum / double(n) : 0;
  const double mse = n ? squares / double(n) : 0;
  r.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
  return r;
}

}  // namespace voxspan::test
