// render/gl/passes/prefix_sum.h - in-place exclusive prefix sum of a GPU array of uints, with the
// grand total written after the last value. Used to turn per-tile particle counts into list
// offsets (binning) and per-pixel span counts into span offsets (compress).
// Reads and writes: values[0, count] of the buffer (count + 1 uints). Cost: about two reads and
// two writes per value; levels of 4096-value blocks (a million values take two dispatches
// down and one up). Scratch for the block totals is kept from call to call.
#pragma once

#include <cstddef>
#include <vector>

#include "render/gl/objects.h"
#include "render/gl/shader_library.h"

namespace voxspan {

class PrefixSumPass {
 public:
  explicit PrefixSumPass(const gl::ShaderLibrary& shaders);
  // values[i] = sum of the old values[0, i) for i < count; values[count] = their total.
  // The buffer must hold count + 1 uints. Values must sum to less than 2^32.
  void run(gl::Buffer& values, std::size_t count);

 private:
  void scan_level(gl::Buffer& values, std::size_t count, std::size_t level);

  gl::Program scan_;
  gl::Program add_;
  std::size_t block_;  // values one scan work group sums
  std::vector<gl::Buffer> level_sums_;
};

}  // namespace voxspan
