#include "render/gl/info.h"

#include <epoxy/gl.h>

#include "render/gl/context.h"

namespace voxspan::gl {
namespace {

std::string gl_string(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

int gl_int(GLenum name) {
  GLint v = 0;
  glGetIntegerv(name, &v);
  return v;
}

glm::ivec3 gl_indexed_ivec3(GLenum name) {
  glm::ivec3 v;
  for (GLuint i = 0; i < 3; ++i) glGetIntegeri_v(name, i, &v[static_cast<int>(i)]);
  return v;
}

}  // namespace

bool software_renderer() {
  const std::string renderer = gl_string(GL_RENDERER);
  for (const char* name : {"llvmpipe", "softpipe", "swrast"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

Info query_info(const Context& context) {
  Info info;
  info.platform = platform_name(context.platform());
  info.device = context.description();
  info.vendor = gl_string(GL_VENDOR);
  info.renderer = gl_string(GL_RENDERER);
  info.version = gl_string(GL_VERSION);
  info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  info.major = gl_int(GL_MAJOR_VERSION);
  info.minor = gl_int(GL_MINOR_VERSION);
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  info.max_ssbo_block_bytes = block;
  info.max_ssbo_bindings = gl_int(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
  info.max_work_group_count = gl_indexed_ivec3(GL_MAX_COMPUTE_WORK_GROUP_COUNT);
  info.max_work_group_size = gl_indexed_ivec3(GL_MAX_COMPUTE_WORK_GROUP_SIZE);
  info.max_work_group_invocations = gl_int(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
  info.max_shared_memory_bytes = gl_int(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
  info.max_3d_texture_size = gl_int(GL_MAX_3D_TEXTURE_SIZE);
  if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
    // Reported in KiB.
    info.gpu_memory_total_bytes =
        std::int64_t(gl_int(GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX)) * 1024;
    info.gpu_memory_available_bytes =
        std::int64_t(gl_int(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX)) * 1024;
  }
  info.gpu_timers = context.has_gpu_timers();
  return info;
}

}  // namespace voxspan::gl
