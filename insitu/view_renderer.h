// insitu/view_renderer.h - one view of one render step, from boundary particles and cell
// states to a linear RGBA picture in host memory: the one place where the runtime calls the
// renderer (paper 001: voxelize, sec. 3.1-4.4; surfaces, filter, normals and shading,
// sec. 3.3-3.6), and reads the picture back for the PNG writer.
//
// Reads: the boundary spheres and cell states of the step, the view's settings, the fluid's
// box (where the ground plane of the environment goes). Writes: ViewImage (its storage is
// reused from step to step; GPU buffers are the renderer's and are reused too).
// Costs: the renderer's passes plus one read-back of width x height x 16 bytes.
#pragma once

#include <span>
#include <vector>

#include "insitu/config.h"
#include "insitu/view_framing.h"
#include "render/camera.h"
#include "render/frame_stats.h"
#include "render/gl/pass_timer.h"
#include "render/gl/shader_library.h"
#include "render/span_image.h"
#include "render/voxelizer.h"
#include "voxspan/cell_states.h"

namespace voxspan {

// Linear RGBA floats, row 0 at the top.
struct ViewImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4
};

// What a view's settings become for the renderer; made once per view.
struct ViewRenderSettings {
  VoxelizeOptions voxelize;
  ShadingMode shading = ShadingMode::translucent;
  bool deep_ao = false;
  double filter_radius = 0;  // world units
  Vec3d absorption{0.45, 0.12, 0.05};
  double ior = 1.33;
  int bounces = 3;
  Vec3d up{0, 0, 1};  // the environment's up: the camera's
};

// `spacing` is the particles' rest spacing (world units): gap bridging and the filter radius
// default to it when the view says `auto`. Throws voxspan::Error naming a bad setting.
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
  Voxelizer voxelizer_;
  std::vector<PixelSpans> pixels_;  // read-back of the span image's pixel records
};

}  // namespace voxspan
