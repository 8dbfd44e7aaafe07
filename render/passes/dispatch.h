// render/passes/dispatch.h - one thread per item for passes over more items than one dispatch
// dimension holds: a 2D grid of work groups, the item count in u_thread_count, and each
// thread's item from render/passes/thread_index.glsl. No thread loops over items, so a thread's
// work stays bounded whatever the count (llvmpipe stops invocations after 65535 loop
// iterations).
#pragma once

#include <cstddef>

#include "render/gl/objects.h"

namespace voxspan {

// Sets u_thread_count and dispatches ceil(threads / group size) groups; nothing when 0.
void dispatch_threads(const gl::Program& program, std::size_t threads);

}  // namespace voxspan
