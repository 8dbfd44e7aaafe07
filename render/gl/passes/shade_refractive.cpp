#include "render/gl/passes/shade_refractive.h"

#include <algorithm>
#include <string>

#include "render/gl/bindings.h"
#include "render/gl/passes/dispatch.h"
#include "render/gl/uniforms.h"

namespace voxspan {
namespace {

constexpr const char* kShader = "render/gl/passes/shade_refractive.comp";
constexpr std::size_t kRayRecordBytes = 96;  // RayRecord in shade_refractive.comp
constexpr int kBlock = 8;                    // VX_BLOCK in render/model/column_march.glsl

// shade_refractive.comp's own buffers, after the shaded image.
enum Binding : GLuint { kRays = binding::kShadeEnd, kMarchTally, kBlockBounds };

std::string binding_defines() {
  return binding::shade_defines() + gl::defines({{"RAYS_BINDING", kRays},
                                                 {"MARCH_TALLY_BINDING", kMarchTally},
                                                 {"BLOCK_BOUNDS_BINDING", kBlockBounds}});
}

}  // namespace

ShadeRefractivePass::ShadeRefractivePass(const gl::ShaderLibrary& shaders)
    : begin_(shaders.compute(kShader, binding_defines() + "#define REFRACT_BEGIN 1")),
      march_(shaders.compute(kShader, binding_defines() + "#define REFRACT_MARCH 1")),
      resolve_(shaders.compute(kShader, binding_defines() + "#define REFRACT_RESOLVE 1")),
      active_(16) {}

RefractTally ShadeRefractivePass::run(const GpuSpanImage& image, const GpuSurfaces& surfaces,
                                      const model::ShadeUniforms& uniforms,
                                      const ShadeOptions& options, const gl::Buffer& backdrop,
                                      GpuFloatImage& out) {
  const std::size_t pixels = std::size_t(image.width()) * std::size_t(image.height());
  out.resize(image.width(), image.height());
  rays_.reserve(std::max<std::size_t>(16, pixels * kRayRecordBytes));
  const int blocks_x = (image.width() + kBlock - 1) / kBlock;
  const std::size_t blocks =
      std::size_t(blocks_x) * std::size_t((image.height() + kBlock - 1) / kBlock);
  blocks_.reserve(blocks * 16);  // four words per block (shade_refractive.comp)
  blocks_.clear(0, blocks * 16);
  const auto bind = [&] {
    surfaces.bind(image);
    gl::bind_storage({{out.buffer(), binding::kShadedImage},
                      {backdrop, binding::kBackdrop},
                      {rays_, kRays},
                      {active_, kMarchTally},
                      {blocks_, kBlockBounds}});
  };
  for (const gl::Program* p : {&begin_, &march_, &resolve_}) {
    set_grid_uniforms(*p, image.grid());
    set_shade_uniforms(*p, uniforms);
    p->set("u_blocks_x", blocks_x);
  }
  march_.set("u_march_budget", options.march_budget);
  active_.clear();
  bind();
  dispatch_threads(begin_, pixels);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::uint32_t most_spans = active_.read_array<std::uint32_t, 4>()[3];
  const int max_dispatches =
      refract_dispatch_limit(image.width(), image.height(), most_spans, options);
  RefractTally tally;
  std::int64_t events = 0, most_events = 0;
  std::uint32_t active = 1;
  while (active != 0 && tally.dispatches < max_dispatches) {
    active_.clear();
    bind();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    dispatch_threads(march_, pixels);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    const auto t = active_.read_array<std::uint32_t, 3>();
    active = t[0];
    events += t[1];
    most_events = std::max<std::int64_t>(most_events, t[2]);
    ++tally.dispatches;
  }
  tally.unfinished = active;
  tally.events = events;
  tally.most_events = most_events;
  bind();
  dispatch_threads(resolve_, pixels);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  return tally;
}

}  // namespace voxspan
