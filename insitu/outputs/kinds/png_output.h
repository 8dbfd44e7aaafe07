// insitu/outputs/kinds/png_output.h - outputs.png: every rendered view as an 8-bit sRGB PNG,
// <folder>/<view>_<step>.png (insitu/outputs/formats/png_image.h). Its settings, for the code
// that reads them by type (the tests).
#pragma once

#include "insitu/config/settings.h"
#include "insitu/outputs/formats/png_image.h"

namespace voxspan {

struct PngSettings : CloneAs<PngSettings, OutputSettings> {
  PngSettings() : CloneAs(true, "frames", TriggerSpec{10, 0, true, true}) {
    follows_render_trigger = true;
  }
  // libdeflate's level for the rows filtered by Sub (PngEncoding).
  int compression_level = PngEncoding{}.level;
  bool operator==(const PngSettings&) const = default;
};

}  // namespace voxspan
