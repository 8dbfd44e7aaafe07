// render/gl/passes/compress.h - compresses one tile's voxel columns into the span image
// (render/gl/passes/compress.comp; [ZD15] sec. 3.1, 3.2, 4.3, 4.4): count pass, prefix sum of
// the per-pixel counts, one read-back of the tile's span total to size the span buffer, copy
// pass, and a re-scan of the few columns with more spans than the scratch holds. One thread per
// column; gaps shorter than g close; inner-empty cells are skipped and inner-full cells count as
// inside when cell states are on. Reads: the tile's bits, the cell states. Writes: the tile's pixel
// records and spans in the GpuSpanImage; per-frame tallies of capped pixels. Cost: one coalesced
// read of the tile's bits (a second only for columns storing more spans than the scratch holds), a
// prefix sum over the tile's pixels, a 4-byte read-back.
#pragma once

#include <cstdint>

#include "render/gl/cell_state_texture.h"
#include "render/gl/gpu_span_image.h"
#include "render/gl/objects.h"
#include "render/gl/passes/prefix_sum.h"
#include "render/gl/shader_library.h"
#include "render/gl/tiling.h"

namespace voxspan {

// Where the compress pass puts a span's entry and exit within the voxels at its ends: their
// outer faces (the span holds every set voxel whole) or their centres (each end half a voxel
// in, an unbiased estimate of a surface that lies anywhere in its voxel).
enum class SpanEdges { outer, middle };

struct CompressSettings {
  double gap_bridging = 0;      // g, world units along the ray
  std::uint32_t max_spans = 0;  // cap on stored spans per pixel; 0 = none
  int scratch_spans = 8;        // spans per pixel kept from the count pass
  SpanEdges span_edges = SpanEdges::outer;
};

struct CompressTallies {
  std::int64_t capped_pixels = 0;
  std::int64_t spans_past_caps = 0;  // found but folded into an extended last span
};

class CompressPass {
 public:
  explicit CompressPass(const gl::ShaderLibrary& shaders);

  // Zeroes the per-frame tallies.
  void begin_frame();
  // Appends the tile's spans to `image` from span number `span_base`; returns how many.
  // `depth_bounds`: BinPass::depth_bounds() of this frame.
  std::uint32_t run(const gl::Buffer& bits, const gl::Buffer& depth_bounds,
                    const TileLayout& layout, const TileRect& tile, const CellStateTexture& cells,
                    const CompressSettings& settings, GpuSpanImage& image, std::uint32_t span_base,
                    PrefixSumPass& prefix_sum, std::size_t max_binding_bytes);
  CompressTallies tallies() const;

 private:
  void set_uniforms(const gl::Program& p, const TileLayout& layout, const TileRect& tile,
                    const CellStateTexture& cells, const CompressSettings& settings,
                    const GpuSpanImage& image) const;

  gl::Program count_, copy_, rescan_;
  gl::Buffer scratch_spans_, scratch_counts_, scratch_exits_, stats_, rescan_list_;
};

}  // namespace voxspan
