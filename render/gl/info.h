// render/gl/info.h - what the current GL context is and the limits that size our buffers and
// dispatches (shader-storage block size, work groups, shared memory, GPU memory).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace voxspan::gl {

class Context;

struct Info {
  std::string platform;  // "surfaceless", "nvidia", ...
  std::string device;    // Context::description()
  std::string vendor, renderer, version, glsl_version;
  int major = 0, minor = 0;
  std::int64_t max_ssbo_block_bytes = 0;
  int max_ssbo_bindings = 0;
  glm::ivec3 max_work_group_count{0};
  glm::ivec3 max_work_group_size{0};
  int max_work_group_invocations = 0;
  int max_shared_memory_bytes = 0;
  int max_3d_texture_size = 0;
  // Only where the driver reports it (GL_NVX_gpu_memory_info on NVIDIA).
  std::optional<std::int64_t> gpu_memory_total_bytes;
  std::optional<std::int64_t> gpu_memory_available_bytes;
  bool gpu_timers = false;
};

// Queries the context, which must be current.
Info query_info(const Context& context);

// Whether the current context renders on the CPU (Mesa's llvmpipe, softpipe or swrast). Passes
// pick their CPU-friendly variants there: llvmpipe runs work-group barriers and shared-memory
// atomics slowly, and plain global atomics and long per-thread loops fast.
bool software_renderer();

}  // namespace voxspan::gl
