// The headless context: GL 4.5 core on whatever this machine has, and clear errors when a
// platform is forced that cannot work.
#include <epoxy/gl.h>

#include <cstdlib>
#include <string>

#include "render/gl/info.h"
#include "tests/render/gl/gl_fixture.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    setenv(name, value, 1);
  }
  ~ScopedEnv() { had_ ? setenv(name_, old_.c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

TEST(Context, GivesOpenGL45CoreOrNewer) {
  gl::Info info = gl::query_info(test::context());
  EXPECT_GE(info.major * 10 + info.minor, 45) << info.version;
  EXPECT_FALSE(info.renderer.empty());
  // GPU-NOTES: llvmpipe limits one shader-storage block to 128 MiB; NVIDIA to 2 GiB - 1.
  EXPECT_GE(info.max_ssbo_block_bytes, std::int64_t(128) << 20);
  EXPECT_GE(info.max_work_group_invocations, 1024);
  if (info.renderer.find("llvmpipe") != std::string::npos) {
    EXPECT_FALSE(info.gpu_timers);
  }
}

TEST(Context, PlatformNamesRoundTrip) {
  for (gl::Platform p : {gl::Platform::automatic, gl::Platform::nvidia, gl::Platform::device,
                         gl::Platform::surfaceless}) {
    gl::Platform parsed;
    ASSERT_TRUE(gl::parse_platform(gl::platform_name(p), parsed));
    EXPECT_EQ(parsed, p);
  }
  gl::Platform unused;
  EXPECT_FALSE(gl::parse_platform("vulkan", unused));
}

TEST(Context, UnknownPlatformInEnvironmentIsOneClearError) {
  ScopedEnv env("VOXSPAN_GL_PLATFORM", "vulkan");
  try {
    gl::Context c;
    FAIL() << "a context was made for a platform that does not exist";
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("VOXSPAN_GL_PLATFORM=vulkan"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

// On a machine without an NVIDIA GPU, forcing it must fail with a message that says so; on a
// machine with one, the context must really be NVIDIA's.
TEST(Context, ForcedNvidiaIsNvidiaOrOneClearError) {
  gl::ContextOptions options;
  options.platform = gl::Platform::nvidia;
  try {
    gl::Context c(options);
    gl::Info info = gl::query_info(c);
    EXPECT_NE(info.vendor.find("NVIDIA"), std::string::npos) << info.vendor;
    test::context().make_current();
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("platform nvidia"), std::string::npos) << what;
    EXPECT_NE(what.find("NVIDIA"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
  test::context().make_current();
}

TEST(Context, ForcedSurfacelessGivesMesa) {
  gl::ContextOptions options;
  options.platform = gl::Platform::surfaceless;
  try {
    gl::Context c(options);
    EXPECT_EQ(c.platform(), gl::Platform::surfaceless);
    EXPECT_GE(epoxy_gl_version(), 45);
  } catch (const Error& e) {
    // Only acceptable where Mesa is absent (an NVIDIA-only bundle); the message must say so.
    EXPECT_NE(std::string(e.what()).find("surfaceless"), std::string::npos) << e.what();
  }
  test::context().make_current();
}

}  // namespace
}  // namespace voxspan
