#include "tests/render/gl/gl_fixture.h"

namespace voxspan::test {

gl::Context& context() {
  static gl::Context c;
  return c;
}

const gl::ShaderLibrary& shaders() {
  context();
  static gl::ShaderLibrary library{embedded::test_shaders()};
  return library;
}

}  // namespace voxspan::test
