// render/backdrop.h - what stands behind the fluid when a scene has walls (the solver's scenery,
// insitu/views/scenery.h): per pixel the colour seen there without the fluid (the walls, lit, or
// the environment) and the view depth of the walls' first drawn surface. A renderer given one
// (SurfaceRenderer::use_backdrop) shows it behind the fluid instead of the environment and ends
// refracted rays where they reach a column's walls (render/model/column_march.glsl), as a ray
// ends on the ground; the fluid's spans are first cut where the walls begin (clip_at_walls), so
// water behind an obstacle is hidden and water against a wall ends at it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/span_image.h"

namespace voxspan {

struct Backdrop {
  static constexpr float kNoWall = 3.0e38f;  // the depth of a pixel whose ray meets no wall

  int width = 0, height = 0;
  // Per pixel (x + y * width, row 0 at the top): rgb the linear colour, a the walls' view depth
  // (kNoWall where none): the layout the GPU reads as it is.
  std::vector<glm::vec4> pixels;
  // Changes whenever `pixels` do, so that a renderer copies them to the GPU only then.
  std::uint64_t version = 0;

  float wall_depth(int x, int y) const {
    return pixels[std::size_t(x) + std::size_t(y) * std::size_t(width)].a;
  }
};

// The backdrop's pyramid for refracted rays' lookups (render/model/column_march.glsl, wall_light):
// level 0 the backdrop's pixels as they are, then levels 1 .. kBackdropLevels - 1, each
// ceil(w / 2) x ceil(h / 2) of the one below, whose texels hold the mean colour of the wall
// pixels under them times their share, and that share (0 where no wall stands), all in one
// array, level after level, rows from the top. Into `out` (its capacity reused).
// kBackdropLevels is column_march.glsl's VX_BACKDROP_LEVELS (render/model/host.h checks).
inline constexpr int kBackdropLevels = 8;
void backdrop_pyramid(const Backdrop& backdrop, std::vector<glm::vec4>& out);

// A renderer's pyramid of the backdrop it uses, made again only when the backdrop or its version
// changes (a hand-made one of version 0: every time), and only for a refractive frame.
class BackdropPyramid {
 public:
  // Whether the pyramid was made again for `backdrop` (kept alive by the caller).
  bool update(const Backdrop& backdrop) {
    if (of_ == &backdrop && version_ == backdrop.version && version_ != 0) return false;
    backdrop_pyramid(backdrop, texels_);
    of_ = &backdrop;
    version_ = backdrop.version;
    return true;
  }
  const std::vector<glm::vec4>& texels() const { return texels_; }

 private:
  std::vector<glm::vec4> texels_;
  const Backdrop* of_ = nullptr;
  std::uint64_t version_ = 0;
};

// Light `c` with transmittance `t` (a volume view's, premultiplied) over pixel (x, y) of the
// backdrop: its colour behind them where a wall stands, or everywhere with `background` (the
// environment's where none stands); elsewhere transparent, alpha 1 - t.
glm::vec4 over_backdrop(const Backdrop& backdrop, int x, int y, glm::vec3 c, float t,
                        bool background);

// Cuts every span of `spans` where its pixel's walls begin, in place (those past them dropped,
// the one across them ended there: the rule of render/gl/passes/cut_at_walls.comp). A cut pixel
// keeps its offset, its count and total become the spans kept, its `inside` their length; a pixel
// that loses nothing keeps its record, a capped one included. Returns the pixels cut. The
// backdrop must be the image's size.
std::int64_t clip_at_walls(SpanImage& spans, const Backdrop& backdrop);

// Whether clip_at_walls would cut any pixel of `spans`: a read-only scan, so that an image held
// by someone else is copied only when a wall cuts it.
bool reaches_past_walls(const SpanImage& spans, const Backdrop& backdrop);

}  // namespace voxspan
