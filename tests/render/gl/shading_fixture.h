// Shared pieces of the shading tests: one Renderer on the test binary's one context (program
// compiles are slow on llvmpipe), span images made by hand or uploaded, and the passes after
// the voxelization run on them with their results read back.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "render/float_image.h"
#include "render/gl/renderer.h"
#include "render/span_image.h"
#include "tests/render/gl/gl_fixture.h"
#include "tools/scenes/accuracy_scenes.h"  // test_shading

namespace voxspan::test {

Renderer& renderer();

// A w x h image in a frame with depths [near, far]; `columns[x + y * w]` lists each pixel's
// spans, in depth order.
SpanImage hand_made(int width, int height, const std::vector<std::vector<Span>>& columns,
                    double near = 0.5, double far = 10);

// The angle between two directions, degrees, from their chord (acos of a float dot product
// cannot resolve thousandths of a degree).
double degrees_between(glm::vec3 a, glm::vec3 b);

// What the GPU made of a span image, read back.
struct GpuResult {
  FloatImage image;
  std::vector<glm::uvec2> links, normals;
  std::vector<glm::vec2> depths;  // surface depths (filtered when the filter ran)
  std::vector<float> ao;
  FrameStats stats;
};

// Uploads `spans` and runs connect, filter, normals, (deep AO) and the shading on the GPU.
GpuResult shade_on_gpu(const SpanImage& spans, const SurfaceOptions& surfaces,
                       const ShadeOptions& shade);

}  // namespace voxspan::test
