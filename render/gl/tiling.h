// render/gl/tiling.h - splits the image into screen tiles whose voxel subgrids fit a GPU memory
// budget ([ZD15] sec. 3.1): the full grid (1920x1080x16384 bits is 4.2 GB) never exists at
// once; each tile is cleared, splatted and compressed in turn.
//
// A tile column costs its bits (layers rounded up to whole uvec4s, 16 bytes per 128 layers) and
// its share of the compress pass's span scratch; a tile is at most one GL binding (1 GiB, and
// the driver's shader-storage block limit). Tiles are as wide as the image unless max_width is
// set, and as tall as the budget allows; sizes are then evened out so no tile is a sliver.
#pragma once

#include <cstddef>
#include <cstdint>

namespace voxspan {

struct TileOptions {
  std::size_t memory_budget = std::size_t(1) << 30;  // bytes for one tile's bits and scratch
  int max_width = 0;                                 // pixels; 0 = the image width
  int max_height = 0;  // pixels; 0 = as many rows as the budget allows
};

struct TileRect {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  int pixels() const { return width * height; }
};

struct TileLayout {
  int tile_width = 0, tile_height = 0;  // the largest tile
  int columns = 0, rows = 0;            // tiles across and down
  int image_width = 0, image_height = 0;
  std::size_t column_bytes = 0;   // bits of one pixel's column, padded to uvec4
  std::size_t scratch_bytes = 0;  // compress scratch per pixel
  std::size_t tile_bytes = 0;     // bits of the largest tile

  int count() const { return columns * rows; }
  TileRect tile(int index) const;
};

// Bytes of the compress pass's per-pixel scratch: `scratch_spans` spans, a count and an exit.
std::size_t scratch_bytes_per_pixel(int scratch_spans);

// Throws voxspan::Error when even one row of a tile does not fit the budget, naming the budget
// that would (and when the largest binding cannot hold one row).
TileLayout plan_tiles(int width, int height, int layers, int scratch_spans,
                      const TileOptions& options, std::size_t max_binding_bytes);

}  // namespace voxspan
