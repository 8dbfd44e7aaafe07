// Encodes unit vectors with render/model/octahedral.glsl on the GPU and decodes them again, so
// the test can compare both directions with the CPU's compilation of the same file.
layout(local_size_x = 64) in;

#include "render/model/octahedral.glsl"

layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, binding = 1) writeonly buffer Words { uint words[]; };
layout(std430, binding = 2) writeonly buffer Decoded { vec4 decoded[]; };

uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  uint w = encode_normal(inputs[i].xyz);
  words[i] = w;
  decoded[i] = vec4(decode_normal(w), 0.0);
}
