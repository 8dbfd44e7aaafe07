// insitu/views/view.h - what a view is to the runtime: a kind of picture made from a render
// step's particles and cell states with the view's own camera. The runtime frames the camera
// (insitu/views/view_framing.h) and hands the step over; the view renders with its kind's
// stages and leaves its products (the picture; a depth image when an output asks) in host
// memory. Each kind is one file here and one line in insitu/runtime/registry.cpp
// (docs/design.md, "A new view kind").
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/parallel/communicator.h"
#include "insitu/parallel/span_merge.h"
#include "insitu/views/legend.h"
#include "insitu/views/scenery.h"
#include "insitu/views/view_framing.h"
#include "insitu/views/view_products.h"
#include "render/camera.h"
#include "render/float_image.h"
#include "render/gl/shader_library.h"
#include "render/recorder.h"
#include "render/surface_renderer.h"
#include "voxspan/adapter.h"

namespace voxspan {

// A stage between the span image and the surfaces of a span-image view: it takes the step's
// span image (in host memory) and gives back the one the surfaces are built from (the same one,
// or another: the composite of every rank's), or null when this process has nothing to shade (a
// rank other than the root). Stages run in order. A stage sees every span found (the view makes
// its spans without a cap when it has stages) and applies the view's cap itself
// (MergeSettings). `spans` is null when this process failed to make its spans (`failure` says
// why): a stage that spans processes must still take part, and throws voxspan::Error, naming
// the first rank that failed, when any did.
class SpanStage {
 public:
  virtual ~SpanStage() = default;
  virtual const SpanImage* run(const SpanImage* spans, const std::string& failure,
                               Recorder& recorder) = 0;
};

// Compositing across MPI ranks, in every view that runs it: the exchanges and the merge, and the
// bytes this rank sent for them; the GL renderer's transfers around a view's stages: its span
// image read back before them, their result uploaded after (the CPU renderer's images are in
// host memory).
namespace pass {
inline constexpr StatName composite{"composite"};
inline constexpr StatName composite_download{"composite_download"};
inline constexpr StatName composite_upload{"composite_upload"};
}  // namespace pass
namespace counter {
inline constexpr StatName composite_bytes_sent{"composite.bytes_sent"};
}  // namespace counter

// What a view is made with.
struct ViewContext {
  const gl::ShaderLibrary& shaders;  // the GL renderer's (unused by the CPU one)
  const RendererConfig& renderer;
  RenderBackend backend;        // resolved: gl or cpu
  double particle_spacing = 0;  // the solver's rest spacing; 0 when unknown
  // The stages a span-image view runs between its voxelization and its surfaces, made for its
  // gap bridging and span cap (none in a single process: then it is empty).
  std::function<std::vector<std::unique_ptr<SpanStage>>(const MergeSettings&)> span_stages;
  // Makes every process fit the same perspective grid (empty in a single process).
  DepthRangeCombine combine_ranks;
  // The job's ranks, for views that combine their parts themselves (null in one process).
  Communicator* comm = nullptr;
};

struct ViewStep {
  const StepData& data;
  const Camera& camera;
  const Bounds& fluid_box;  // the box the framing follows (the ground lies under it)
  ViewNeeds needs;          // what the due outputs want beyond the picture
  // The same step again from another camera (an orbit of outputs.cinema): what follows the
  // steps (trails) does not advance.
  bool again = false;
  const Scenery* scenery = nullptr;  // the solver's walls (null: none)
  // The axis a 2D run's particles lie flat along (step_scene.h), -1 for a 3D fluid: slices
  // interpolate such a run with the 2D kernel.
  int flat_axis = -1;
};

class View {
 public:
  virtual ~View() = default;
  // Renders the step into `out`; false when this process has no picture to show (an MPI rank
  // other than the root: the picture is made where the ranks' parts meet). Throws
  // voxspan::Error on bad input or a memory budget too small (the step fails, the run goes on).
  virtual bool render(const ViewStep& step, Recorder& recorder, ViewProducts& out) = 0;
  // A few words for the start-up line: "translucent 640x360".
  virtual std::string description() const = 0;
  // Whether the view draws the solver's scenery, so that automatic framing takes it in.
  virtual bool draws_scenery() const { return false; }
  // What the view's legends cover along the picture's edges, which automatic framing keeps the
  // fluid out of (a 2D view lays out its own picture: none).
  virtual LegendMargins framing_margins() const { return {}; }
};

struct ViewKind {
  ViewConfigKind config;
  std::function<std::unique_ptr<View>(const ViewSettings&, const ViewContext&)> make;
};

// The table of a kind's nested map for its reference: `key` as the config writes it ("iso[k]").
template <class T>
std::string part_reference(std::string_view key, std::string_view kind,
                           const schema::Section<T>& part) {
  return "\n#### `views[i]." + std::string(key) + "` (kind `" + std::string(kind) + "`)\n\n" +
         part.reference();
}

// The kind `name` of settings S drawn by view V; `parts`, when given, appends the tables of its
// nested maps (part_reference) to the section's in the reference.
template <class S, class V>
ViewKind view_kind(std::string_view name, const schema::Section<S>& section,
                   std::function<std::string()> parts = {}) {
  ViewKind kind{config_kind<ViewSettings>(name, section),
                [](const ViewSettings& s, const ViewContext& c) -> std::unique_ptr<View> {
                  return std::make_unique<V>(dynamic_cast<const S&>(s), c);
                }};
  if (parts) kind.config.reference = [&section, parts] { return section.reference() + parts(); };
  return kind;
}

}  // namespace voxspan
