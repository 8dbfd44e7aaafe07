// How clearly a picture shows its water: the water pixels (where the view's depth image has a
// hit) against the background pixels (none), for the default-view tests (tests only).
#pragma once

#include <filesystem>
#include <vector>

#include "output_files.h"

namespace voxspan::test {

// The depth output's channel Z (0 where the ray hit nothing), row by row.
std::vector<float> read_depth_exr(const std::filesystem::path& path, int& width, int& height);

struct Contrast {
  double tint = 0;       // mean (blue - red) / 255 of the water pixels minus the background's
  double luminance = 0;  // mean of the water pixels, 0..1
  int water = 0, background = 0;
  int grey_background = 0;  // background pixels whose channels are within 10/255 of each other
};

// Water: pixels with a hit whose 5x5 neighbourhood is all hits (silhouettes left out, where
// the picture blends water and background); background: pixels whose 5x5 neighbourhood has
// none. `depth` is the picture's own size.
Contrast water_contrast(const DecodedPng& png, const std::vector<float>& depth);

}  // namespace voxspan::test
