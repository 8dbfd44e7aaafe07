// tools/tool_args.h - what the rendering tools (bench_voxelize, bench_shading, render_pictures)
// share: the scene and image flags of their command lines, main()'s frame (--help, usage on a
// bad command line, one error line on failure), the renderer line their output starts with,
// and the median of timed frames.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "render/gl/context.h"
#include "render/gl/info.h"

namespace voxspan::tools {

struct SceneArgs {
  double particles = 1e5;
  double time = -1;  // < 0: the tool's default
  int width = 960, height = 540;
  double alpha = 14;  // normal-angle resolution of the layers, degrees
  gl::ContextOptions context;
};

enum class Flag { other, read, bad };

// Reads argv[i] when it is --particles N, --time T, --size WxH, --alpha DEG or --platform P,
// advancing i past its value: `read`, or `bad` when the value is missing or malformed (not a
// finite number, not a positive size, no such platform); `other` for any other argument.
inline Flag read_scene_flag(int argc, char** argv, int& i, SceneArgs& a) {
  const std::string k = argv[i];
  double* number = k == "--particles" ? &a.particles
                   : k == "--time"    ? &a.time
                   : k == "--alpha"   ? &a.alpha
                                      : nullptr;
  if (number == nullptr && k != "--size" && k != "--platform") return Flag::other;
  if (i + 1 >= argc) return Flag::bad;
  const char* value = argv[++i];
  if (k == "--platform") return gl::parse_platform(value, a.context.platform) ? Flag::read : Flag::bad;
  if (k == "--size") {
    char tail = 0;
    const bool ok = std::sscanf(value, "%dx%d%c", &a.width, &a.height, &tail) == 2;
    return ok && a.width > 0 && a.height > 0 ? Flag::read : Flag::bad;
  }
  char* end = nullptr;
  *number = std::strtod(value, &end);
  return end != value && *end == '\0' && std::isfinite(*number) ? Flag::read : Flag::bad;
}

// --help or -h anywhere prints the usage; a command line `parse` refuses prints it to stderr
// (exit 2); an exception from `run` is one line "name: error: what" (exit 1).
template <class Args, class Parse, class Run>
int tool_main(const char* name, int argc, char** argv, int (*usage)(FILE*), Parse parse, Run run) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") return usage(stdout);
  Args a;
  if (!parse(argc, argv, a)) return usage(stderr);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return 1;
  }
}

inline void print_renderer(const gl::Context& context) {
  const gl::Info info = gl::query_info(context);
  std::printf("renderer: %s (%s), GPU timers: %s\n", info.renderer.c_str(), info.version.c_str(),
              context.has_gpu_timers() ? "yes" : "no, glFinish + wall clock");
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace voxspan::tools
