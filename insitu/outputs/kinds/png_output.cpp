// outputs.png: every rendered view as an 8-bit sRGB PNG, <folder>/<view>_<step>.png. The job
// holds the view's picture by reference (no copy on the solver's thread); the sRGB conversion
// (none where the GL renderer made the picture 8-bit sRGB on the GPU: ViewNeeds) and the
// encoding, at the `compression_level` chosen, run on the writer's
// (insitu/outputs/formats/png_image.h).
#include "insitu/outputs/kinds/png_output.h"

#include "insitu/outputs/kinds/view_images.h"
#include "insitu/outputs/output.h"

namespace voxspan {
namespace {

const schema::Section<PngSettings>& png_section() {
  static const schema::Section<PngSettings> s{
      "outputs.png",
      output_keys<PngSettings>(
          {schema::integer("compression_level", &PngSettings::compression_level, 0, 12,
                           "deflate level (libdeflate) of the rows filtered by Sub: 0 stored, "
                           "1 fastest, 12 smallest; 4: about 30 ms and 0.7 MB a 1920x1080 frame "
                           "on one core (docs/benchmarks.md, \"PNG encoding\")")},
          "the render trigger")};
  return s;
}

class PngOutput final : public Output {
 public:
  PngOutput(const PngSettings& s, const OutputContext& c)
      : jobs_(c, "png", "PNG frame",
              [encoding = PngEncoding{s.compression_level, PngFilter::sub}, sync = c.fsync](
                  const std::filesystem::path& path, KeptImage& picture) {
                write_png(path, picture.srgb8(), sync, encoding);
              }) {}
  void write(const OutputStep& step) override { jobs_.submit(step, &ViewResult::picture); }
  OutputTally tally() const override { return jobs_.tally(); }

 private:
  ViewImageJobs jobs_;
};

}  // namespace

OutputKind png_output_kind() {
  return output_kind<PngSettings, PngOutput>("png", "PNG", png_section(), {.picture = true}, false,
                                             true);
}

}  // namespace voxspan
