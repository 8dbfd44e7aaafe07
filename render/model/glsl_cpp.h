// render/model/glsl_cpp.h - the subset of GLSL 4.50 that is also C++ with GLM, in which the
// shared model files of render/model/ (*.glsl) are written: the surface links, the filter,
// normals, deep AO and shading, written once, run by the GL passes (included into their .comp
// files) and on the CPU by the host class of render/model/host.h (the CPU renderer and the
// exact reference).
//
// The subset: GLM's types and functions, float literals with an `f` and unsigned ones with a
// `u`, no swizzles beyond single components, no in/out parameters, no global constants (use
// #define with a VX_ prefix), structs declared before use. The host class provides what a
// model file says it needs (sd_* accessors for the span data, view_ray, ray_scale and the u_*
// uniforms as members), and includes the model files inside its body, so their functions
// become its members and see its data.
#pragma once

#include <glm/glm.hpp>

namespace voxspan::model {

using namespace glm;  // NOLINT: the model files use GLSL's unqualified names
using uint = unsigned int;

// The uniforms of render/gl/perspective_grid.glsl, as the CPU host holds them.
struct GridUniforms {
  vec3 u_eye{0.0f}, u_right{1.0f, 0.0f, 0.0f}, u_up{0.0f, 1.0f, 0.0f}, u_forward{0.0f, 0.0f, -1.0f};
  vec2 u_tan_half{1.0f};
  ivec2 u_image{1};
  float u_near = 1.0f, u_grid_far = 2.0f, u_log2_step = 0.0f;

  // As render/gl/perspective_grid.glsl computes them, in float.
  vec3 view_ray(ivec2 pixel) const {
    const vec2 ndc(2.0f * (float(pixel.x) + 0.5f) / float(u_image.x) - 1.0f,
                   1.0f - 2.0f * (float(pixel.y) + 0.5f) / float(u_image.y));
    return vec3(ndc * u_tan_half, 1.0f);
  }
  float ray_scale(ivec2 pixel) const { return length(view_ray(pixel)); }
  // Whether every pixel's world ray (eye and direction) is the same as under `o`.
  bool same_rays(const GridUniforms& o) const {
    return u_eye == o.u_eye && u_right == o.u_right && u_up == o.u_up && u_forward == o.u_forward &&
           u_tan_half == o.u_tan_half && u_image == o.u_image;
  }
};

}  // namespace voxspan::model
