#include "tools/scenes/image_compare.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "voxspan/error.h"

namespace voxspan::test {

ImageDifference compare_images(const FloatImage& a, const FloatImage& b) {
  return compare_images(linear_to_srgb8(a.rgba, a.width, a.height),
                        linear_to_srgb8(b.rgba, b.width, b.height));
}

ImageDifference compare_images(const ImageRGBA8& ea, const ImageRGBA8& eb) {
  if (ea.width != eb.width || ea.height != eb.height)
    throw make_error("compare_images: ", ea.width, "x", ea.height, " against ", eb.width, "x",
                     eb.height);
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
