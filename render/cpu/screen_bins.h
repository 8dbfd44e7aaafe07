// render/cpu/screen_bins.h - the CPU renderers' binning of items (spheres, boxes, particles'
// supports) into screen tiles: a counting sort in parallel chunks that keeps every bin's items
// in their order, whatever the threads, and the tiles of the screen.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "render/perspective_grid.h"

namespace voxspan {

// Items sorted into bins (a counting sort): count() the items' bins, then place() each item in
// each of its bins. Both run in parallel over fixed chunks of the items, each chunk's items
// placed after those of the chunks before it, so that every bin holds its items in their
// order, whatever the threads. bins_of(i, f): f(bin) for each bin item i goes in.
struct Bins {
  std::vector<std::uint32_t> start;  // per bin its first slot, then the total

  template <class BinsOf> void count(std::size_t bins, std::size_t n, BinsOf&& bins_of) {
    start.assign(bins + 1, 0);
    cursor.assign(kChunks * bins, 0);
    each_chunk(n, [&](std::size_t i, std::uint32_t* count) {
      bins_of(i, [&](std::size_t b) { ++count[b]; });
    });
    // Each chunk's counts become its first slot in each bin.
    std::uint32_t slot = 0;
    for (std::size_t b = 0; b < bins; ++b) {
      start[b] = slot;
      for (std::size_t c = 0; c < kChunks; ++c) slot += std::exchange(cursor[c * bins + b], slot);
    }
    start[bins] = slot;
    items = n;
  }
  std::size_t size() const { return start.empty() ? 0 : start.back(); }
  // put(i, slot) for each bin of item i: slot is its place in the bins.
  template <class BinsOf, class Put> void place(BinsOf&& bins_of, Put&& put) {
    each_chunk(items, [&](std::size_t i, std::uint32_t* next) {
      bins_of(i, [&](std::size_t b) { put(i, next[b]++); });
    });
  }

 private:
  static constexpr std::size_t kChunks = 16;
  // body(i, the chunk's row of cursor) for every item, chunks in parallel.
  template <class F> void each_chunk(std::size_t n, F&& body) {
    tbb::parallel_for(std::size_t(0), kChunks, [&](std::size_t c) {
      std::uint32_t* row = cursor.data() + c * (start.size() - 1);
      for (std::size_t i = n * c / kChunks; i < n * (c + 1) / kChunks; ++i) body(i, row);
    });
  }
  std::vector<std::uint32_t> cursor;  // per chunk, per bin: its count, then its next slot
  std::size_t items = 0;              // count()'s, for place()
};

// The screen's tile^2-pixel tiles, row by row: an item's bins are the tiles its pixels touch.
struct Tiles {
  int width = 0, height = 0, tile = 1, nx = 0, ny = 0;
  Tiles(int w, int h, int tile_side)
      : width(w),
        height(h),
        tile(tile_side),
        nx((w + tile_side - 1) / tile_side),
        ny((h + tile_side - 1) / tile_side) {}
  std::size_t count() const { return std::size_t(nx) * std::size_t(ny); }
  // Tile t's pixels, clipped to the screen.
  PixelRect rect(std::size_t t) const {
    const int x0 = int(t % std::size_t(nx)) * tile, y0 = int(t / std::size_t(nx)) * tile;
    return {x0, y0, std::min(x0 + tile, width) - 1, std::min(y0 + tile, height) - 1};
  }
  // The tile of pixel (x, y).
  std::size_t of(int x, int y) const {
    return std::size_t(x / tile) + std::size_t(y / tile) * std::size_t(nx);
  }
  template <class F> void each(const PixelRect& r, F&& f) const {
    for (int ty = r.y0 / tile; ty <= r.y1 / tile; ++ty)
      for (int tx = r.x0 / tile; tx <= r.x1 / tile; ++tx)
        f(std::size_t(tx) + std::size_t(ty) * std::size_t(nx));
  }
};

}  // namespace voxspan
