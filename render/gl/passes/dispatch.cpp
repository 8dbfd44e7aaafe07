#include "render/gl/passes/dispatch.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {
namespace {

std::size_t groups_for(const gl::Program& program, std::size_t threads) {
  const std::size_t group = program.work_group_size().x;
  return (threads + group - 1) / group;
}

}  // namespace

void dispatch_threads(const gl::Program& program, std::size_t threads) {
  if (threads == 0) return;
  const std::size_t groups = groups_for(program, threads);
  const std::size_t x = std::min(groups, kMaxGroups);
  const std::size_t y = (groups + x - 1) / x;
  if (y > kMaxGroups || threads > 0xFFFFFFFFu)
    throw make_error(program.name(), ": ", threads, " threads are more than one dispatch holds");
  program.set("u_thread_count", static_cast<unsigned>(threads));
  program.dispatch(static_cast<GLuint>(x), static_cast<GLuint>(y));
}

void dispatch_strided(const gl::Program& program, std::size_t items) {
  program.dispatch(static_cast<GLuint>(std::min(groups_for(program, items), kMaxGroups)));
}

std::size_t strided_threads(const gl::Program& program) {
  return kMaxGroups * program.work_group_size().x;
}

}  // namespace voxspan
