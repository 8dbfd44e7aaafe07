#include "insitu/views/slice_view.h"

#include <algorithm>

#include "insitu/views/view.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

const schema::Section<SliceSettings>& slice_section() {
  using S = SliceSettings;
  static const schema::Section<S> s{"views[i]",
                                    view_keys<S>("slice", schema::from_base<S>(slice_field_keys())),
                                    [](yaml::MapReader& r, S& v) { check_slice_field(r, v); }};
  return s;
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
      : settings_(s),
        layer_(s, s.name, s.source.where, c.particle_spacing, c.comm),
        comm_(c.comm) {}

  bool render(const ViewStep& step, Recorder& recorder, ViewProducts& out) override {
    if (step.data.particles == nullptr) throw make_error("slice: the step has no particles");
    const int w = settings_.width, h = settings_.height;
    {
      auto t = recorder.host(pass::slice_sum);
      const Vec3d& up = settings_.camera.up;
      layer_.interpolate(*step.data.particles, step.fluid_box, step.flat_axis,
                         {up[0], up[1], up[2]}, step.data.step, w, h, legend_margins(w, h));
    }
    if (comm_ != nullptr && !comm_->root()) return false;  // the root draws the picture
    auto t = recorder.host(pass::slice_draw);
    layer_.draw_image(out.picture);
    if (step.needs.first_hit_depth) no_surface(out.first_hit_depth, w, h);
    out.shaded_spans = nullptr;
    out.shaded_field = nullptr;
    if (step.needs.field) {
      layer_.fill_field(out.field);
      out.shaded_field = &out.field;
    }
    return true;
  }

  std::string description() const override {
    return "slice of " + settings_.quantity + " " + std::to_string(settings_.width) + "x" +
           std::to_string(settings_.height);
  }

 private:
  const SliceSettings settings_;
  SliceLayer layer_;
  Communicator* const comm_;  // null in one process
};

}  // namespace

ViewKind slice_view_kind() {
  return view_kind<SliceSettings, SliceView>("slice", slice_section(), [] {
    return part_reference("plane", "slice", slice_plane_section());
  });
}

}  // namespace voxspan
