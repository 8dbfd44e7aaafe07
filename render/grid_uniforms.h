// render/grid_uniforms.h - fills the uniforms of render/perspective_grid.glsl from a
// PerspectiveGrid, for every pass that includes it.
#pragma once

#include "render/gl/objects.h"
#include "render/perspective_grid.h"

namespace voxspan {

void set_grid_uniforms(const gl::Program& program, const PerspectiveGrid& grid);

}  // namespace voxspan
