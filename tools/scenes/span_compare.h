// Accuracy of a span image against another (the GPU's against the exact reference), in units
// of the local layer thickness, as the voxelization issue states its bounds:
//   - span counts: equal on the pixels that either side hits;
//   - boundaries: on pixels with equal counts, each entry and exit within `layers` local layer
//     thicknesses (the thickness of the layer holding the reference's depth);
//   - inside length per pixel: within one layer thickness (along the ray) per span boundary;
//   - inside length summed over the image.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "render/span_image.h"

namespace voxspan::test {

struct SpanComparison {
  std::int64_t pixels_hit = 0;          // either side has a span
  std::int64_t pixels_count_equal = 0;  // of those, same stored and found counts
  std::int64_t boundaries = 0;          // compared (pixels with equal counts)
  std::int64_t boundaries_within = 0;
  std::int64_t pixels_inside_within = 0;  // of pixels_hit
  double worst_boundary_layers = 0;       // largest boundary error, in layer thicknesses
  double inside_sum_test = 0, inside_sum_reference = 0;

  double count_match() const { return pixels_hit ? double(pixels_count_equal) / pixels_hit : 1; }
  double boundary_match() const { return boundaries ? double(boundaries_within) / boundaries : 1; }
  double inside_match() const { return pixels_hit ? double(pixels_inside_within) / pixels_hit : 1; }
  double inside_sum_error() const;  // relative
  std::string summary() const;
};

SpanComparison compare_spans(const SpanImage& test, const SpanImage& reference,
                             double layers = 1.0);

// The first `most` pixels whose span counts differ, with both lists, for failure messages.
std::string describe_mismatches(const SpanImage& test, const SpanImage& reference, int most);

// True when both images hold exactly the same records and spans (bit for bit).
bool identical(const SpanImage& a, const SpanImage& b);
// The same, but each pixel's `inside` within a relative tolerance (a merge of span images
// sums it again, in another order).
bool same_spans(const SpanImage& a, const SpanImage& b, double inside_tolerance);

// A span image's pixels and spans in a file, to compare two renderers' voxelizations of the
// same scene on different machines (an NVIDIA GPU against llvmpipe). The grid is not stored:
// load_spans takes the loading side's, and throws voxspan::Error when the file cannot be read
// or its pixel count does not match the grid.
void save_spans(const SpanImage& image, const std::filesystem::path& path);
SpanImage load_spans(const std::filesystem::path& path, const PerspectiveGrid& grid);

}  // namespace voxspan::test
