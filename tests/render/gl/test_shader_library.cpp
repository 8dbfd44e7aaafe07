// Embedded shaders: includes expand once, compile errors name the file.
#include <string>
#include <vector>

#include "tests/render/gl/gl_fixture.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

TEST(ShaderLibrary, ExpandsIncludesWithLineMarkers) {
  std::vector<std::string> files;
  std::string src = test::shaders().compose("tests/render/gl/atomic_or.comp", "#define X 1", files);
  EXPECT_TRUE(src.starts_with("#version 450 core\n#define X 1\n")) << src;
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], "tests/render/gl/atomic_or.comp");
  EXPECT_EQ(files[1], "tests/render/gl/bit_range.glsl");
  EXPECT_NE(src.find("void set_bit_range"), std::string::npos);
  EXPECT_EQ(src.find("#include"), std::string::npos);
  EXPECT_NE(src.find("#line 1 1\n"), std::string::npos);
}

TEST(ShaderLibrary, UnknownShaderIsAnError) {
  EXPECT_THROW(test::shaders().source("render/gl/passes/nope.comp"), Error);
}

TEST(ShaderLibrary, CompileErrorNamesTheFile) {
  try {
    test::shaders().compute("tests/render/gl/broken.comp");
    FAIL() << "a broken shader compiled";
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("compiling tests/render/gl/broken.comp failed"), std::string::npos) << what;
    EXPECT_NE(what.find("file 0: tests/render/gl/broken.comp"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace voxspan
