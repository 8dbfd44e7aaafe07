// One thread per bit range; many ranges overlap, so threads race on the same words.
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Bits { uint bits[]; };
layout(std430, binding = 1) readonly buffer Ranges { uvec2 ranges[]; };  // (first bit, count)

uniform uint u_count;

#include "tests/render/gl/bit_range.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < u_count) set_bit_range(ranges[i].x, ranges[i].y);
}
