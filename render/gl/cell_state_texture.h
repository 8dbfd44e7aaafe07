// render/gl/cell_state_texture.h - the simulation grid's cell states on the GPU (an R8UI 3D
// texture, voxspan/cell_states.h layout) for the compress pass's march ([ZD15] sec. 4.3),
// and the uniforms of render/gl/passes/cell_march.glsl. The texture is reused while the grid's
// dimensions stay the same.
#pragma once

#include "render/gl/objects.h"
#include "voxspan/cell_states.h"

namespace voxspan {

class CellStateTexture {
 public:
  CellStateTexture();
  // Uploads the states (throws voxspan::Error naming the limit when a side exceeds the GL's
  // 3D texture size and a cell is inner and full; with none, the cells go off: they would
  // skip only empty space);
  // an empty view switches the cells off.
  void upload(const CellStatesView& cells);
  bool on() const { return on_; }
  // Binds the texture to its unit (render/gl/bindings.h) and sets u_cells_*.
  void bind(const gl::Program& program) const;

 private:
  gl::Texture3D texture_;
  gl::Texture3D none_;  // 1x1x1, bound when off so the sampler is always complete
  CellStatesView view_;
  bool on_ = false;
};

}  // namespace voxspan
