// render/gl/context.h - a headless OpenGL 4.5+ core context through EGL, with or without a GPU.
//
// Platform choice (ContextOptions::platform, overridden by the environment variable
// VOXSPAN_GL_PLATFORM when it is set):
//   auto        an NVIDIA EGL device if there is one, else Mesa's surfaceless platform;
//   nvidia      the EGL device platform on an NVIDIA device (EGL_NV_device_cuda), or fail;
//   device      the EGL device platform on the first usable device, NVIDIA first;
//   surfaceless Mesa's surfaceless platform (llvmpipe when there is no GPU).
// When no context can be made, the constructor throws voxspan::Error with one line that says
// which platform was tried, what failed and what to install.
#pragma once

#include <string>
#include <string_view>

#include "render/enum_names.h"

namespace voxspan::gl {

enum class Platform { automatic, nvidia, device, surfaceless };
inline constexpr EnumName<Platform> kPlatformNames[] = {{"auto", Platform::automatic},
                                                        {"nvidia", Platform::nvidia},
                                                        {"device", Platform::device},
                                                        {"surfaceless", Platform::surfaceless}};

const char* platform_name(Platform platform);
// Accepts the names above; false for anything else.
bool parse_platform(std::string_view text, Platform& platform);
// The platform a Context made with `configured` tries: VOXSPAN_GL_PLATFORM when set, else
// `configured`. Throws voxspan::Error naming the variable when it holds no platform's name.
Platform requested_platform(Platform configured);

struct ContextOptions {
  Platform platform = Platform::automatic;
  // A debug context: GL checks every call and reports through the logger synchronously.
  // Also switched on by VOXSPAN_GL_DEBUG=1.
  bool debug = false;
  // The EGL device to try first (device platforms), modulo the devices there are; -1: the
  // first (NVIDIA ones before others).
  int device = -1;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Makes the context current on the calling thread (the constructor does it once).
  void make_current() const;

  Platform platform() const { return platform_; }
  // e.g. "EGL device 0 (EGL_NV_device_cuda)" or "Mesa surfaceless".
  const std::string& description() const { return description_; }
  // GPU timer queries give real durations (false on llvmpipe, where they read ~1 ns).
  bool has_gpu_timers() const { return has_gpu_timers_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  Platform platform_ = Platform::automatic;
  std::string description_;
  bool has_gpu_timers_ = false;
};

}  // namespace voxspan::gl
