// render/gl/passes/volume_march.h - a volume view's frame on the GPU ([FAW10] sec. 5, [HOK16]
// sec. 6.1): the CPU caster's project, sort and bin (render/cpu/volume_caster.h, VolumeSetup)
// uploaded, then one work group per 8x8-pixel bundle gathering its tile's supports through
// shared memory, summing each sample in float in the list's order (no atomics: the same picture
// whatever the threads), compositing through render/model/volume.glsl, lighting the iso hits.
// Reads: the setup, the transfer table, the options. Writes: the picture (linear RGBA) and the
// depth per pixel (VolumeFrame's), and the frame's counts. With adaptive sampling, the setup's
// plans (render/cpu/volume_adaptive.h) followed as the CPU caster's march follows them; with
// walls (VolumeOptions::backdrop) each ray ends at the sample where the CPU caster's ends, over
// the walls' colour.
// Cost: per pixel, every support of its tile whose first sample lies before each slab's end is
// read once per slab of kSlab samples (a chord test each); kernel evaluations as the caster's.
#pragma once

#include <cstdint>

#include "render/cpu/volume_caster.h"
#include "render/gl/objects.h"
#include "render/gl/shader_library.h"
#include "render/model/volume_host.h"
#include "render/volume.h"

namespace voxspan {

class VolumeMarchPass {
 public:
  static constexpr int kSlab = 32;  // samples summed per slab, in each thread's own arrays

  explicit VolumeMarchPass(const gl::ShaderLibrary& shaders);

  // The frame of `setup` into `out` (read back); adds the march's counts to `counts`. False when
  // a bundle ran past llvmpipe's loop budget (out is then not the frame: draw it elsewhere).
  bool run(const Camera& camera, const VolumeSetup& setup, const VolumeOptions& options,
           const model::VolumeHost& host, VolumeFrame& out, VolumeCounts& counts);

 private:
  bool software_;  // llvmpipe and the like: a loop budget per invocation
  gl::Program program_;
  gl::Buffer supports_, tile_start_, tile_lists_, depths_, transfer_, picture_, depth_, counts_;
  gl::Buffer bundle_cells_, cells_, super_pixels_;  // adaptive sampling's plans
  gl::Buffer walls_;  // VolumeOptions::backdrop: colours and the samples where rays end
};

}  // namespace voxspan
