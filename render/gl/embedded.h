// render/gl/embedded.h - text files (GLSL) compiled into the binary by voxspan_embed_files()
// (cmake/VoxspanEmbed.cmake), named by their path relative to the repository root.
#pragma once

#include <span>
#include <string_view>

namespace voxspan {

struct EmbeddedFile {
  std::string_view path;
  std::string_view text;
};

namespace embedded {
// The shaders of render/ (its passes and their shared GLSL helpers).
std::span<const EmbeddedFile> render_shaders();
}  // namespace embedded

}  // namespace voxspan
