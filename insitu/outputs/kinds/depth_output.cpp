// outputs.depth: each rendered view's first-entry distance as a 32-bit float OpenEXR image,
// <folder>/<view>_<step>.exr, channel `Z`: per pixel the distance from the eye along the unit
// ray through the pixel centre to where it first enters the fluid (the span image's first
// entry, render/gl/passes/first_hit.h), row 0 at the top; 0 where the ray misses. The camera
// model is in docs/runtime.md ("Depth images").
#include "insitu/outputs/formats/exr_image.h"
#include "insitu/outputs/kinds/view_images.h"
#include "insitu/outputs/output.h"

namespace voxspan {
namespace {

struct DepthSettings : CloneAs<DepthSettings, OutputSettings> {
  DepthSettings() : CloneAs(false, "depth", TriggerSpec{100, 0, false, true}) {}
  bool operator==(const DepthSettings&) const = default;
};

const schema::Section<DepthSettings>& depth_section() {
  static const schema::Section<DepthSettings> s{"outputs.depth", output_keys<DepthSettings>()};
  return s;
}

void write_depth(const std::filesystem::path& path, const FloatImage& depth, bool sync) {
  write_exr_channel(path, depth, "Z", sync);
}

}  // namespace

OutputKind depth_output_kind() {
  return view_image_output_kind(
      "depth", "depth images", depth_section(),
      {"exr", "depth image", &ViewResult::first_hit_depth, {.first_hit_depth = true}, write_depth});
}

}  // namespace voxspan
