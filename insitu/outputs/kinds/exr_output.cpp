// outputs.exr: each rendered view's spans as an OpenEXR 2.0 deep scanline image for
// compositors (Nuke, Houdini, OpenEXR's own tools): <folder>/<view>_<step>.exr holds per pixel
// one deep sample per span, Z its entry and ZBack its exit, as distances from the eye along
// the unit ray through the pixel's centre (docs/runtime.md, "Depth images"), and
// <folder>/<view>_color_<step>.exr the shaded picture, R G B A as linear 32-bit floats. The
// span image is copied into a pooled slot on the solver's thread, the picture referenced; the
// encoding and the writing (each file atomically) run on the writer's. A slice view has no
// spans: its file is <folder>/<view>_<step>.exr with its raw values as 32-bit floats (channels
// `value` and `weight`) and the plane's pixel-to-world mapping in the header. A volume view's
// is its deep image: one sample per run of fluid along the ray, Z, ZBack and premultiplied
// R, G, B, A (render/volume.h).
#include "insitu/outputs/formats/exr_image.h"
#include "insitu/outputs/output.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "insitu/outputs/writer/pooled_jobs.h"

namespace voxspan {
namespace {

struct ExrSettings : CloneAs<ExrSettings, OutputSettings> {
  ExrSettings() : CloneAs(false, "exr", TriggerSpec{100, 0, false, true}) {}
  bool operator==(const ExrSettings&) const = default;
};

const schema::Section<ExrSettings>& exr_section() {
  static const schema::Section<ExrSettings> s{"outputs.exr", output_keys<ExrSettings>()};
  return s;
}

class ExrOutput final : public Output {
 public:
  ExrOutput(const ExrSettings&, const OutputContext& c)
      : folder_(c.folder),
        view_names_(c.view_names.begin(), c.view_names.end()),
        sync_(c.fsync),
        jobs_(c.writer, c.slots, [this](Slot& s) { run(s); }) {}

  void write(const OutputStep& step) override {
    for (std::size_t v = 0; v < step.views.size(); ++v) {
      const ViewResult& r = step.views[v];
      // failed, not this rank's, or a view with no spans, deep image or raw values (particles)
      if (r.picture == nullptr || (r.field == nullptr && r.spans == nullptr && r.deep == nullptr))
        continue;
      jobs_.submit(r.field != nullptr ? "slice EXR image" : "deep EXR image", [&](Slot& s) {
        s.view = v;
        s.step = step.data.step;
        // the slot's vectors keep their capacity
        s.kind = r.field != nullptr ? Kind::field : r.deep != nullptr ? Kind::deep : Kind::spans;
        if (s.kind == Kind::field) s.field = *r.field;
        else if (s.kind == Kind::deep) s.deep = *r.deep;
        else s.spans = *r.spans;
        s.picture.keep(*r.picture, r.shared_picture);
      });
    }
  }
  OutputTally tally() const override { return jobs_.tally(); }

 private:
  enum class Kind { spans, field, deep };
  struct Slot {
    SpanImage spans;
    FieldImage field;
    DeepImage deep;
    Kind kind = Kind::spans;
    KeptImage picture;
    std::size_t view = 0;
    std::int64_t step = 0;
  };

  void run(Slot& s) const {
    const std::string& name = view_names_[s.view];
    write_file_atomically(folder_ / step_file_name(name, s.step, "exr"),
                          s.kind == Kind::field  ? encode_exr_field(s.field)
                          : s.kind == Kind::deep ? encode_deep_exr(s.deep)
                                                 : encode_deep_exr(s.spans),
                          sync_);
    write_file_atomically(folder_ / step_file_name(name + "_color", s.step, "exr"),
                          encode_exr_rgba(s.picture.image()), sync_);
    s.picture.release();
  }

  std::filesystem::path folder_;
  std::vector<std::string> view_names_;
  bool sync_;
  PooledJobs<Slot> jobs_;
};

}  // namespace

OutputKind exr_output_kind() {
  return output_kind<ExrSettings, ExrOutput>(
      "exr", "deep EXR images", exr_section(),
      {.picture = true, .linear_picture = true, .spans = true, .field = true, .deep = true}, false,
      true);
}

}  // namespace voxspan
