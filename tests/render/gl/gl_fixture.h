// One GL context for the whole test binary: contexts are expensive on llvmpipe, and the passes
// under test must leave no state behind for the next test anyway.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "render/gl/context.h"
#include "render/gl/embedded.h"
#include "render/gl/shader_library.h"

namespace voxspan::embedded {
std::span<const EmbeddedFile> test_shaders();
}

namespace voxspan::test {

// The shared context (made on first use) and a shader library with the test shaders.
gl::Context& context();
const gl::ShaderLibrary& shaders();

}  // namespace voxspan::test
