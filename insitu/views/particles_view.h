// insitu/views/particles_view.h - views[i] of kind `particles`: every owned particle (or the
// shell's, or those with a quantity in a range) drawn as a sphere ray-cast per pixel
// (insitu/views/glyphs.h), coloured by a named scalar or vector magnitude through a colour map
// with its legend, lit with a key light and ambient occlusion. Its settings, for the code that
// reads them by type. With `trails`, the paths of chosen particles over the last render steps
// as lines, hidden behind nearer glyphs; with `slice`, an SPH slice plane placed among the
// glyphs (insitu/views/slice_layer.h), those in front of it cut away. The solver's walls
// (insitu/views/scenery.h) stand among the glyphs as in a surface view, nearer ones hiding them.
//
// Reads: the owned particles (positions, color_by, cull_by), the cell states (the shell and
// the occlusion culling), the framed camera. Writes: the picture; the first-hit depth when an
// output asks. Runs on the CPU whichever renderer draws the surfaces. In an MPI job every rank
// draws its owned particles and sends its nearest glyph per pixel to rank 0, which keeps the
// nearest of all (a depth composite: exact) and shades the picture.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/views/color_map.h"
#include "insitu/views/glyphs.h"
#include "insitu/views/scenery.h"
#include "insitu/views/slice_layer.h"
#include "insitu/views/view_keys.h"

namespace voxspan {

// What the view times on a step (besides its slice's); its counts: particles_view.cpp.
namespace pass {
inline constexpr StatName glyph_raster{"glyph_raster"};  // every rank's glyphs and trail points
inline constexpr StatName glyph_composite{"glyph_composite"};  // MPI: the nearest of all ranks
inline constexpr StatName glyph_shade{"glyph_shade"};
}  // namespace pass

enum class GlyphSubset : std::uint8_t { all, boundary };
inline constexpr EnumName<GlyphSubset> kGlyphSubsetNames[] = {{"all", GlyphSubset::all},
                                                              {"boundary", GlyphSubset::boundary}};

// `trails`: the paths of the particles whose id (the attribute `id`) is a multiple of `every`
// or is listed in `ids`, over the last `length` render steps (insitu/views/trails.h).
struct TrailSettings {
  std::string id = "id";
  std::int64_t every = 0;         // 0: none by multiple
  std::vector<std::int64_t> ids;  // sorted
  std::int64_t length = 16;
  Vec3d colour{1.0, 0.9, 0.6};
  bool operator==(const TrailSettings&) const = default;
};

// Its colouring: color_by empty gives one colour; range nullopt = the drawn particles' min and max.
struct ParticlesSettings : CloneAs<ParticlesSettings, ViewSettings>, ColorBySettings {
  std::string cull_by;  // empty: color_by
  std::optional<std::array<double, 2>> cull_range;
  GlyphSubset draw = GlyphSubset::all;
  GlyphCulling culling = GlyphCulling::occlusion;
  std::optional<double> radius;  // world units; nullopt = half the particle spacing
  double ambient_occlusion = 0.8;
  TrailSettings trails;
  ParticleSlice slice;  // quantity empty: none
  ScenerySettings scenery;
  bool operator==(const ParticlesSettings&) const = default;
};

}  // namespace voxspan
