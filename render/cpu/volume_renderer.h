// render/cpu/volume_renderer.h - the CPU volume renderer (render/cpu/volume_caster.h) behind the
// volume-renderer interface (render/volume_renderer.h).
#pragma once

#include <memory>

#include "render/volume_renderer.h"

namespace voxspan {

std::unique_ptr<VolumeRenderer> make_cpu_volume_renderer();

}  // namespace voxspan
