// insitu/outputs/formats/exr_image.h - OpenEXR images of a view, for compositors (Nuke, Houdini,
// OpenEXR's own tools): scanline files, ZIP-compressed, row 0 at the top (line order
// INCREASING_Y), 32-bit float channels. Encoded in memory, so the file is written atomically.
// Everything OpenEXR stays inside exr_image.cpp.
#pragma once

#include <filesystem>
#include <string>

#include "insitu/views/view_products.h"
#include "render/float_image.h"
#include "render/span_image.h"
#include "render/volume.h"

namespace voxspan {

// One FLOAT channel named `channel` from the r component of `image`.
std::string encode_exr_channel(const FloatImage& image, const std::string& channel);

// The picture's R, G, B, A as FLOAT channels (linear, as shaded).
std::string encode_exr_rgba(const FloatImage& image);

// An OpenEXR 2.0 deep scanline image of the span image: per pixel one sample per stored span,
// channels Z (its entry) and ZBack (its exit) as distances from the eye along the unit ray
// through the pixel's centre; ZIPS-compressed, row 0 at the top.
std::string encode_deep_exr(const SpanImage& spans);

// An OpenEXR 2.0 deep scanline image of a volume view's deep image (render/volume.h): per pixel
// one sample per run of fluid along the ray, channels Z and ZBack (its ends, distances from the
// eye along the unit ray) and R, G, B, A (its light, premultiplied, and opacity), which
// OpenEXR's flattening composites into the picture without its background.
std::string encode_deep_exr(const DeepImage& deep);

// A slice's raw values as FLOAT channels `value` (the quantity, 0 where no particle reaches) and
// `weight` (sum_j (m_j / rho_j) W: 0 there), with the plane's pixel-to-world mapping in the
// header (docs/runtime.md, "Depth images"): voxspan:quantity (string), voxspan:origin,
// voxspan:u, voxspan:v (v3d), voxspan:width, voxspan:height (double, world units) and
// voxspan:pixel_to_world, the formula as text.
std::string encode_exr_field(const FieldImage& field);

// encode_exr_channel + write_file_atomically (temp name, fsync when sync, rename). Throws
// WriteError on I/O failure, voxspan::Error when OpenEXR refuses the image.
void write_exr_channel(const std::filesystem::path& path, const FloatImage& image,
                       const std::string& channel, bool sync = true);

}  // namespace voxspan
