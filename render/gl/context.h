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

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "render/enum_names.h"

namespace voxspan::gl {

class ReadbackStaging;

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
// Whether EGL lists devices and every one is Mesa's software device (EGL_MESA_device_software:
// llvmpipe), asked of EGL without making a display or a context: the automatic renderer's
// choice then needs no GL context (whose llvmpipe start-up costs time and memory, and raises
// floating-point exceptions a solver built to trap them dies of).
bool only_software_devices();

struct ContextOptions {
  Platform platform = Platform::automatic;
  // A debug context: GL checks every call and reports through the logger synchronously, the
  // driver's performance notes as warnings (else at the debug level, counted).
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

  // The buffer the host's reads go through (render/gl/objects.h), current with the context.
  ReadbackStaging& staging() { return *staging_; }

  // A message of the driver's (GL_KHR_debug), to the logger at its level; from any thread.
  void driver_message(unsigned type, unsigned id, unsigned severity, std::string_view text);

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  Platform platform_ = Platform::automatic;
  std::string description_;
  bool has_gpu_timers_ = false;
  bool debug_ = false;
  std::unique_ptr<ReadbackStaging> staging_;
  // Driver notes of type performance or other left at the debug level (NVIDIA sends one per
  // buffer it moves): summed, said once when the context goes.
  std::atomic<std::uint64_t> quiet_notes_{0};
};

}  // namespace voxspan::gl
