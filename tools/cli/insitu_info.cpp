// insitu-info: which renderer the library would use here, its GL version, the limits that size
// our buffers and dispatches, and the library's version.
//   insitu-info [--backend auto|gl|cpu] [--platform auto|nvidia|device|surfaceless]
// Exit status 0 on success; 1 with one error line when no context can be made.
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "render/backend.h"
#include "render/gl/context.h"
#include "render/gl/info.h"
#include "tools/common/usage.h"
#include "voxspan/error.h"
#include "voxspan/version.h"

namespace {

std::string mib(std::int64_t bytes) { return std::to_string(bytes / (1024 * 1024)) + " MiB"; }

void print(const voxspan::gl::Info& i) {
  std::printf("platform        %s (%s)\n", i.platform.c_str(), i.device.c_str());
  std::printf("vendor          %s\n", i.vendor.c_str());
  std::printf("renderer        %s\n", i.renderer.c_str());
  std::printf("OpenGL          %d.%d core (%s)\n", i.major, i.minor, i.version.c_str());
  std::printf("GLSL            %s\n", i.glsl_version.c_str());
  std::printf("max SSBO block  %s (%lld bytes)\n", mib(i.max_ssbo_block_bytes).c_str(),
              static_cast<long long>(i.max_ssbo_block_bytes));
  std::printf("SSBO bindings   %d\n", i.max_ssbo_bindings);
  std::printf("work groups     count %d x %d x %d, size %d x %d x %d, %d invocations\n",
              i.max_work_group_count.x, i.max_work_group_count.y, i.max_work_group_count.z,
              i.max_work_group_size.x, i.max_work_group_size.y, i.max_work_group_size.z,
              i.max_work_group_invocations);
  std::printf("shared memory   %d KiB\n", i.max_shared_memory_bytes / 1024);
  std::printf("3D texture      %d texels per side\n", i.max_3d_texture_size);
  if (i.gpu_memory_total_bytes)
    std::printf("GPU memory      %s total, %s available\n", mib(*i.gpu_memory_total_bytes).c_str(),
                mib(i.gpu_memory_available_bytes.value_or(0)).c_str());
  else std::printf("GPU memory      not reported by the driver\n");
  std::printf("GPU timers      %s\n", i.gpu_timers ? "yes" : "no (wall clock after glFinish)");
}

constexpr char kUsage[] =
    "usage: insitu-info [--backend auto|gl|cpu] [--platform auto|nvidia|device|surfaceless]\n"
    "  VOXSPAN_GL_PLATFORM overrides --platform when set.\n";

}  // namespace

int main(int argc, char** argv) {
  voxspan::gl::ContextOptions options;
  voxspan::RenderBackend backend = voxspan::RenderBackend::automatic;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--help") || !std::strcmp(argv[a], "-h"))
      return voxspan::tools::print_usage(stdout, kUsage);
    if (!std::strcmp(argv[a], "--backend") && a + 1 < argc) {
      const auto b =
          voxspan::value_of<voxspan::RenderBackend>(voxspan::kRenderBackendNames, argv[++a]);
      if (!b) {
        std::fprintf(stderr,
                     "insitu-info: error: --backend %s is not a renderer (expected auto, gl or "
                     "cpu)\n",
                     argv[a]);
        return 2;
      }
      backend = *b;
      continue;
    }
    if (!std::strcmp(argv[a], "--platform") && a + 1 < argc) {
      if (!voxspan::gl::parse_platform(argv[++a], options.platform)) {
        std::fprintf(stderr,
                     "insitu-info: error: --platform %s is not a platform (expected "
                     "auto, nvidia, device or surfaceless)\n",
                     argv[a]);
        return 2;
      }
      continue;
    }
    return voxspan::tools::print_usage(stderr, kUsage);
  }
  try {
    // What a run would render with, then the GL context's facts where there is one.
    voxspan::BackendChoice choice = voxspan::choose_backend(backend, options);
    std::printf("voxspan         %s\n", voxspan::version());
    std::printf("renders with    %s\n", voxspan::describe(choice).c_str());
    if (!choice.context) {
      try {
        choice.context = std::make_unique<voxspan::gl::Context>(options);
      } catch (const voxspan::Error& e) {
        std::printf("OpenGL          none here (%s)\n", e.what());
        return 0;
      }
    }
    print(voxspan::gl::query_info(*choice.context));
    return 0;
  } catch (const voxspan::Error& e) {
    std::fprintf(stderr, "insitu-info: error: %s\n", e.what());
    return 1;
  }
}
