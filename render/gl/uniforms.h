// render/gl/uniforms.h - the shared model's uniforms set on a GL program: those of
// render/gl/perspective_grid.glsl from a PerspectiveGrid (every pass that includes it), and the
// shading's (render/model/shade_uniforms.h) for the passes that shade.
#pragma once

#include "render/gl/objects.h"
#include "render/model/shade_uniforms.h"
#include "render/perspective_grid.h"

namespace voxspan {

void set_grid_uniforms(const gl::Program& program, const PerspectiveGrid& grid);
void set_shade_uniforms(const gl::Program& program, const model::ShadeUniforms& u);

}  // namespace voxspan
