#include "insitu/views/volume_view.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "insitu/parallel/communicator.h"
#include "insitu/views/legend.h"
#include "insitu/views/view.h"
#include "insitu/views/view_attributes.h"
#include "insitu/views/view_environment.h"
#include "insitu/views/view_framing.h"
#include "insitu/views/view_keys.h"
#include "insitu/views/volume_compositor.h"
#include "render/backend.h"
#include "render/frame_origin.h"
#include "render/volume_merge.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {

TransferTable transfer_table(ColorMap map, const std::vector<std::array<double, 2>>& opacity,
                             const ColorAxis& axis) {
  TransferTable t;
  t.lo = axis.lo;
  t.hi = axis.hi;
  t.log = axis.scale == ColorScale::log;
  for (int k = 0; k < kTransferEntries; ++k) {
    const double u = double(k) / (kTransferEntries - 1);
    double alpha = opacity.empty() ? 0.0 : opacity.front()[1];
    for (std::size_t i = 1; i < opacity.size(); ++i) {
      const auto& [t0, a0] = opacity[i - 1];
      const auto& [t1, a1] = opacity[i];
      if (u >= t0 && u <= t1) alpha = t1 > t0 ? a0 + (a1 - a0) * (u - t0) / (t1 - t0) : a1;
      if (u >= t1) alpha = a1;
    }
    t.rgba[std::size_t(k)] = glm::vec4(map_color(map, u), float(alpha));
  }
  return t;
}

namespace {

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

const schema::Section<VolumeIsoSettings>& iso_section() {
  using I = VolumeIsoSettings;
  static const schema::Section<I> s{
      "views[i].iso[k]",
      {schema::number("value", &I::value, schema::any_number(), "the field's value on the surface"),
       schema::vec3("color", &I::color, "its colour, linear RGB"),
       schema::number("opacity", &I::opacity, schema::between(0, 1),
                      "its opacity (1: hides what lies behind)")},
      [](yaml::MapReader& r, I& v) {
        if (!r.has("value"))
          r.checker().error(r.node(), r.path("value"), "an iso surface needs its `value`");
        if (v.color[0] < 0 || v.color[1] < 0 || v.color[2] < 0)
          r.checker().error(r.find("color"), r.path("color"), "a colour must not be negative");
        else if (v.color[0] > 1 || v.color[1] > 1 || v.color[2] > 1)
          r.checker().error(r.find("color"), r.path("color"),
                            "a colour's channels are linear RGB in [0, 1] (values of 0 to 255: "
                            "divide them by 255)");
      }};
  return s;
}

const schema::Section<VolumeAdaptiveSettings>& adaptive_section() {
  using A = VolumeAdaptiveSettings;
  static const schema::Section<A> s{
      "views[i].adaptive",
      {schema::number("error_tolerance", &A::error_tolerance, schema::between(0, 1),
                      "the most any channel of any pixel may move from the full-rate picture "
                      "([HOK16]'s E_I; DVR of a Shepard-normalised `quantity`, either renderer; "
                      "in an MPI job, of the composited picture: each rank spends 1 / ranks of "
                      "it); 0: every sample. It pays where 8x8-pixel bundles are flat (a radial "
                      "concentration: 1.4 times faster at 0.004, 1.6 at 0.01); where none is "
                      "(the dam break's height) the planning makes the frame 3 to 10 % slower "
                      "(docs/benchmarks.md)"),
       schema::number("relax", &A::relax, schema::between(0, 1),
                      "the share of each cell's full-rate bound width left out of its coarser "
                      "ones ([HOK16]'s E_relax): more cells sparser, no longer a guarantee; on "
                      "sharp fields (a narrow opacity spike, sharp fronts) pixels then move by "
                      "far more than the tolerance")}};
  return s;
}

void check_volume(yaml::MapReader& r, VolumeSettings& v) {
  check_color_axis(r, v);
  check_sph_sum(r, v);
  const auto& points = v.opacity;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(points[i][0] >= 0 && points[i][0] <= 1) || !(points[i][1] >= 0 && points[i][1] <= 1))
      r.checker().error(r.find("opacity"), r.path("opacity"),
                        "each point is [t, alpha] with t and alpha in [0, 1]; point " +
                            std::to_string(i) + " is [" + yaml::number_text(points[i][0]) + ", " +
                            yaml::number_text(points[i][1]) + "]");
    if (i > 0 && points[i][0] < points[i - 1][0])
      r.checker().error(r.find("opacity"), r.path("opacity"),
                        "the points' t must not decrease; point " + std::to_string(i) +
                            " comes before point " + std::to_string(i - 1));
  }
  if (points.empty())
    r.checker().error(r.find("opacity"), r.path("opacity"), "needs at least one point");
  // An `iso` the reader refused has its own error; one given in mode dvr would be drawn nowhere.
  if (v.mode != VolumeMode::dvr && v.iso.empty() && !r.has("iso"))
    r.checker().error(r.has("mode") ? r.find("mode") : r.node(), r.path("iso"),
                      "mode `" + std::string(name_of(kVolumeModeNames, v.mode)) +
                          "` needs at least one iso surface");
  if (v.mode == VolumeMode::dvr && !v.iso.empty())
    r.checker().error(r.find("iso"), r.path("iso"),
                      "mode `dvr` draws no iso surfaces: set mode: mixed (or iso), or leave iso "
                      "out");
  if (v.quantity.empty() && r.has("shepard") && v.shepard)
    r.checker().error(r.find("shepard"), r.path("shepard"),
                      "with no `quantity` the field is the volume fraction, which Shepard "
                      "normalisation would make 1 everywhere");
  // Its bounds hold for a convex combination of the particles' values seen as a medium; taken
  // elsewhere it would skip nothing and say nothing.
  const bool applies = v.mode == VolumeMode::dvr && v.shepard && !v.quantity.empty();
  if (v.adaptive.error_tolerance > 0 && !applies)
    r.checker().error(r.find("adaptive"), r.path("adaptive"),
                      "adaptive sampling applies to DVR of a Shepard-normalised quantity (mode: "
                      "dvr, shepard: true, a `quantity`); this view would take every sample");
}

std::vector<schema::Key<VolumeSettings>> volume_keys() {
  using S = VolumeSettings;
  return schema::joined(
      sph_sum_keys<S>(
          "the particle attribute shown (a vector: its magnitude); empty: the fluid's volume "
          "fraction sum (m / rho) W",
          "divide by sum (m / rho) W ([HOK16]'s CSPH): a uniform field stays flat up to the "
          "free surface; off with no quantity"),
      std::vector<schema::Key<S>>{
          schema::choice("mode", &S::mode, kVolumeModeNames,
                         "`dvr`: the field as a glowing, absorbing medium; `iso`: its iso "
                         "surfaces; `mixed`: both ([FAW10] sec. 5)")},
      color_map_keys<S>("the transfer function's colours over `range`",
                        "the particles' smallest and largest ([0, 1] for the volume fraction)"),
      std::vector<schema::Key<S>>{
          schema::pairs("opacity", &S::opacity,
                        "the transfer function's opacity: [t, alpha] points, t in [0, 1] "
                        "across `range` (not decreasing), alpha in [0, 1] the opacity of "
                        "`opacity_length` of fluid at that value; linear between them"),
          schema::number("opacity_length", &S::opacity_length, schema::above(0),
                         "the length, in particle spacings, over which `opacity` holds: the "
                         "picture does not change with the scene's scale"),
          schema::maps("iso", &S::iso, iso_section(), kMaxIsoSurfaces,
                       "iso surfaces (modes `iso` and `mixed`), lit with the field's gradient"),
          schema::number("sampling", &S::sampling, schema::between(0.125, 16),
                         "samples per pixel spacing along each ray (1: as along as across, "
                         "[FAW10]'s perspective grid)"),
          schema::number("termination", &S::termination, schema::between(0, 0.5),
                         "a ray stops when its transmittance falls under this (the error it "
                         "makes is at most this times what lies behind)"),
          schema::number("weight_floor", &S::weight_floor, schema::at_least(0),
                         "with Shepard, where sum (m / rho) W is under this the field is "
                         "empty (the free surface, where the ratio is noise)"),
          schema::number("ambient", &S::ambient, schema::between(0, 1),
                         "the iso surfaces' light from everywhere"),
          schema::choice("background", &S::background, kVolumeBackgroundNames,
                         "`sky`: the surface views' sky and ground behind the fluid; `none`: "
                         "transparent, alpha = 1 - transmittance (premultiplied)"),
          schema::map("adaptive", &S::adaptive, adaptive_section(),
                      "adaptive sampling under an error tolerance ([HOK16])"),
          schema::number(
              "level_of_detail", &S::level_of_detail, schema::between(0, 8),
              "0: every particle drawn; above 0, particles whose h at their depth is under this "
              "many pixel spacings are merged per world grid cell into coarser ones of at least "
              "that h ([FAW10] sec. 4.1): far fewer particles, a smoother picture, silhouettes "
              "about a pixel wider (docs/benchmarks.md); with `adaptive` its tolerance holds "
              "against the merged particles' picture; over MPI each rank merges its own"),
          schema::flag("legend", &S::legend, "the colour bar with the range's values"),
          schema::map<S, ScenerySettings>(
              "scenery", &S::scenery, scenery_section(),
              "the solver's walls and obstacles as opaque solids: rays end at them and the "
              "fluid glows in front of them")});
}

const schema::Section<VolumeSettings>& volume_section() {
  using S = VolumeSettings;
  static const schema::Section<S> s{"views[i]", view_keys<S>("volume", volume_keys()),
                                    check_volume};
  return s;
}

class VolumeView final : public View {
 public:
  VolumeView(const VolumeSettings& s, const ViewContext& c)
      : settings_(s),
        spacing_(c.particle_spacing),
        renderer_(make_volume_renderer(c.backend, c.shaders)),
        comm_(c.comm != nullptr && c.comm->size() > 1 ? c.comm : nullptr),
        scenery_(s.scenery, spacing_) {
    if (comm_ != nullptr) compositor_.emplace(*comm_);
    if (!(spacing_ > 0) || !std::isfinite(spacing_))
      throw make_error("view ", s.name,
                       ": the particle spacing is needed (the samples and "
                       "the opacity follow it); set classification.particle_spacing or pass it "
                       "to the adapter");
    if (comm_ == nullptr || comm_->root())
      warn_of_odd_smoothing("view " + s.name + ": smoothing_length", s.smoothing_length, spacing_);
  }

  bool render(const ViewStep& step, Recorder& recorder, ViewProducts& out) override {
    if (step.data.particles == nullptr) throw make_error("volume: the step has no particles");
    // Cast relative to the eye when it stands far from the world's origin: the particles'
    // floats are then as fine as the picture needs at their depth. Every rank has the same
    // camera, so the same frame.
    const FrameOrigin frame = FrameOrigin::near(step.camera.eye, spacing_);
    const ColorAxis axis = gathered_axis(*step.data.particles, frame, step.data.step);
    VolumeOptions o = options(step, axis);
    o.backdrop = walls(step, o.environment, recorder);  // in world units, as the scenery is
    o.environment = frame.environment(o.environment);
    const Camera camera = frame.camera(step.camera);
    const bool deep = step.needs.deep;
    if (compositor_) {
      if (!compositor_->render(*renderer_, camera, particles_, o, deep, recorder, frame_))
        return false;  // the root draws the frame
    } else if (deep) {
      render_with_deep(*renderer_, camera, particles_, o, recorder, frame_);
    } else {
      renderer_->render(camera, particles_, o, recorder, frame_);
    }
    out.shaded_deep = deep ? &frame_.deep : nullptr;
    std::swap(out.picture, frame_.picture);
    if (draws_bar()) draw_color_bar(out.picture, settings_.color_map, axis, bar_title_);
    if (step.needs.first_hit_depth) {
      FloatImage& d = out.first_hit_depth;
      if (d.width != settings_.width || d.height != settings_.height)
        d = FloatImage(settings_.width, settings_.height);
      for (std::size_t k = 0; k < frame_.depth.size(); ++k) d.rgba[4 * k] = frame_.depth[k];
    }
    out.shaded_spans = nullptr;
    out.shaded_field = nullptr;
    return true;
  }

  bool draws_scenery() const override { return settings_.scenery.draw; }

  LegendMargins framing_margins() const override {
    return draws_bar() ? color_bar_margins(settings_.width, settings_.height, BarSide::right)
                       : LegendMargins{};
  }

  std::string description() const override {
    return "volume " + std::string(name_of(kVolumeModeNames, settings_.mode)) + " of " +
           (settings_.quantity.empty() ? std::string("the volume fraction") : settings_.quantity) +
           " " + std::to_string(settings_.width) + "x" + std::to_string(settings_.height);
  }

 private:
  // An iso surface has no colour map: no bar.
  bool draws_bar() const { return settings_.legend && settings_.mode != VolumeMode::iso; }

  // The step's walls (null: none), lit under `environment`: made on the root, whose scenery holds
  // every rank's spheres, and in an MPI job sent to the other ranks (when they change), whose
  // rays end at them too. A failure on the root fails every rank.
  const Backdrop* walls(const ViewStep& step, const Environment& environment, Recorder& recorder) {
    const Backdrop* made = nullptr;
    std::string failure;
    if (comm_ == nullptr || comm_->root()) {
      try {
        if (step.scenery != nullptr) {
          const Scenery& s = *step.scenery;
          ShadeOptions shade;
          shade.environment = environment;
          made = scenery_.backdrop(step.camera, s.spheres, s.version, s.box, shade, recorder);
        }
      } catch (const std::exception& e) {
        if (comm_ == nullptr) throw;
        failure = e.what();
      }
    }
    if (comm_ == nullptr) return made;
    comm_->agree_or_throw(failure.empty(), failure);
    std::array<std::uint64_t, 2> header{made != nullptr ? 1u : 0u,
                                        made != nullptr ? made->version : 0};
    comm_->broadcast(std::as_writable_bytes(std::span(header)));
    if (header[0] == 0) return nullptr;
    if (header[1] != sent_version_) {  // every rank holds the same sent_version_
      received_.width = step.camera.width;
      received_.height = step.camera.height;
      received_.pixels.resize(std::size_t(received_.width) * std::size_t(received_.height));
      if (made != nullptr) received_.pixels = made->pixels;
      comm_->broadcast(std::as_writable_bytes(std::span(received_.pixels)));
      received_.version = header[1];
      sent_version_ = header[1];
    }
    return comm_->root() ? made : &received_;
  }

  // gather() on every rank, the failure of any failing all (before the collectives that follow);
  // the colour map's axis: the settings' range, or that of every rank's values.
  ColorAxis gathered_axis(const ParticleView& particles, const FrameOrigin& frame,
                          std::int64_t step) {
    ValueSpan found;
    if (comm_ == nullptr) {
      found = gather(particles, frame);
    } else {
      std::string failure;
      bool ok = true;
      try {
        found = gather(particles, frame);
      } catch (const std::exception& e) {
        ok = false;
        failure = e.what();
      }
      comm_->agree_or_throw(ok, failure);
      span_over_ranks(*comm_, found);
    }
    if (comm_ == nullptr || comm_->root()) tell(found, step);
    if (settings_.quantity.empty() && !settings_.range) return {0.0, 1.0};
    return color_axis_(settings_.range, found, settings_.scale);
  }

  // Said once a run, or the picture has holes or is empty without a word: values that are not
  // numbers (left out; each step's stats count them: particles_invalid), and iso surfaces of a
  // Shepard-normalised field, which lies between its particles' values, at levels outside them.
  void tell(const ValueSpan& found, std::int64_t step) {
    if (found.non_finite > 0 && !std::exchange(told_non_finite_, true))
      log_warning("view ", settings_.name, ": step ", step, ": particles whose ",
                  settings_.quantity, " is NaN or infinite are left out (", found.non_finite,
                  comm_ != nullptr ? " on one rank" : "", "; said once)");
    if (!settings_.shepard || settings_.quantity.empty() || !(found.lo <= found.hi)) return;
    told_iso_.resize(settings_.iso.size());
    for (std::size_t k = 0; k < settings_.iso.size(); ++k) {
      const double v = settings_.iso[k].value;
      if ((v >= found.lo && v <= found.hi) || told_iso_[k]) continue;
      told_iso_[k] = true;
      log_warning("view ", settings_.name, ": step ", step, ": iso[", k, "].value ", v,
                  " lies outside the field's values (", found.lo, " to ", found.hi,
                  "): that surface is nowhere (said once)");
    }
  }

  // The step's owned particles as the renderer reads them, in `frame`; returns the span of
  // their values.
  ValueSpan gather(const ParticleView& particles, const FrameOrigin& frame) {
    const AttributeView* q =
        settings_.quantity.empty()
            ? nullptr
            : &require_attribute(particles, settings_.quantity, settings_.key_path("quantity"));
    const AttributeView* h_attr =
        settings_.smoothing_attribute.empty()
            ? nullptr
            : &require_attribute(particles, settings_.smoothing_attribute,
                                 settings_.key_path("smoothing_attribute"));
    const AttributeView* mass = particles.find_attribute(settings_.mass);
    const AttributeView* density = particles.find_attribute(settings_.density);
    const bool per_particle_volume = mass != nullptr && density != nullptr;
    const double rest_volume = spacing_ * spacing_ * spacing_;
    const double h = settings_.smoothing_length.value_or(kAutoSmoothingFactor * spacing_);
    const std::size_t n = particles.owned_count();
    particles_.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const auto p = particles.position(i);
        const double volume =
            per_particle_volume ? mass->magnitude(i) / density->magnitude(i) : rest_volume;
        const double hi = h_attr != nullptr ? h_attr->magnitude(i) : h;
        const glm::vec3 at = frame.position(p[0], p[1], p[2]);
        particles_[i] = {at.x,
                         at.y,
                         at.z,
                         float(hi),
                         float(volume / (hi * hi * hi)),
                         q != nullptr ? float(q->magnitude(i)) : 1.0f};
      }
    });
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 16384), ValueSpan{},
        [&](const auto& r, ValueSpan s) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) s.add(particles_[i].value);
          return s;
        },
        [](ValueSpan a, const ValueSpan& b) {
          a.add(b);
          return a;
        });
  }

  VolumeOptions options(const ViewStep& step, const ColorAxis& axis) const {
    const VolumeSettings& s = settings_;
    VolumeOptions o;
    o.mode = s.mode;
    o.kernel = s.kernel;
    o.shepard = s.shepard && !s.quantity.empty();
    o.weight_floor = s.weight_floor;
    o.transfer = transfer_table(s.color_map, s.opacity, axis);
    o.opacity_length = s.opacity_length * spacing_;
    for (const VolumeIsoSettings& iso : s.iso)
      o.isos.push_back({iso.value, vec(iso.color), iso.opacity});
    o.sampling = s.sampling;
    o.anchor = spacing_;
    o.termination = s.termination;
    o.background = s.background == VolumeBackground::sky;
    o.ambient = s.ambient;
    o.adaptive = {s.adaptive.error_tolerance, s.adaptive.relax};
    o.level_of_detail = s.level_of_detail;
    Environment& e = o.environment;
    e.up = step.camera.up;
    e.sun_direction = sun_direction(e.up);
    e.ground_tile = 12 * spacing_;
    if (!step.fluid_box.empty())
      e.rest_on_floor(floor_height(step.fluid_box, e.up, spacing_), spacing_);
    return o;
  }

  const VolumeSettings settings_;
  const std::string bar_title_ = color_bar_title(
      settings_.quantity.empty() ? "volume fraction" : settings_.quantity, settings_.units);
  const double spacing_;
  std::unique_ptr<VolumeRenderer> renderer_;
  Communicator* const comm_;                    // null in one process
  std::optional<VolumeCompositor> compositor_;  // in an MPI job
  const ViewColorAxis color_axis_{settings_.name, settings_.quantity,
                                  comm_ == nullptr || comm_->root()};
  SceneryLayer scenery_;
  Backdrop received_;               // an MPI job's walls, on the ranks but the root
  std::uint64_t sent_version_ = 0;  // the walls' version last sent to them
  std::vector<VolumeParticle> particles_;
  VolumeFrame frame_;
  bool told_non_finite_ = false;
  std::vector<bool> told_iso_;
};

}  // namespace

ViewKind volume_view_kind() {
  return view_kind<VolumeSettings, VolumeView>("volume", volume_section(), [] {
    return part_reference("iso[k]", "volume", iso_section()) +
           part_reference("adaptive", "volume", adaptive_section());
  });
}

}  // namespace voxspan
