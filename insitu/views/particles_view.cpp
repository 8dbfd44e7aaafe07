#include "insitu/views/particles_view.h"

#include <algorithm>
#include <array>
#include <cstring>

#include "insitu/parallel/communicator.h"
#include "insitu/views/legend.h"
#include "insitu/views/trails.h"
#include "insitu/views/view.h"
#include "insitu/views/view_environment.h"
#include "insitu/views/view_keys.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

// The view's counts in the step's stats: the glyphs' (GlyphCounts), each under its name, and the
// trails drawn.
struct GlyphCount {
  StatName name;
  std::int64_t GlyphCounts::*count;
  bool cut_only = false;  // only where the slice cuts the glyphs
};
constexpr GlyphCount kGlyphCounts[] = {
    {StatName("glyphs_drawn"), &GlyphCounts::drawn},
    {StatName("glyphs_frustum_culled"), &GlyphCounts::frustum_culled},
    {StatName("glyphs_occlusion_culled"), &GlyphCounts::occlusion_culled},
    {StatName("glyphs_range_culled"), &GlyphCounts::range_culled},
    {StatName("glyphs_cut"), &GlyphCounts::cut, true},
    {StatName("glyph_cells_hidden"), &GlyphCounts::cells_hidden}};
constexpr StatName kTrails{"trails"};

const schema::Section<TrailSettings>& trails_section() {
  using T = TrailSettings;
  static const schema::Section<T> s{
      "views[i].trails",
      {schema::text("id", &T::id, "the attribute that tells the particles apart"),
       schema::integer("every", &T::every, std::int64_t(0), std::int64_t(1) << 53,
                       "trail the particles whose id is a multiple of it; 0: none"),
       schema::integers("ids", &T::ids, 0, std::int64_t(1) << 53,
                        "and the particles with these ids"),
       schema::integer("length", &T::length, std::int64_t(2), std::int64_t(4096),
                       "render steps a trail spans"),
       schema::vec3("colour", &T::colour, "linear RGB of the newest part")}};
  return s;
}

const schema::Section<ParticleSlice>& slice_section() {
  using P = ParticleSlice;
  static const schema::Section<P> s{
      "views[i].slice",
      [] {
        auto keys = schema::from_base<P>(slice_field_keys());
        keys.push_back(schema::flag("cut", &P::cut,
                                    "leave out the particles whose spheres reach the camera's side "
                                    "of the plane, so that it shows inside the fluid"));
        return keys;
      }(),
      [](yaml::MapReader& r, P& v) { check_slice_field(r, v); }};
  return s;
}

const schema::Section<ParticlesSettings>& particles_section() {
  using S = ParticlesSettings;
  static const schema::Section<S> s{
      "views[i]",
      view_keys<S>(
          "particles",
          schema::joined(
              schema::from_base<S>(
                  color_by_keys("the attribute that colours the glyphs (a vector: its "
                                "magnitude); empty: one colour",
                                "the drawn particles' smallest and largest")),
              std::vector<schema::Key<S>>{
                  schema::text("cull_by", &S::cull_by,
                               "the attribute cull_range tests; empty: color_by"),
                  schema::interval_or_auto("cull_range", &S::cull_range,
                                           "draw only the particles with cull_by in [min, max]; "
                                           "`auto`: all"),
                  schema::choice(
                      "draw", &S::draw, kGlyphSubsetNames,
                      "every owned particle, or only those of the cells that are not inner "
                      "(the fluid's shell)"),
                  schema::choice(
                      "culling",
                      &S::culling, kGlyphCullingNames,
                      "skip particles outside the view (`frustum`) and also cells hidden "
                      "behind drawn glyphs (`occlusion`); never changes a pixel"),
                  schema::number_or_auto(
                      "radius", &S::radius, schema::above(0),
                      "the glyphs' radius, world units; `auto` = half the particle "
                      "spacing (glyphs at rest touch)"),
                  schema::number("ambient_occlusion", &S::ambient_occlusion, schema::between(0, 1),
                                 "how much neighbouring glyphs darken a glyph (0: not at all)"),
                  schema::map<S, TrailSettings>(
                      "trails", &S::trails, trails_section(),
                      "paths of chosen particles over the last render steps"),
                  schema::map<S, ParticleSlice>("slice", &S::slice, slice_section(),
                                                "an SPH slice plane placed among the glyphs", true)
                      .only_when([](const S& v) { return !v.slice.quantity.empty(); }),
                  schema::map<S, ScenerySettings>(
                      "scenery", &S::scenery, scenery_section(),
                      "the solver's walls and obstacles as opaque solids among the glyphs")})),
      [](yaml::MapReader& r, S& v) {
        check_color_axis(r, v);
        if (v.cull_range && v.cull_by.empty() && v.color_by.empty())
          r.checker().error(r.find("cull_range"), r.path("cull_range"),
                            "needs `cull_by` or `color_by` (the attribute it tests)");
      }};
  return s;
}

// One pixel's nearest glyph as a rank sends it to the root.
struct GlyphHit {
  std::uint32_t pixel;
  float depth, value;
  float normal[3];
};
static_assert(sizeof(GlyphHit) == 24);

class ParticlesView final : public View {
 public:
  ParticlesView(const ParticlesSettings& s, const ViewContext& c)
      : settings_(s), spacing_(c.particle_spacing), comm_(c.comm), scenery_(s.scenery, spacing_) {
    if (!s.slice.quantity.empty())
      slice_.emplace(s.slice, s.name, s.key_path("slice"), spacing_, comm_);
  }

  bool render(const ViewStep& step, Recorder& recorder, ViewProducts& out) override {
    if (step.data.particles == nullptr) throw make_error("particles: the step has no particles");
    if (slice_) {
      auto t =
          recorder.host(pass::slice_sum);  // collective: before anything that may fail on one rank
      slice_->interpolate(*step.data.particles, step.fluid_box, step.flat_axis, step.camera.up,
                          step.data.step, settings_.width, settings_.height);
    }
    const GlyphSelection selection = selection_for(*step.data.particles, step.camera);
    std::string failure;
    try {
      auto t = recorder.host(pass::glyph_raster);
      rasterize_glyphs(*step.data.particles, step.data.cells, step.camera, selection, glyphs_);
      collect_trail_points(*step.data.particles, trail_choice(), trail_points_);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    if (comm_ != nullptr) {
      // Every rank takes part even when its own part failed; then all throw together.
      comm_->agree_or_throw(failure.empty(), failure);
      auto t = recorder.host(pass::glyph_composite);
      combine_ranks();
      gather_trail_points();
      if (!comm_->root()) return false;
    } else if (!failure.empty()) {
      throw Error(failure);
    }
    if (trail_choice().any() && !step.again) trails_.add_step(trail_points_);
    report(recorder);
    auto t = recorder.host(pass::glyph_shade);
    GlyphShading shading;
    shading.by_value = !settings_.color_by.empty();
    shading.map = settings_.color_map;
    shading.axis = color_axis_(settings_.range, glyphs_.values, settings_.scale);
    shading.ao_radius = 4 * selection.radius;
    shading.ao_strength = settings_.ambient_occlusion;
    shade_glyphs(glyphs_, step.camera, shading, out.picture);
    depth_ = glyphs_.depth;
    draw_walls(step, recorder, out.picture);
    if (slice_) {
      auto ts = recorder.host(pass::slice_draw);
      slice_->draw_in_view(step.camera, depth_, out.picture, slice_bar_side());
    }
    if (trail_choice().any()) {
      const Vec3d& c = settings_.trails.colour;
      trails_.draw(step.camera, depth_, glm::vec3(c[0], c[1], c[2]), out.picture);
      recorder.count(kTrails, std::int64_t(trails_.count()));
    }
    if (glyph_bar()) draw_color_bar(out.picture, settings_.color_map, shading.axis, bar_title_);
    // The glyphs' or the slice's distance per pixel, as the depth output writes it.
    if (step.needs.first_hit_depth)
      distances_from_view_depth(step.camera, depth_, out.first_hit_depth);
    out.shaded_spans = nullptr;
    return true;
  }

  bool draws_scenery() const override { return settings_.scenery.draw; }

  LegendMargins framing_margins() const override {
    const int w = settings_.width, h = settings_.height;
    LegendMargins m;
    if (glyph_bar()) m = color_bar_margins(w, h, BarSide::right);
    if (slice_) m = covering(m, slice_->bar_margins(w, h, slice_bar_side()));
    return m;
  }

  std::string description() const override {
    return "particles" +
           (settings_.color_by.empty() ? std::string() : " by " + settings_.color_by) + " " +
           std::to_string(settings_.width) + "x" + std::to_string(settings_.height);
  }

 private:
  // The glyphs' colour bar goes at the right, the slice's then at the left.
  bool glyph_bar() const { return settings_.legend && !settings_.color_by.empty(); }
  BarSide slice_bar_side() const { return glyph_bar() ? BarSide::left : BarSide::right; }

  GlyphSelection selection_for(const ParticleView& particles, const Camera& camera) const {
    GlyphSelection s;
    s.radius =
        settings_.radius.value_or(spacing_ > 0 ? 0.5 * spacing_ : particles.uniform_radius());
    if (!(s.radius > 0))
      throw make_error("view ", settings_.name,
                       ": radius is `auto` but neither the particle spacing nor a radius is "
                       "known; set it");
    s.color_by = settings_.color_by;
    s.cull_by = settings_.cull_by;
    s.color_by_key = color_by_key_;
    s.cull_by_key = cull_by_key_;
    s.cull_range = settings_.cull_range;
    s.boundary_only = settings_.draw == GlyphSubset::boundary;
    s.culling = settings_.culling;
    if (slice_ && settings_.slice.cut) {
      // The spheres reaching the eye's side of the plane: none pokes through it.
      const SlicePlane& p = slice_->plane();
      const double side = glm::dot(p.normal, camera.eye - p.origin) >= 0 ? 1 : -1;
      s.cut = GlyphCut{side * p.normal, side * glm::dot(p.normal, p.origin) - s.radius};
    }
    return s;
  }

  // The walls where they stand nearer than the glyphs (or where there are none), into the picture
  // and depth_, so that a slice, the trails and the depth output stand behind them too. Lit as a
  // surface view lights them, under the sun of the view's up; the view's own dark background,
  // not the environment, where no wall is.
  void draw_walls(const ViewStep& step, Recorder& recorder, FloatImage& picture) {
    if (step.scenery == nullptr) return;
    const Scenery& s = *step.scenery;
    ShadeOptions shade;
    shade.environment.up = step.camera.up;
    shade.environment.sun_direction = sun_direction(step.camera.up);
    const Backdrop* walls =
        scenery_.backdrop(step.camera, s.spheres, s.version, s.box, shade, recorder);
    if (walls == nullptr) return;
    for (int y = 0; y < walls->height; ++y)
      for (int x = 0; x < walls->width; ++x) {
        const std::size_t k = std::size_t(x) + std::size_t(y) * std::size_t(walls->width);
        const glm::vec4 w = walls->pixels[k];
        if (w.a == Backdrop::kNoWall || (depth_[k] > 0 && depth_[k] <= w.a)) continue;
        picture.set(x, y, glm::vec4(w.r, w.g, w.b, 1.0f));
        depth_[k] = w.a;
      }
  }

  // The nearest glyph of all ranks per pixel on the root (ties: the lower rank), the value range
  // and the counts of all. Collective.
  void combine_ranks() {
    span_over_ranks(*comm_, glyphs_.values);
    const auto fields = GlyphCounts::fields(glyphs_.counts);
    std::array<std::int64_t, fields.size()> counts;
    for (std::size_t k = 0; k < fields.size(); ++k) counts[k] = *fields[k];
    comm_->sum(counts);
    for (std::size_t k = 0; k < fields.size(); ++k) *fields[k] = counts[k];
    hits_.clear();
    for (std::size_t k = 0; k < glyphs_.nearest.size(); ++k)
      if (glyphs_.nearest[k] != kNoGlyph) {
        const glm::vec3 n = glyphs_.normal[k];
        hits_.push_back({std::uint32_t(k), glyphs_.depth[k], glyphs_.value[k], {n.x, n.y, n.z}});
      }
    const auto parts = comm_->gather(std::as_bytes(std::span(hits_)));
    if (!comm_->root()) return;
    std::fill(glyphs_.nearest.begin(), glyphs_.nearest.end(), kNoGlyph);
    for (std::size_t rank = 0; rank < parts.size(); ++rank)
      for (std::size_t b = 0; b + sizeof(GlyphHit) <= parts[rank].size(); b += sizeof(GlyphHit)) {
        GlyphHit h;
        std::memcpy(&h, parts[rank].data() + b, sizeof h);
        const std::uint64_t key = glyph_key(h.depth, rank);
        if (!(key < glyphs_.nearest[h.pixel])) continue;
        glyphs_.nearest[h.pixel] = key;
        glyphs_.depth[h.pixel] = h.depth;
        glyphs_.value[h.pixel] = h.value;
        glyphs_.normal[h.pixel] = glm::vec3(h.normal[0], h.normal[1], h.normal[2]);
      }
  }

  TrailChoice trail_choice() const {
    return {settings_.trails.id, trail_id_key_, settings_.trails.every, settings_.trails.ids};
  }

  // Every rank's trail points on the root, in rank order. Collective.
  void gather_trail_points() {
    if (!trail_choice().any()) return;
    const auto parts = comm_->gather(std::as_bytes(std::span(trail_points_)));
    if (!comm_->root()) return;
    trail_points_.clear();
    for (const auto& part : parts)
      for (std::size_t b = 0; b + sizeof(TrailPoint) <= part.size(); b += sizeof(TrailPoint)) {
        TrailPoint p;
        std::memcpy(&p, part.data() + b, sizeof p);
        trail_points_.push_back(p);
      }
  }

  void report(Recorder& recorder) const {
    const GlyphCounts& c = glyphs_.counts;
    const bool cut = settings_.slice.cut && slice_;
    for (const GlyphCount& k : kGlyphCounts)
      if (cut || !k.cut_only) recorder.count(k.name, c.*k.count);
  }

  const ParticlesSettings settings_;
  const std::string color_by_key_ = settings_.key_path("color_by");
  const std::string bar_title_ = color_bar_title(settings_.color_by, settings_.units);
  const std::string cull_by_key_ = settings_.key_path("cull_by");
  const std::string trail_id_key_ = settings_.key_path("trails.id");
  const double spacing_;
  Communicator* const comm_;  // null in one process
  const ViewColorAxis color_axis_{settings_.name, settings_.color_by,
                                  comm_ == nullptr || comm_->root()};
  GlyphImage glyphs_;
  std::vector<GlyphHit> hits_;
  std::vector<TrailPoint> trail_points_;
  Trails trails_{int(settings_.trails.length)};
  std::optional<SliceLayer> slice_;
  std::vector<float> depth_;  // the glyphs' or the walls', then the slice's where nearer
  SceneryLayer scenery_;
};

}  // namespace

ViewKind particles_view_kind() {
  return view_kind<ParticlesSettings, ParticlesView>("particles", particles_section(), [] {
    return part_reference("trails", "particles", trails_section()) +
           part_reference("slice", "particles", slice_section()) +
           "\nIts `plane` is a `views[i].plane` (kind `slice`).\n";
  });
}

}  // namespace voxspan
