// render/passes/prefix_sum.comp - exclusive prefix sum of uints in blocks of 1024 (256 threads
// x 4 values), the building block of PrefixSumPass (render/passes/prefix_sum.h).
//   scan (default): scans each block of values[0, u_count) in place and writes the block's total
//     to sums[u_sum_base + block];
//   PREFIX_ADD: values[i] += sums[i / 1024], after the block totals were scanned in turn.
// Reads and writes: values, sums. Cost: one read and one write per value per pass.
layout(local_size_x = 256) in;

layout(std430, binding = 0) buffer Values { uint values[]; };
layout(std430, binding = 1) buffer Sums { uint sums[]; };

uniform uint u_count;
uniform uint u_sum_base;

#ifndef PREFIX_ADD
shared uint s_sum[256];

void main() {
  uint lane = gl_LocalInvocationID.x;
  uint first = gl_WorkGroupID.x * 1024u + lane * 4u;
  uvec4 v = uvec4(0u);
  for (uint j = 0u; j < 4u; ++j)
    if (first + j < u_count) v[j] = values[first + j];
  uvec4 local = uvec4(0u, v.x, v.x + v.y, v.x + v.y + v.z);  // exclusive within the thread
  s_sum[lane] = local.w + v.w;
  barrier();
  // Inclusive scan of the 256 thread totals (Hillis-Steele, log2(256) steps).
  for (uint step = 1u; step < 256u; step <<= 1u) {
    uint add = lane >= step ? s_sum[lane - step] : 0u;
    barrier();
    s_sum[lane] += add;
    barrier();
  }
  uint before = lane == 0u ? 0u : s_sum[lane - 1u];
  for (uint j = 0u; j < 4u; ++j)
    if (first + j < u_count) values[first + j] = before + local[j];
  if (lane == 255u) sums[u_sum_base + gl_WorkGroupID.x] = s_sum[255];
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 256u)
    values[i] += sums[i / 1024u];
}
#endif
