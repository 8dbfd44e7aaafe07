// render/gl/passes/prefix_sum.comp - exclusive prefix sum of uints in blocks of 4096 (256 threads
// x 16 values: PREFIX_PER_THREAD), the building block of PrefixSumPass
// (render/gl/passes/prefix_sum.h).
//   scan (default): scans each block of values[0, u_count) in place and writes the block's total
//     to sums[u_sum_base + block];
//   PREFIX_ADD: values[i] += sums[i / kBlock], after the block totals were scanned in turn.
// Reads and writes: values, sums. Cost: one read and one write per value per pass.
layout(local_size_x = 256) in;

layout(std430, binding = VALUES_BINDING) buffer Values { uint values[]; };
layout(std430, binding = SUMS_BINDING) buffer Sums { uint sums[]; };

uniform uint u_count;
uniform uint u_sum_base;

const uint kPerThread = PREFIX_PER_THREAD;
const uint kBlock = gl_WorkGroupSize.x * kPerThread;  // values per work group

#ifndef PREFIX_ADD
shared uint s_sum[256];

void main() {
  uint lane = gl_LocalInvocationID.x;
  uint first = gl_WorkGroupID.x * kBlock + lane * kPerThread;
  // Each thread scans its kPerThread values; one thread then scans the 256 thread totals: two
  // barriers per block (llvmpipe's barriers are slow; on a GPU this is a sliver of a frame).
  uint local[kPerThread];
  uint sum = 0u;
  for (uint j = 0u; j < kPerThread; ++j) {
    local[j] = sum;
    if (first + j < u_count) sum += values[first + j];
  }
  s_sum[lane] = sum;
  barrier();
  if (lane == 0u) {
    uint running = 0u;
    for (uint t = 0u; t < 256u; ++t) {
      uint v = s_sum[t];
      s_sum[t] = running;
      running += v;
    }
    sums[u_sum_base + gl_WorkGroupID.x] = running;
  }
  barrier();
  uint before = s_sum[lane];
  for (uint j = 0u; j < kPerThread; ++j)
    if (first + j < u_count) values[first + j] = before + local[j];
}
#else
void main() {
  for (uint i = gl_GlobalInvocationID.x; i < u_count; i += gl_NumWorkGroups.x * 256u)
    values[i] += sums[i / kBlock];
}
#endif
