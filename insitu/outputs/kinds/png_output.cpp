// outputs.png: every rendered view as an 8-bit sRGB PNG, <folder>/<view>_<step>.png. The
// picture is copied on the solver's thread; the sRGB conversion and the encoding run on the
// writer's (insitu/outputs/formats/png_image.h).
#include "insitu/outputs/formats/png_image.h"
#include "insitu/outputs/kinds/view_images.h"
#include "insitu/outputs/output.h"

namespace voxspan {
namespace {

struct PngSettings : CloneAs<PngSettings, OutputSettings> {
  PngSettings() : CloneAs(true, "frames", TriggerSpec{10, 0, true, true}) {
    follows_render_trigger = true;
  }
  bool operator==(const PngSettings&) const = default;
};

const schema::Section<PngSettings>& png_section() {
  static const schema::Section<PngSettings> s{"outputs.png",
                                              output_keys<PngSettings>({}, "the render trigger")};
  return s;
}

void write_picture(const std::filesystem::path& path, const FloatImage& picture, bool sync) {
  write_png(path, linear_to_srgb8(picture.rgba, picture.width, picture.height), sync);
}

}  // namespace

OutputKind png_output_kind() {
  return view_image_output_kind(
      "png", "PNG", png_section(),
      {"png", "PNG frame", &ViewResult::picture, {.picture = true}, write_picture});
}

}  // namespace voxspan
