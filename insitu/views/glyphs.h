// insitu/views/glyphs.h - particles drawn as spheres ray-cast per pixel ([GRIBBLE] sec. 3.1,
// ../shared/papers/004): each pixel's ray meets the sphere of radius r around each drawn
// particle exactly (in double), and the nearest entry wins; what the `particles` view kind
// shades. The result is a G-buffer: per pixel the nearest particle, its depth, the normal there
// and the particle's quantity.
//
// The work: every selected particle is projected to the pixels its sphere can cover and tested
// there, threads over particles (oneTBB), the nearest kept with an atomic minimum of
// (depth as float, particle index), so that the picture does not depend on the thread count or
// the order. Culling, which never changes a pixel:
//   frustum:   particles whose sphere lies outside the view pyramid are skipped;
//   occlusion: the solver's grid (its cell states) adapted from [GRIBBLE] sec. 4: particles of
//              cells that are not inner-full are drawn first (they hold the visible shell), then
//              each inner-full cell is skipped whole when every 8x8 pixel tile its box can cover
//              is already nearer than the box's nearest point (a conservative depth test: a
//              skipped particle could not have been the nearest anywhere).
// A sphere that holds the eye is not drawn (as if clipped by a near plane at the eye).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "insitu/views/color_map.h"
#include "render/camera.h"
#include "render/enum_names.h"
#include "render/float_image.h"
#include "voxspan/cell_states.h"
#include "voxspan/particles.h"

namespace voxspan {

enum class GlyphCulling : std::uint8_t { none, frustum, occlusion };
inline constexpr EnumName<GlyphCulling> kGlyphCullingNames[] = {
    {"none", GlyphCulling::none},
    {"frustum", GlyphCulling::frustum},
    {"occlusion", GlyphCulling::occlusion}};

// A half space whose particles are left out: those with dot(normal, centre) > offset (the side
// of a slice plane that faces the camera, so that the plane shows).
struct GlyphCut {
  glm::dvec3 normal{0, 0, 1};
  double offset = 0;
};

// Which particles are drawn, with what radius and value.
struct GlyphSelection {
  double radius = 0;          // every glyph's radius, world units (> 0)
  std::string_view color_by;  // the value's attribute (vector: magnitude); empty: none
  std::string_view cull_by;   // the attribute cull_range tests (empty: color_by)
  // The keys that name them, for messages (ViewSettings::key_path).
  std::string_view color_by_key = "color_by", cull_by_key = "cull_by";
  std::optional<std::array<double, 2>> cull_range;  // drawn only with cull_by in [a, b]
  bool boundary_only = false;  // only particles of cells that are not inner (the shell)
  std::optional<GlyphCut> cut;
  GlyphCulling culling = GlyphCulling::occlusion;
};

// Particle counts of one rasterization. selected = drawn + frustum_culled + occlusion_culled.
struct GlyphCounts {
  std::int64_t owned = 0;          // owned particles with finite positions
  std::int64_t range_culled = 0;   // outside cull_range (or a non-finite value)
  std::int64_t cut = 0;            // in the cut's half space
  std::int64_t inner_skipped = 0;  // in inner cells when only the shell is drawn
  std::int64_t holding_eye = 0;    // spheres around the eye
  std::int64_t frustum_culled = 0;
  std::int64_t occlusion_culled = 0;
  std::int64_t drawn = 0;         // projected and tested at their pixels
  std::int64_t cells_hidden = 0;  // inner-full cells the occlusion test skipped
  std::int64_t selected() const { return drawn + frustum_culled + occlusion_culled; }
  // Every count, for the code that adds them up (threads, ranks) without naming each.
  template <class C> static auto fields(C& c) {
    return std::array{
        &c.owned,          &c.range_culled,     &c.cut,   &c.inner_skipped, &c.holding_eye,
        &c.frustum_culled, &c.occlusion_culled, &c.drawn, &c.cells_hidden};
  }
  GlyphCounts& operator+=(const GlyphCounts& o) {
    const auto mine = fields(*this);
    const auto theirs = fields(o);
    for (std::size_t k = 0; k < mine.size(); ++k) *mine[k] += *theirs[k];
    return *this;
  }
};

inline constexpr std::uint64_t kNoGlyph = ~std::uint64_t(0);

struct GlyphImage {
  int width = 0, height = 0;
  // Per pixel, row 0 at the top: (float bits of the view depth << 32 | particle index), or
  // kNoGlyph. Then, where hit: the view depth, the view-space unit normal and the value.
  std::vector<std::uint64_t> nearest;
  std::vector<float> depth;  // view z (distance along the camera axis); 0: no glyph
  std::vector<glm::vec3> normal;
  std::vector<float> value;  // 0 without color_by
  GlyphCounts counts;
  ValueSpan values;  // over the selected particles

  // Working storage of the occlusion culling, kept from step to step.
  struct CellScratch {
    struct Cell {
      double z_min;
      std::uint32_t cell;
      std::uint8_t verdict;
    };
    std::vector<std::uint32_t> start, fill, sorted;  // the inner-full cells' particles, by cell
    std::vector<Cell> cells;                         // those holding selected particles
  } scratch;
};

// The particle's depth and whether the ray through pixel (x, y) meets its sphere (view-space
// centre c, radius r) in front of the eye; the one intersection both renderings use.
inline bool glyph_hit(const ViewFrame& frame, int x, int y, glm::dvec3 c, double r2, float& z) {
  const glm::dvec3 v = frame.view_ray(x, y);
  const double a = glm::dot(v, v), b = glm::dot(v, c);
  const double disc = b * b - a * (glm::dot(c, c) - r2);
  if (!(disc >= 0)) return false;
  const double t = (b - std::sqrt(disc)) / a;
  if (!(t > 0)) return false;
  z = float(t);
  return z > 0;
}

// Positive floats order as their bits do: the smallest key is the nearest glyph, and of two at
// the same float depth the lower particle index.
inline std::uint64_t glyph_key(float z, std::size_t particle) {
  return (std::uint64_t(std::bit_cast<std::uint32_t>(z)) << 32) | std::uint64_t(particle);
}

// How the glyphs are lit and coloured: the value through a colour map (or one colour), a key
// light from above and behind the eye with a small highlight, and ambient occlusion from the
// neighbouring pixels' glyphs within a world radius (the surfaces' deep AO term,
// render/model/deep_ao.glsl, on the front glyphs), so that depth and packing read.
struct GlyphShading {
  bool by_value = false;  // colour from the value; else `colour`
  ColorMap map = ColorMap::viridis;
  ColorAxis axis;  // the values along the map
  glm::vec3 colour{0.25f, 0.5f, 0.85f};
  double ao_radius = 0;  // world units; 0: no occlusion
  double ao_strength = 0.8;
  int ao_samples = 16;
  glm::vec3 background{0.03f, 0.035f, 0.045f};
};

// The picture (linear RGBA, row 0 at the top) of a G-buffer, its storage reused.
void shade_glyphs(const GlyphImage& glyphs, const Camera& camera, const GlyphShading& shading,
                  FloatImage& picture);

// Draws the selected owned particles into `out` (its storage reused). `cells` may be empty
// (then no occlusion culling and no shell selection). Throws voxspan::Error naming the
// attribute when color_by or cull_by is not passed, or when the radius is not positive.
void rasterize_glyphs(const ParticleView& particles, const CellStatesView& cells,
                      const Camera& camera, const GlyphSelection& selection, GlyphImage& out);

// The same picture by brute force: every pixel's ray against every selected particle, no
// projection, no culling. For the tests and the benchmark (it is O(pixels x particles)).
void reference_glyphs(const ParticleView& particles, const CellStatesView& cells,
                      const Camera& camera, const GlyphSelection& selection, GlyphImage& out);

}  // namespace voxspan
