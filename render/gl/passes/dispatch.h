// render/gl/passes/dispatch.h - how every pass sizes its grid of work groups: from the program's
// own work-group size (gl::Program::work_group_size()) and the group count GL guarantees per
// grid dimension, so no pass redoes the arithmetic. Two ways to cover items with threads:
//   one thread per item (dispatch_threads): a 2D grid, the item count in u_thread_count, each
//     thread's item from render/gl/passes/thread_index.glsl. No thread loops over items, so a
//     thread's work stays bounded whatever the count (llvmpipe stops invocations after 65535
//     loop iterations): for passes over more items than one grid dimension holds;
//   grid-stride (dispatch_strided): a 1D grid of at most kMaxGroups groups whose threads step
//     through the items by the grid's thread count, for passes whose work groups loop over
//     batches together (shared memory, barriers) or whose items fit one row of groups.
#pragma once

#include <cstddef>

#include "render/gl/objects.h"

namespace voxspan {

// Work groups GL guarantees per grid dimension (GL_MAX_COMPUTE_WORK_GROUP_COUNT).
inline constexpr std::size_t kMaxGroups = 65535;

// Sets u_thread_count and dispatches one thread per item; nothing when 0.
void dispatch_threads(const gl::Program& program, std::size_t threads);

// Dispatches ceil(items / group size) groups, at most kMaxGroups, in one row; nothing when 0.
void dispatch_strided(const gl::Program& program, std::size_t items);

// The threads of the largest dispatch_strided() grid: kMaxGroups groups.
std::size_t strided_threads(const gl::Program& program);

}  // namespace voxspan
