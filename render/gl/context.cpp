#include "render/gl/context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "render/gl/info.h"
#include "render/gl/objects.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan::gl {
namespace {

const char* egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
  }
}

std::string last_egl_error() {
  EGLint code = eglGetError();
  return egl_error_name(code);
}

bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view rest(list);
  while (!rest.empty()) {
    std::size_t end = rest.find(' ');
    if (rest.substr(0, end) == name) return true;
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  return false;
}

bool has_client_extension(std::string_view name) {
  return has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name);
}

struct Device {
  EGLDeviceEXT handle;
  int index;
  bool nvidia;
  bool software;
  std::string description;
};

// Every EGL device, NVIDIA ones first (GPU-NOTES: there is no /dev/dri on the GPU machines,
// so a device is recognised by its extensions, not by a DRM file).
std::vector<Device> enumerate_devices() {
  if (!has_client_extension("EGL_EXT_device_enumeration") &&
      !has_client_extension("EGL_EXT_device_base"))
    return {};
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
  eglQueryDevicesEXT(count, handles.data(), &count);
  std::vector<Device> devices;
  for (int i = 0; i < count; ++i) {
    const char* ext = eglQueryDeviceStringEXT(handles[static_cast<std::size_t>(i)], EGL_EXTENSIONS);
    bool nvidia = has_extension(ext, "EGL_NV_device_cuda");
    bool software = has_extension(ext, "EGL_MESA_device_software");
    std::string description = "EGL device " + std::to_string(i) +
                              (nvidia     ? " (EGL_NV_device_cuda)"
                               : software ? " (EGL_MESA_device_software)"
                                          : "");
    devices.push_back(
        {handles[static_cast<std::size_t>(i)], i, nvidia, software, std::move(description)});
  }
  std::stable_partition(devices.begin(), devices.end(), [](const Device& d) { return d.nvidia; });
  return devices;
}

// One attempt at a display: initialised, or an error string saying why not.
struct DisplayAttempt {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string description;
  std::string failure;
};

DisplayAttempt initialise(EGLDisplay display, std::string description) {
  DisplayAttempt attempt{EGL_NO_DISPLAY, std::move(description), {}};
  if (display == EGL_NO_DISPLAY) {
    attempt.failure = attempt.description + ": no display (" + last_egl_error() + ")";
    return attempt;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    attempt.failure = attempt.description + ": eglInitialize failed (" + last_egl_error() + ")";
    return attempt;
  }
  attempt.display = display;
  return attempt;
}

// `preferred` >= 0: that device of the candidates (modulo their number) is tried first, so
// that the ranks of an MPI job on one node spread over its GPUs.
DisplayAttempt open_device(bool nvidia_only, int preferred) {
  if (!has_client_extension("EGL_EXT_platform_device"))
    return {EGL_NO_DISPLAY, "EGL device platform",
            "EGL device platform: the EGL library lacks EGL_EXT_platform_device"};
  std::vector<Device> devices = enumerate_devices();
  if (nvidia_only) std::erase_if(devices, [](const Device& d) { return !d.nvidia; });
  if (preferred >= 0 && !devices.empty())
    std::rotate(devices.begin(), devices.begin() + preferred % int(devices.size()), devices.end());
  std::string failures;
  for (const Device& d : devices) {
    DisplayAttempt a = initialise(
        eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, d.handle, nullptr), d.description);
    if (a.display != EGL_NO_DISPLAY) return a;
    failures += (failures.empty() ? "" : "; ") + a.failure;
  }
  if (failures.empty())
    failures = nvidia_only ? "EGL device platform: no NVIDIA EGL device (EGL_NV_device_cuda); "
                             "is the NVIDIA driver with its EGL vendor library installed?"
                           : "EGL device platform: no EGL device found";
  return {EGL_NO_DISPLAY, "EGL device platform", failures};
}

DisplayAttempt open_surfaceless() {
  if (!has_client_extension("EGL_MESA_platform_surfaceless"))
    return {EGL_NO_DISPLAY, "Mesa surfaceless",
            "Mesa surfaceless platform: EGL_MESA_platform_surfaceless is missing "
            "(install libegl-mesa0 and libgl1-mesa-dri)"};
  return initialise(
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
      "Mesa surfaceless");
}

bool debug_requested(bool configured) {
  const char* env = std::getenv("VOXSPAN_GL_DEBUG");
  return configured || (env != nullptr && std::strcmp(env, "0") != 0 && *env != '\0');
}

void GLAPIENTRY debug_message(GLenum /*source*/, GLenum type, GLuint id, GLenum severity,
                              GLsizei length, const GLchar* message, const void* user) {
  std::string_view text(message, length < 0 ? std::strlen(message) : std::size_t(length));
  static_cast<Context*>(const_cast<void*>(user))->driver_message(type, id, severity, text);
}

// Tries the newest core version first: Mesa 22.3 refuses 4.6 with EGL_BAD_MATCH (GPU-NOTES).
EGLContext create_core_context(EGLDisplay display, bool debug, std::string& failure) {
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &n) || n == 0) {
      failure = "no EGL config for desktop OpenGL (" + last_egl_error() + ")";
      return EGL_NO_CONTEXT;
    }
  }
  for (EGLint minor : {6, 5}) {
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              minor,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG,
                              debug ? EGL_TRUE : EGL_FALSE,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (ctx != EGL_NO_CONTEXT) return ctx;
    failure = "no OpenGL 4.5 core context (" + last_egl_error() + ")";
  }
  return EGL_NO_CONTEXT;
}

}  // namespace

bool only_software_devices() {
  const std::vector<Device> devices = enumerate_devices();
  return !devices.empty() &&
         std::all_of(devices.begin(), devices.end(), [](const Device& d) { return d.software; });
}

Platform requested_platform(Platform configured) {
  const char* env = std::getenv("VOXSPAN_GL_PLATFORM");
  if (env == nullptr || *env == '\0') return configured;
  Platform p;
  if (!parse_platform(env, p))
    throw make_error("VOXSPAN_GL_PLATFORM=", env,
                     " is not a platform (expected auto, nvidia, device or surfaceless)");
  return p;
}

const char* platform_name(Platform platform) { return name_of(kPlatformNames, platform).data(); }

bool parse_platform(std::string_view text, Platform& platform) {
  const std::optional<Platform> p = value_of(kPlatformNames, text);
  if (p) platform = *p;
  return p.has_value();
}

Context::Context(const ContextOptions& options) {
  const Platform requested = requested_platform(options.platform);
  const bool debug = debug_requested(options.debug);
  debug_ = debug;

  DisplayAttempt attempt;
  switch (requested) {
    case Platform::nvidia: attempt = open_device(true, options.device); break;
    case Platform::device: attempt = open_device(false, options.device); break;
    case Platform::surfaceless: attempt = open_surfaceless(); break;
    case Platform::automatic: {
      attempt = open_device(true, options.device);
      if (attempt.display == EGL_NO_DISPLAY) {
        log_debug("no NVIDIA EGL device, using Mesa: ", attempt.failure);
        attempt = open_surfaceless();
      }
      break;
    }
  }
  if (attempt.display == EGL_NO_DISPLAY)
    throw make_error("cannot create an OpenGL context (platform ", platform_name(requested),
                     "): ", attempt.failure);
  platform_ =
      requested == Platform::automatic
          ? (attempt.description == "Mesa surfaceless" ? Platform::surfaceless : Platform::nvidia)
          : requested;
  description_ = attempt.description;

  // Without this, EGL may hand out an OpenGL ES context (the default API).
  if (!eglBindAPI(EGL_OPENGL_API))
    throw make_error("cannot create an OpenGL context on ", description_,
                     ": eglBindAPI(EGL_OPENGL_API) failed (", last_egl_error(), ")");
  std::string failure;
  EGLContext ctx = create_core_context(attempt.display, debug, failure);
  if (ctx == EGL_NO_CONTEXT)
    throw make_error("cannot create an OpenGL context on ", description_, ": ", failure);
  display_ = attempt.display;
  context_ = ctx;
  make_current();

  const int version = epoxy_gl_version();
  if (version < 45) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    throw make_error("cannot create an OpenGL context on ", description_, ": it offers OpenGL ",
                     version / 10, ".", version % 10, ", 4.5 core is needed");
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  // llvmpipe's timer queries read ~1 ns (GPU-NOTES): time with glFinish and a wall clock there.
  has_gpu_timers_ = renderer != nullptr && std::strstr(renderer, "llvmpipe") == nullptr &&
                    std::strstr(renderer, "softpipe") == nullptr;
  staging_ = std::make_unique<ReadbackStaging>(!software_renderer());
  set_current_staging(staging_.get());
  if (epoxy_has_gl_extension("GL_KHR_debug") || version >= 43) {
    glDebugMessageCallback(debug_message, this);
    glEnable(GL_DEBUG_OUTPUT);
    if (debug) glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  }
  log_info("OpenGL context on ", description_, ": ", renderer ? renderer : "?", ", GL ",
           reinterpret_cast<const char*>(glGetString(GL_VERSION)));
}

void Context::driver_message(unsigned type, unsigned id, unsigned severity, std::string_view text) {
  LogLevel level = LogLevel::debug;
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
    level = LogLevel::error;
  } else if (!debug_ && (type == GL_DEBUG_TYPE_PERFORMANCE || type == GL_DEBUG_TYPE_OTHER)) {
    ++quiet_notes_;  // advice about the driver's own choices, not a fault of the run's
  } else if (severity == GL_DEBUG_SEVERITY_MEDIUM) {
    level = LogLevel::warning;
  }
  log(level, "GL [", id, "] ", text);
}

Context::~Context() {
  if (context_ == nullptr) return;
  if (const std::uint64_t n = quiet_notes_.load(); n > 0)
    log_info("GL: ", n,
             " driver notes on performance left at the debug level (VOXSPAN_GL_DEBUG=1 "
             "shows them as warnings)");
  if (current_staging() == staging_.get()) set_current_staging(nullptr);
  // Its GL buffer goes with the context; deleted by hand only where the context is current.
  if (eglGetCurrentContext() != context_) staging_->forget();
  staging_.reset();
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  // No eglTerminate: an EGL display is a process-wide singleton per platform and device,
  // shared by every context on it; terminating it here would pull it from under the others.
  eglReleaseThread();
}

void Context::make_current() const {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw make_error("eglMakeCurrent failed on ", description_, " (", last_egl_error(), ")");
  set_current_staging(staging_.get());
}

}  // namespace voxspan::gl
