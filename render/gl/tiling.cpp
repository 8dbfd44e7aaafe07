#include "render/gl/tiling.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {
namespace {

int ceil_div(std::size_t a, std::size_t b) { return static_cast<int>((a + b - 1) / b); }

}  // namespace

TileRect TileLayout::tile(int index) const {
  const int tx = index % columns, ty = index / columns;
  TileRect r;
  r.x0 = tx * tile_width;
  r.y0 = ty * tile_height;
  r.width = std::min(tile_width, image_width - r.x0);
  r.height = std::min(tile_height, image_height - r.y0);
  return r;
}

std::size_t scratch_bytes_per_pixel(int scratch_spans) {
  return static_cast<std::size_t>(scratch_spans) * 8 + 8;
}

TileLayout plan_tiles(int width, int height, int layers, int scratch_spans,
                      const TileOptions& options, std::size_t max_binding_bytes) {
  if (width < 1 || height < 1 || layers < 32 || layers % 32 != 0 || scratch_spans < 1)
    throw make_error("plan_tiles: image ", width, "x", height, ", ", layers, " layers, ",
                     scratch_spans, " scratch spans is not a valid grid");
  TileLayout t;
  t.image_width = width;
  t.image_height = height;
  t.column_bytes = static_cast<std::size_t>((layers + 127) / 128) * 16;
  t.scratch_bytes = scratch_bytes_per_pixel(scratch_spans);
  const int max_width = options.max_width > 0 ? std::min(options.max_width, width) : width;
  const std::size_t row_bits = t.column_bytes * static_cast<std::size_t>(max_width);
  const std::size_t row_bytes = row_bits + t.scratch_bytes * static_cast<std::size_t>(max_width);
  if (options.memory_budget < row_bytes)
    throw make_error("tile memory budget of ", options.memory_budget,
                     " bytes is too small for one row of a ", max_width, "-pixel-wide tile at ",
                     layers, " layers: that needs ", row_bytes, " bytes (", row_bits, " of bits + ",
                     row_bytes - row_bits, " of span scratch); raise the budget to at least ",
                     row_bytes, " bytes, narrow the tiles or lower max_layers");
  if (max_binding_bytes < row_bits)
    throw make_error("one row of a ", max_width, "-pixel-wide tile at ", layers, " layers needs ",
                     row_bits, " bytes of bits, more than one GL binding holds (",
                     max_binding_bytes, "); narrow the tiles (max_width) or lower max_layers");
  std::size_t rows = std::min(options.memory_budget / row_bytes, max_binding_bytes / row_bits);
  rows = std::min<std::size_t>(rows, static_cast<std::size_t>(height));
  if (options.max_height > 0)
    rows = std::min<std::size_t>(rows, static_cast<std::size_t>(options.max_height));
  // Even out: as few tiles as the limits allow, all of about the same size.
  t.columns = ceil_div(static_cast<std::size_t>(width), static_cast<std::size_t>(max_width));
  t.rows = ceil_div(static_cast<std::size_t>(height), rows);
  t.tile_width = ceil_div(static_cast<std::size_t>(width), static_cast<std::size_t>(t.columns));
  t.tile_height = ceil_div(static_cast<std::size_t>(height), static_cast<std::size_t>(t.rows));
  t.tile_bytes = t.column_bytes * static_cast<std::size_t>(t.tile_width) * t.tile_height;
  return t;
}

}  // namespace voxspan
