// render/gl/passes/bits.h - the C++ side of render/gl/passes/bits.glsl: the uniforms that give the
// column clear, the splat and the compress pass the layout of the tile's voxel bits.
#pragma once

#include "render/gl/objects.h"
#include "render/gl/tiling.h"

namespace voxspan {

void set_bit_uniforms(const gl::Program& program, const TileLayout& layout, const TileRect& tile);

}  // namespace voxspan
