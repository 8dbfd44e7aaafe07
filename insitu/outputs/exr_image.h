// insitu/outputs/exr_image.h - OpenEXR images of a view, for compositors (Nuke, Houdini,
// OpenEXR's own tools): scanline files, ZIP-compressed, row 0 at the top (line order
// INCREASING_Y), 32-bit float channels. Encoded in memory, so the file is written atomically.
// Everything OpenEXR stays inside exr_image.cpp.
#pragma once

#include <filesystem>
#include <string>

#include "render/float_image.h"

namespace voxspan {

// One FLOAT channel named `channel` from the r component of `image`.
std::string encode_exr_channel(const FloatImage& image, const std::string& channel);

// encode_exr_channel + write_file_atomically (temp name, fsync when sync, rename). Throws
// WriteError on I/O failure, voxspan::Error when OpenEXR refuses the image.
void write_exr_channel(const std::filesystem::path& path, const FloatImage& image,
                       const std::string& channel, bool sync = true);

}  // namespace voxspan
