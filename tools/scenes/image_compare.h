// Picture comparisons for the shading tests and tools (bench_shading, render_pictures --compare):
// PSNR and largest difference of two float images as they are seen, i.e. after the 8-bit sRGB
// encoding the PNG frames get (insitu/outputs/formats/png_image.h), over the RGB channels of every
// pixel.
#pragma once

#include "insitu/outputs/formats/png_image.h"
#include "render/float_image.h"

namespace voxspan::test {

struct ImageDifference {
  double psnr = 0;     // dB; infinite when identical
  int max_levels = 0;  // largest difference of one channel, in 1/255 steps
  double mean_levels = 0;
};

// Throws voxspan::Error when the sizes differ.
ImageDifference compare_images(const FloatImage& a, const FloatImage& b);
ImageDifference compare_images(const ImageRGBA8& a, const ImageRGBA8& b);

}  // namespace voxspan::test
