#include "render/passes/dispatch.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {

void dispatch_threads(const gl::Program& program, std::size_t threads) {
  if (threads == 0) return;
  constexpr std::size_t kMaxGroups = 65535;
  const std::size_t group = program.work_group_size().x;
  const std::size_t groups = (threads + group - 1) / group;
  const std::size_t x = std::min(groups, kMaxGroups);
  const std::size_t y = (groups + x - 1) / x;
  if (y > kMaxGroups || threads > 0xFFFFFFFFu)
    throw make_error(program.name(), ": ", threads, " threads are more than one dispatch holds");
  program.set("u_thread_count", static_cast<unsigned>(threads));
  program.dispatch(static_cast<GLuint>(x), static_cast<GLuint>(y));
}

}  // namespace voxspan
