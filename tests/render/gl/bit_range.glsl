// Sets bits [first, first + count) of `bits` with atomicOr, one whole word per store where
// the range covers it: the splat's way of marking a chord of voxels.
void set_bit_range(uint first, uint count) {
  if (count == 0u) return;
  uint last = first + count - 1u;
  uint w0 = first >> 5u, w1 = last >> 5u;
  for (uint w = w0; w <= w1; ++w) {
    uint lo = (w == w0) ? (first & 31u) : 0u;
    uint hi = (w == w1) ? (last & 31u) : 31u;
    uint upper = (hi == 31u) ? 0xFFFFFFFFu : ((1u << (hi + 1u)) - 1u);
    atomicOr(bits[w], upper & ~((1u << lo) - 1u));
  }
}
