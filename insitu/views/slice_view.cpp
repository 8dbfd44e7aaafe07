#include "insitu/views/slice_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "insitu/parallel/communicator.h"
#include "insitu/views/legend.h"
#include "insitu/views/view.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace {

glm::dvec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }

const schema::Section<SlicePlaneConfig>& plane_section() {
  using P = SlicePlaneConfig;
  static const schema::Section<P> s{
      "views[i].plane",
      {schema::vec3_or_auto("origin", &P::origin,
                            "a point of the plane; `auto` = the centre of the fluid's box"),
       schema::vec3("normal", &P::normal, "the plane's normal (any length but 0)")},
      [](yaml::MapReader& r, P& p) {
        if (r.has("normal") && !(glm::length(vec(p.normal)) > 0))
          r.checker().error(r.find("normal"), r.path("normal"), "must not be zero");
      }};
  return s;
}

const schema::Section<SliceSettings>& slice_section() {
  using S = SliceSettings;
  static const schema::Section<S> s{
      "views[i]",
      view_keys<S>(
          "slice",
          {schema::text("quantity", &S::quantity,
                        "the particle attribute interpolated on the plane (a vector: its "
                        "magnitude); required"),
           schema::choice("kernel", &S::kernel, kSphKernelNames,
                          "the SPH kernel W (3D, normalised)"),
           schema::number_or_auto("smoothing_length", &S::smoothing_length, schema::above(0),
                                  "h, world units; `auto` = 1.3 particle spacings"),
           schema::flag("shepard", &S::shepard,
                        "divide by the sum of (m / rho) W: a uniform field stays flat up to "
                        "the free surface"),
           schema::text("mass", &S::mass,
                        "the mass attribute; without it or `density`, m / rho = spacing^3"),
           schema::text("density", &S::density, "the density attribute"),
           schema::map<S, SlicePlaneConfig>("plane", &S::plane, plane_section(),
                                            "the plane: `origin` and `normal`"),
           schema::number_or_auto("extent", &S::extent, schema::above(0),
                                  "the plane's width in the picture, world units (the height "
                                  "follows the picture's aspect); `auto` = the fluid's box "
                                  "as the plane sees it"),
           schema::choice("color_map", &S::color_map, kColorMapNames, "the colour map"),
           schema::interval_or_auto("range", &S::range,
                                    "the values at the colour map's ends; `auto` = the "
                                    "step's smallest and largest"),
           schema::integer("isolines", &S::isolines, 0, 64,
                           "isolines, evenly spaced inside the range; 0: none")}),
      [](yaml::MapReader& r, S& v) {
        if (v.quantity.empty())
          r.checker().error(r.find("kind"), r.path("quantity"),
                            "a slice view needs `quantity` (the attribute it shows)");
      }};
  return s;
}

// The plane's rectangle for this step: the settings, or fitted around the fluid's box.
SlicePlane plane_for(const SliceSettings& s, const Bounds& box, int width, int height) {
  const bool have_box = !box.empty();
  const glm::dvec3 lo = have_box ? vec(box.lo) : glm::dvec3(-0.5);
  const glm::dvec3 hi = have_box ? vec(box.hi) : glm::dvec3(0.5);
  const glm::dvec3 origin = s.plane.origin ? vec(*s.plane.origin) : 0.5 * (lo + hi);
  const double aspect = double(width) / double(height);
  SlicePlane p = SlicePlane::make(origin, vec(s.plane.normal), 1, 1, vec(s.camera.up));
  double w = s.extent.value_or(0);
  if (!s.extent) {
    double su = 0, sv = 0;  // the box's half extents along u and v, around the origin
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      su = std::max(su, std::abs(glm::dot(corner - origin, p.u)));
      sv = std::max(sv, std::abs(glm::dot(corner - origin, p.v)));
    }
    w = 2.1 * std::max({su, sv * aspect, 1e-300});
  }
  p.width = w;
  p.height = w / aspect;
  return p;
}

// A depth image with no fluid surface in it, reusing its storage (a render step whose sizes are
// stable allocates nothing).
void no_surface(FloatImage& depth, int width, int height) {
  if (depth.width != width || depth.height != height) depth = FloatImage(width, height);
  else std::fill(depth.rgba.begin(), depth.rgba.end(), 0.0f);
}

class SliceView final : public View {
 public:
  SliceView(const SliceSettings& s, const ViewContext& c)
      : settings_(s), spacing_(c.particle_spacing), comm_(c.comm) {
    if (!s.smoothing_length && !(spacing_ > 0))
      throw make_error("view ", s.name,
                       ": smoothing_length is `auto` but the particle spacing is unknown; set it");
  }

  bool render(const ViewStep& step, gl::PassTimer& timer, FrameStats& /*stats*/,
              ViewProducts& out) override {
    if (step.data.particles == nullptr) throw make_error("slice: the step has no particles");
    const int w = settings_.width, h = settings_.height;
    const SlicePlane plane = plane_for(settings_, step.fluid_box, w, h);
    {
      auto t = timer.cpu("slice_sum");
      SliceQuantity q;
      q.name = settings_.quantity;
      q.mass = settings_.mass;
      q.density = settings_.density;
      q.rest_volume = spacing_ * spacing_ * spacing_;
      q.kernel = settings_.kernel;
      q.smoothing_length = settings_.smoothing_length.value_or(kAutoSmoothingFactor * spacing_);
      q.shepard = settings_.shepard;
      interpolate(*step.data.particles, q, plane);
    }
    if (comm_ != nullptr && !comm_->root()) return false;  // the root draws the picture
    if (values_.pixels_reached == 0) {
      ++misses_;
      log_warning("view ", settings_.name, ": step ", step.data.step,
                  ": the slice plane reaches no particle (", misses_, " steps so far)");
    }
    auto t = timer.cpu("slice_draw");
    draw(out.picture);
    if (step.needs.first_hit_depth) no_surface(out.first_hit_depth, w, h);
    out.shaded_spans = nullptr;
    out.shaded_field = nullptr;
    if (step.needs.field) {
      fill_field(plane, out.field);
      out.shaded_field = &out.field;
    }
    return true;
  }

  std::string description() const override {
    return "slice of " + settings_.quantity + " " + std::to_string(settings_.width) + "x" +
           std::to_string(settings_.height);
  }

 private:
  // The slice of this process's owned particles; in an MPI job the sum over every rank's
  // (exact: each particle counts on one rank). Every rank takes part in the sums even when its
  // own part failed, then all throw, naming the failure, so that none waits for another.
  void interpolate(const ParticleView& particles, const SliceQuantity& q, const SlicePlane& plane) {
    std::string failure;
    try {
      interpolate_slice(particles, q, plane, settings_.width, settings_.height, values_);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    if (comm_ == nullptr) {
      if (!failure.empty()) throw Error(failure);
      return;
    }
    std::int64_t failed[1] = {failure.empty() ? 0 : 1};
    comm_->sum(failed);
    if (failed[0] > 0)
      throw make_error(failure.empty() ? "the slice failed on another rank" : failure);
    comm_->sum(values_.sum);
    comm_->sum(values_.weight);
    finish_slice(values_, q.shepard);
  }

  void fill_field(const SlicePlane& plane, FieldImage& f) const {
    const int w = settings_.width, h = settings_.height;
    if (f.values.width != w || f.values.height != h) f.values = FloatImage(w, h);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const std::size_t k = std::size_t(i) + std::size_t(w) * std::size_t(j);
        f.values.set(i, j, glm::vec4(values_.values[k], float(values_.weight[k]), 0, 0));
      }
    f.quantity = settings_.quantity;
    f.origin = plane.origin, f.u = plane.u, f.v = plane.v;
    f.width = plane.width, f.height = plane.height;
  }

  std::array<double, 2> range() const {
    if (settings_.range) return *settings_.range;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < values_.values.size(); ++k)
      if (values_.weight[k] > 0)
        lo = std::min(lo, double(values_.values[k])), hi = std::max(hi, double(values_.values[k]));
    return display_range(lo, hi);
  }

  // The colour-mapped values, isolines darkened, no-fluid pixels dark, the colour bar.
  void draw(FloatImage& picture) const {
    const int w = settings_.width, h = settings_.height;
    if (picture.width != w || picture.height != h) picture = FloatImage(w, h);
    const auto [lo, hi] = range();
    const double scale = 1.0 / (hi - lo);
    const int lines = settings_.isolines;
    auto level = [&](std::size_t k) {
      return std::floor((values_.values[k] - lo) * scale * (lines + 1));
    };
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const std::size_t k = std::size_t(i) + std::size_t(w) * std::size_t(j);
        if (!(values_.weight[k] > 0)) {
          picture.set(i, j, glm::vec4(0.02f, 0.02f, 0.025f, 1.0f));
          continue;
        }
        glm::vec3 c = map_color(settings_.color_map, (values_.values[k] - lo) * scale);
        if (lines > 0) {
          const double mine = level(k);
          const bool edge = (i + 1 < w && values_.weight[k + 1] > 0 && level(k + 1) != mine) ||
                            (j + 1 < h && values_.weight[k + std::size_t(w)] > 0 &&
                             level(k + std::size_t(w)) != mine);
          if (edge) c *= 0.25f;
        }
        picture.set(i, j, glm::vec4(c, 1.0f));
      }
    draw_color_bar(picture, settings_.color_map, lo, hi);
  }

  const SliceSettings settings_;
  const double spacing_;
  Communicator* const comm_;  // null in one process
  SliceImage values_;
  std::int64_t misses_ = 0;
};

}  // namespace

ViewKind slice_view_kind() {
  ViewKind kind = view_kind<SliceSettings, SliceView>("slice", slice_section());
  kind.config.reference = [] {
    return slice_section().reference() + "\n#### `views[i].plane` (kind `slice`)\n\n" +
           plane_section().reference();
  };
  return kind;
}

}  // namespace voxspan
