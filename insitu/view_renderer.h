// insitu/view_renderer.h - one view of one render step, from boundary particles and cell
// states to a linear RGBA picture in host memory: the one place where the runtime calls the
// renderer (paper 001: voxelize, sec. 3.1-4.4; surfaces, filter, normals and shading,
// sec. 3.3-3.6), and reads the picture back for the PNG writer.
//
// Reads: the boundary spheres and cell states of the step, the view's settings, the fluid's
// box (the ground plane of the environment lies under it). Writes: ViewImage (its storage is
// reused from step to step; GPU buffers are the renderer's and are reused too).
// Costs: the renderer's passes (render/README.md, render/SHADING.md) plus one read-back of
// width x height x 16 bytes.
#pragma once

#include <span>
#include <vector>

#include "insitu/config.h"
#include "insitu/view_framing.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "render/frame_stats.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/renderer.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// Linear RGBA floats, row 0 at the top.
using ViewImage = FloatImage;

// What a view's settings become for the renderer; made once per view. Only the ground plane's
// height follows the fluid from step to step (render()).
struct ViewRenderSettings {
  RenderOptions render;
};

// `spacing` is the particles' rest spacing (world units), the scale of what the view leaves
// `auto`: gap bridging and the filter radius one spacing, deep AO's radius four, the ground's
// checker twelve. The environment's up is the camera's, the sun above and to one side.
// Throws voxspan::Error naming a bad setting.
ViewRenderSettings view_render_settings(const ViewConfig& view, const RendererConfig& renderer,
                                        double spacing);

class ViewRenderer {
 public:
  // Needs a current GL context; compiles the passes once.
  explicit ViewRenderer(const gl::ShaderLibrary& shaders);

  // Renders and reads back one view. Throws voxspan::Error on bad options or a memory budget
  // too small for one tile row (the step fails, the run goes on).
  void render(const ViewRenderSettings& settings, const Camera& camera, const Bounds& fluid_box,
              std::span<const ParticleSphere> boundary, const CellStatesView& cells,
              gl::PassTimer& timer, FrameStats& stats, ViewImage& out);

 private:
  Renderer renderer_;
  RenderOptions options_;  // the settings' options with this step's ground
};

}  // namespace voxspan
