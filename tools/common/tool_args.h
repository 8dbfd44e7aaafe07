// tools/common/tool_args.h - what the rendering tools (bench_voxelize, bench_shading,
// bench_composite, render_pictures) share: the scene and image flags of their command lines, the
// flags the benchmarks have, the reading of each tool's own flags and of lists and sizes, main()'s
// frame
// (--help, usage on a bad command line, one error line on failure), the renderer line their
// output starts with, and the median of timed frames.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "render/gl/context.h"
#include "render/enum_names.h"
#include "render/gl/info.h"
#include "tools/common/usage.h"

namespace voxspan::tools {

struct SceneArgs {
  double particles = 1e5;
  double time = -1;  // < 0: the tool's default
  int width = 960, height = 540;
  double alpha = 14;  // normal-angle resolution of the layers, degrees
  gl::ContextOptions context;
};

enum class Flag { other, read, bad };

// "WxH" (both positive) into width and height; false for anything else.
inline bool parse_size(const char* text, int& width, int& height) {
  char tail = 0;
  return std::sscanf(text, "%dx%d%c", &width, &height, &tail) == 2 && width > 0 && height > 0;
}

// The items of a comma-separated list: "a,b" gives {"a", "b"}.
inline std::vector<std::string> comma_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) items.push_back(item);
  return items;
}

// The values a comma-separated list of enum names gives, from an EnumName table: false when a
// name is not in it or the list is empty.
template <class E, std::size_t N>
bool read_names(const char* list, const EnumName<E> (&table)[N], std::vector<E>& out) {
  out.clear();
  for (const std::string& name : comma_list(list)) {
    const std::optional<E> value = value_of(table, name);
    if (!value) return false;
    out.push_back(*value);
  }
  return !out.empty();
}

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
  if (k == "--platform")
    return gl::parse_platform(value, a.context.platform) ? Flag::read : Flag::bad;
  if (k == "--size") return parse_size(value, a.width, a.height) ? Flag::read : Flag::bad;
  char* end = nullptr;
  *number = std::strtod(value, &end);
  return end != value && *end == '\0' && std::isfinite(*number) ? Flag::read : Flag::bad;
}

// A tool's own flag at argv[i]. `flag` sets a switch; `value` takes the argument after the flag
// and moves i past it: as text, or as a number read by atoi or atof (unchecked: a malformed
// number reads as 0; the scene flags are the checked ones). Both return false when argv[i] is
// another flag or its value is missing.
class Arg {
 public:
  Arg(int argc, char** argv, int& i) : argc_(argc), argv_(argv), i_(i) {}

  bool flag(const char* name, bool& on, bool set_to = true) {
    if (std::string(argv_[i_]) != name) return false;
    on = set_to;
    return true;
  }
  const char* value(const char* name) {
    if (std::string(argv_[i_]) != name || i_ + 1 >= argc_) return nullptr;
    return argv_[++i_];
  }
  template <class T> bool value(const char* name, T& v) {
    const char* text = value(name);
    if (text == nullptr) return false;
    if constexpr (std::is_same_v<T, int>) v = std::atoi(text);
    else if constexpr (std::is_same_v<T, double>) v = std::atof(text);
    else v = text;
    return true;
  }

 private:
  int argc_;
  char** argv_;
  int& i_;
};

// The flags the rendering benchmarks (bench_voxelize, bench_shading, bench_composite) have
// beyond the scene's.
struct BenchArgs : SceneArgs {
  int max_layers = 16384;      // the grid's layer cap
  int frames = 3;              // timed frames, after one warm-up; at least 1
  bool all_particles = false;  // voxelize every particle, no cell states
  bool json = false;           // each configuration's frame stats as JSON too
};

// Reads argv[i] when it is one of BenchArgs' flags; false for another.
inline bool read_bench_flag(Arg& arg, BenchArgs& a) {
  if (arg.value("--frames", a.frames)) {
    a.frames = std::max(1, a.frames);
    return true;
  }
  return arg.value("--max-layers", a.max_layers) || arg.flag("--all-particles", a.all_particles) ||
         arg.flag("--json", a.json);
}

// Reads a command line into a tool's Args (a SceneArgs): the scene flags, and every other
// argument through `own`, which returns false for one the tool does not know. False on a bad
// scene flag or an unknown argument.
template <class Args> bool read_args(int argc, char** argv, Args& a, bool (*own)(Arg&, Args&)) {
  for (int i = 1; i < argc; ++i) {
    const Flag shared = read_scene_flag(argc, argv, i, a);
    if (shared == Flag::bad) return false;
    if (shared == Flag::read) continue;
    Arg arg(argc, argv, i);
    if (!own(arg, a)) return false;
  }
  return true;
}

// --help or -h anywhere prints the usage; a command line `parse` refuses prints it to stderr
// (exit 2); an exception from `run` is one line "name: error: what" (exit 1).
template <class Args, class Parse, class Run>
int tool_main(const char* name, int argc, char** argv, const char* usage, Parse parse, Run run) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
      return print_usage(stdout, usage);
  Args a;
  if (!parse(argc, argv, a)) return print_usage(stderr, usage);
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
