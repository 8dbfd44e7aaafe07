#include "insitu/views/surface_view.h"

#include "insitu/views/surface_colors.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "insitu/views/view.h"
#include "insitu/views/view_environment.h"
#include "render/backend.h"
#include "render/frame_origin.h"
#include "render/stat_names.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

// What a frame of the view follows, made once; the renderer's own settings (its memory budget)
// are given when it is made.
struct FrameOptions {
  SpanOptions spans;
  SurfaceOptions surfaces;
  ShadeOptions shade;
};

FrameOptions frame_options(const SurfaceSettings& view, double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw make_error("view ", view.name, ": the particle spacing (", spacing,
                     ") is needed for the view's automatic settings; set "
                     "classification.particle_spacing or pass it to the adapter");
  FrameOptions o;
  SpanOptions& v = o.spans;
  v.grid.alpha_degrees = view.alpha_degrees;
  v.grid.max_layers = view.max_layers;
  v.gap_bridging = view.gap.value_or(spacing);
  v.max_spans = static_cast<std::uint32_t>(view.max_spans);
  o.surfaces.filter_radius = view.filter_radius.value_or(spacing);
  // Folds (render/model/links.glsl): the main job's crest hides the water behind it three to
  // five spacings further on; below about two, the steps of a bumpy surface seen nearly edge-on
  // (cut there, its bumps go unfiltered: docs/benchmarks.md).
  o.surfaces.fold_step = 2.5 * spacing;
  ShadeOptions& shade = o.shade;
  shade.mode = view.shading;
  shade.deep_ao = view.deep_ao;
  shade.ao.radius = 4 * spacing;
  if (view.absorption) shade.material.absorption = vec(*view.absorption);
  shade.material.ior = view.ior;
  shade.bounces = view.bounces;
  shade.environment.ground_tile = view.ground_tile.value_or(12 * spacing);
  shade.environment.ground_light = vec(view.ground_light);
  shade.environment.ground_dark = vec(view.ground_dark);
  shade.environment.sky_zenith = vec(view.sky_zenith);
  shade.environment.sky_horizon = vec(view.sky_horizon);
  if (view.ground_height) shade.environment.ground_height = *view.ground_height;
  validate(v);
  validate(o.surfaces);
  validate(shade);
  return o;
}

void check_surface(yaml::MapReader& r, SurfaceSettings& v) {
  check_color_axis(r, v);
  if (r.has("max_layers") && v.max_layers % 32 != 0)
    r.checker().error(r.find("max_layers"), r.path("max_layers"),
                      "must be a multiple of 32 (a column's layers are stored in 32-bit words); "
                      "got " +
                          std::to_string(v.max_layers));
  if (v.absorption && ((*v.absorption)[0] < 0 || (*v.absorption)[1] < 0 || (*v.absorption)[2] < 0))
    r.checker().error(r.find("absorption"), r.path("absorption"), "must not be negative");
  for (auto [key, c] : {std::pair{"ground_light", v.ground_light},
                        {"ground_dark", v.ground_dark},
                        {"sky_zenith", v.sky_zenith},
                        {"sky_horizon", v.sky_horizon}})
    if (r.has(key) && (c[0] < 0 || c[1] < 0 || c[2] < 0))
      r.checker().error(r.find(key), r.path(key), "a colour must not be negative");
}

const schema::Section<SliceField>& slice_section() {
  static const schema::Section<SliceField> s{
      "views[i].slice", slice_field_keys(),
      [](yaml::MapReader& r, SliceField& v) { check_slice_field(r, v); }};
  return s;
}

const schema::Section<SurfaceSettings>& surface_section() {
  using S = SurfaceSettings;
  static const schema::Section<S> s{
      "views[i]",
      view_keys<S>(
          "surface",
          schema::joined(
              schema::from_base<S>(color_by_keys(
                  "the attribute SPH-interpolated at the first surface that colours it (a "
                  "vector: its magnitude); empty: the shading's own colours",
                  "the picture's smallest and largest")),
              std::vector<schema::Key<S>>{
                  schema::choice("shading", &S::shading, kShadeModeNames,
                                 "shade pass ([ZD15] sec. 3.5)"),
                  schema::flag("deep_ao", &S::deep_ao,
                               "deep ambient occlusion over all stored layers (sec. 3.6)"),
                  schema::number(
                      "layer_angle", &S::alpha_degrees, schema::above_up_to(0, 45),
                      "normal-angle resolution of the depth layers, degrees: the paper's "
                      "alpha (sec. 4.2; 14 degrees gives ~16 000 layers there)"),
                  schema::number_or_auto("gap", &S::gap, schema::at_least(0),
                                         "gap-bridging distance, world units (sec. 3.2, "
                                         "4.4); `auto` = the particle spacing"),
                  schema::integer("max_spans", &S::max_spans, 0, 1 << 20,
                                  "stored spans per pixel, 0: no cap; over the cap the last "
                                  "span is extended and its empty length recorded (sec. 3.1)"),
                  schema::number_or_auto(
                      "filter_radius", &S::filter_radius, schema::at_least(0),
                      "world radius of the depth filter (sec. 3.4, 4.6), on the screen at most "
                      "1/" +
                          std::to_string(std::lround(1 / SurfaceOptions{}.max_screen_radius)) +
                          " of the picture's height; 0 = off; `auto` = the particle spacing"),
                  schema::integer("max_layers", &S::max_layers, 32, 1 << 20,
                                  "cap on depth layers, a multiple of 32"),
                  schema::vec3_or_auto(
                      "absorption", &S::absorption,
                      "Beer-Lambert absorption per world unit, RGB, >= 0; `auto` = "
                      "clear water's tint, scaled to the fluid: red keeps a tenth "
                      "through the smallest side of the fluid's box at the first "
                      "render step (kept for the run)"),
                  schema::number("ior", &S::ior, schema::between(1, 4),
                                 "refractive index (refractive mode)"),
                  schema::integer("bounces", &S::bounces, 0, 16,
                                  "refraction/reflection bounces (refractive mode)"),
                  schema::number_or_auto(
                      "ground_height", &S::ground_height, schema::any_number(),
                      "height of the ground plane along the camera's `up`, world "
                      "units; `auto` = the floor under the fluid, half a spacing "
                      "under its lowest spheres (each step)"),
                  schema::number_or_auto("ground_tile", &S::ground_tile, schema::above(0),
                                         "side of the ground's checker, world units; `auto` = 12 "
                                         "particle spacings"),
                  schema::vec3("ground_light", &S::ground_light,
                               "the ground's light squares, linear RGB"),
                  schema::vec3("ground_dark", &S::ground_dark,
                               "the ground's dark squares, linear RGB"),
                  schema::vec3("sky_zenith", &S::sky_zenith, "the sky overhead, linear RGB"),
                  schema::vec3("sky_horizon", &S::sky_horizon,
                               "the sky at the horizon (and the ground's fade into the distance), "
                               "linear RGB"),
                  schema::map<S, SliceField>(
                      "slice", &S::slice, slice_section(),
                      "an SPH slice plane drawn where it lies in front of the "
                      "first surface",
                      true)
                      .only_when([](const S& v) { return !v.slice.quantity.empty(); }),
                  schema::map<S, ScenerySettings>(
                      "scenery", &S::scenery, scenery_section(),
                      "the solver's walls and obstacles as opaque solids")})),
      check_surface};
  return s;
}

class SurfaceView final : public View {
 public:
  SurfaceView(const SurfaceSettings& s, const ViewContext& c)
      : settings_(s),
        options_(frame_options(s, c.particle_spacing)),
        renderer_(make_surface_renderer(
            c.backend, c.shaders, static_cast<std::size_t>(c.renderer.gpu_memory_mib * kMiB))),
        stages_(c.span_stages
                    ? c.span_stages({options_.spans.gap_bridging, options_.spans.max_spans,
                                     c.backend == RenderBackend::cpu})
                    : std::vector<std::unique_ptr<SpanStage>>{}),
        combine_ranks_(c.combine_ranks),
        comm_(c.comm),
        read_later_(c.renderer.readback),
        spacing_(c.particle_spacing),
        scenery_(s.scenery, c.particle_spacing) {
    if (!s.slice.quantity.empty())
      slice_.emplace(s.slice, s.name, s.key_path("slice"), spacing_, c.comm);
    if (!s.color_by.empty()) colors_.emplace(s, s.name, s.key_path("color_by"), spacing_, c.comm);
  }

  bool render(const ViewStep& step, Recorder& recorder, ViewProducts& out) override {
    FrameOptions& o = step_options_;
    o = options_;
    if (!settings_.absorption && !auto_absorption_ && !step.fluid_box.empty())
      auto_absorption_ =
          Material::water_absorption(std::max(smallest_side(step.fluid_box), spacing_));
    if (auto_absorption_) o.shade.material.absorption = *auto_absorption_;
    // The environment's up is the camera's (a 2D fluid's camera has its plane's upward axis up).
    o.shade.environment.up = step.camera.up;
    o.shade.environment.sun_direction = sun_direction(step.camera.up);
    if (!step.fluid_box.empty() && !settings_.ground_height)
      // Under the framed box: with scenery framed, under the tank rather than in its floor.
      o.shade.environment.rest_on_floor(
          floor_height(step.fluid_box, o.shade.environment.up, spacing_), spacing_);
    o.shade.environment.wall_contact = spacing_;
    // Options are checked before any work, so a bad one costs nothing.
    validate(o.surfaces);
    validate(o.shade);
    // With stages, every span goes on (a merge needs them all); the stages apply the cap.
    if (!stages_.empty()) o.spans.max_spans = 0;
    o.spans.combine_ranks = combine_ranks_;
    if (!slice_ && !colors_) return render_surfaces(step, step.needs, recorder, out);
    if (step.data.particles == nullptr)
      throw make_error(slice_ ? "slice" : "color_by", ": the step has no particles");
    // The slice stands in front of the cast's first surface; the colours read the shaded one
    // (render_colored), so without a slice only the depth output asks for the cast's.
    ViewNeeds with_depth = step.needs;
    with_depth.first_hit_depth = step.needs.first_hit_depth || slice_.has_value();
    if (!slice_) return render_colored(step, with_depth, recorder, out);
    {
      auto t = recorder.host(pass::slice_sum);  // collective: before anything that may fail
      slice_->interpolate(*step.data.particles, step.fluid_box, step.flat_axis, step.camera.up,
                          step.data.step, settings_.width, settings_.height);
    }
    if (!render_colored(step, with_depth, recorder, out)) return false;
    auto t = recorder.host(pass::slice_draw);
    view_depth_from_distances(step.camera, out.first_hit_depth, depth_);
    slice_->draw_in_view(step.camera, depth_, out.picture, BarSide::right);
    // The depth output sees the plane where it shows.
    if (step.needs.first_hit_depth)
      distances_from_view_depth(step.camera, depth_, out.first_hit_depth);
    return true;
  }

  bool draws_scenery() const override { return settings_.scenery.draw; }

  LegendMargins framing_margins() const override {
    const int w = settings_.width, h = settings_.height;
    LegendMargins m;
    if (slice_) m = slice_->bar_margins(w, h, BarSide::right);
    if (colors_) m = covering(m, colors_->bar_margins(w, h, colors_bar_side()));
    return m;
  }

  std::string description() const override {
    return std::string(shade_mode_name(settings_.shading)) +
           (colors_ ? " by " + settings_.color_by : std::string()) + " " +
           std::to_string(settings_.width) + "x" + std::to_string(settings_.height);
  }

 private:
  // The slice's colour bar goes at the right, the surface colours' then at the left.
  BarSide colors_bar_side() const { return slice_ ? BarSide::left : BarSide::right; }

  // render_surfaces, then with color_by the shaded first surface coloured: the sums are
  // collective, so a process that failed to shade still takes part and all ranks throw together.
  bool render_colored(const ViewStep& step, const ViewNeeds& needs, Recorder& recorder,
                      ViewProducts& out) {
    if (!colors_) return render_surfaces(step, needs, recorder, out);
    bool shown = false;
    std::string failure;
    try {
      shown = render_surfaces(step, needs, recorder, out);
    } catch (const std::exception& e) {
      if (comm_ == nullptr) throw;
      failure = e.what();
    }
    // The colours sit on the surface the picture shows: its filtered depths give them smooth
    // normals (the cast's first entries are the spheres' bumps: a lattice of dots).
    if (shown) renderer_->first_hit(recorder, shaded_hits_, HitSurface::shaded);
    {
      auto t = recorder.host(pass::color_sum);
      colors_->sample(*step.data.particles, step.camera, shown ? &shaded_hits_ : nullptr, failure);
    }
    if (!shown) return false;
    auto t = recorder.host(pass::color_draw);
    colors_->paint(step_options_.shade, out.picture, colors_bar_side());
    return true;
  }

  // The span image, through the stages, shaded; the products `needs` asks for. False where this
  // process has nothing to shade (an MPI rank other than the root).
  bool render_surfaces(const ViewStep& step, const ViewNeeds& needs, Recorder& recorder,
                       ViewProducts& out) {
    const FrameOptions& o = step_options_;
    if (!through_stages(step, o.spans, recorder)) return false;
    const Backdrop* backdrop = nullptr;
    if (step.scenery != nullptr) {
      const Scenery& s = *step.scenery;
      // In world coordinates, as the scenery is: its depths are the same in any frame.
      backdrop = scenery_.backdrop(step.camera, s.spheres, s.version, s.box, o.shade, recorder);
    }
    renderer_->use_backdrop(backdrop, recorder);
    // The fluid is shaded in its spheres' frame (StepData::origin), the ground where the world
    // has it.
    ShadeOptions shade = o.shade;
    shade.environment = FrameOrigin::of(step.data.origin).environment(o.shade.environment);
    // The pixels may land later unless this thread draws on them next (a slice, colours), and
    // as 8-bit sRGB where that is all the step's readers take.
    const bool draws = slice_ || colors_;
    const ReadLater when = draws ? ReadLater::never : read_later_;
    out.picture_is_srgb8 = !draws && needs.srgb8_picture() && renderer_->packs_srgb8(when);
    out.pending_picture =
        out.picture_is_srgb8
            ? renderer_->shade_srgb8_later(o.surfaces, shade, recorder, out.srgb8_picture, when)
            : renderer_->shade_later(o.surfaces, shade, recorder, out.picture, when);
    if (needs.first_hit_depth)
      renderer_->first_hit(recorder, out.first_hit_depth, HitSurface::cast);
    // No copy here: the outputs copy what they keep.
    out.shaded_spans =
        needs.spans ? &renderer_->host_spans(pass::span_readback, recorder) : nullptr;
    return true;
  }

  // The renderer's span image through the view's stages, which take part even where this process
  // failed to make it, and then throw for every one. False where a stage leaves nothing here.
  bool through_stages(const ViewStep& step, const SpanOptions& spans, Recorder& recorder) {
    std::string failure;
    bool made = false;
    try {
      // The spheres are measured from the step's origin: the camera and the cell grid with them
      // (in double). Spans and depths do not change under the translation.
      const FrameOrigin frame = FrameOrigin::of(step.data.origin);
      renderer_->make_spans(frame.camera(step.camera), step.data.boundary,
                            frame.cells(step.data.cells), spans, recorder);
      made = true;
    } catch (const std::exception& e) {
      if (stages_.empty()) throw;
      failure = e.what();
    }
    if (stages_.empty()) return true;
    const SpanImage* image =
        made ? &renderer_->host_spans(pass::composite_download, recorder) : nullptr;
    for (const std::unique_ptr<SpanStage>& stage : stages_)
      image = stage->run(image, failure, recorder);
    if (image == nullptr) return false;
    renderer_->use_spans(*image, pass::composite_upload, recorder);
    return true;
  }

  const SurfaceSettings settings_;
  const FrameOptions options_;  // made once; only the ground follows the fluid
  FrameOptions step_options_;
  std::unique_ptr<SurfaceRenderer> renderer_;
  std::vector<std::unique_ptr<SpanStage>> stages_;
  DepthRangeCombine combine_ranks_;
  Communicator* const comm_;  // null in one process
  const ReadLater read_later_;
  const double spacing_;
  std::optional<glm::dvec3> auto_absorption_;  // absorption: auto, fixed at the first box
  std::optional<SliceLayer> slice_;
  std::optional<SurfaceColors> colors_;
  std::vector<float> depth_;  // the surface's view depth per pixel, then the slice's
  FloatImage shaded_hits_;    // color_by: the shaded surface's first-hit distances
  SceneryLayer scenery_;
};

}  // namespace

ViewKind surface_view_kind() {
  return view_kind<SurfaceSettings, SurfaceView>("surface", surface_section(), [] {
    return part_reference("slice", "surface", slice_section()) +
           "\nIts `plane` is a `views[i].plane` (kind `slice`).\n" +
           part_reference("scenery", "surface", scenery_section());
  });
}

}  // namespace voxspan
