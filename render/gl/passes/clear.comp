// Zeroes u_count uvec4 words of the bound range. uvec4 stores run at ~1.8 TB/s on an H100,
// 50x faster than glClearBufferData (GPU-NOTES). Grid-stride loop: the group count stays under
// the 65535 that GL guarantees.
layout(local_size_x = 256) in;

layout(std430, binding = WORDS_BINDING) writeonly buffer Words { uvec4 words[]; };

uniform uint u_count;

void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += stride) words[i] = uvec4(0u);
}
