#include "render/gl/cell_state_texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "render/gl/bindings.h"
#include "voxspan/error.h"

namespace voxspan {

CellStateTexture::CellStateTexture() : none_(GL_R8UI, glm::ivec3(1)) {
  const std::uint8_t empty = cell::kEmpty;
  none_.upload(GL_RED_INTEGER, GL_UNSIGNED_BYTE, &empty);
}

void CellStateTexture::upload(const CellStatesView& cells) {
  on_ = !cells.empty();
  view_ = cells;
  if (!on_) return;
  if (!(cells.cell_size > 0) || !std::isfinite(cells.cell_size))
    throw make_error("cell states: cell_size = ", cells.cell_size, " is not a positive number");
  for (double o : cells.origin)
    if (!std::isfinite(o)) throw make_error("cell states: origin is not finite");
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_side);
  const glm::ivec3 dims(cells.dims[0], cells.dims[1], cells.dims[2]);
  for (int a = 0; a < 3; ++a) {
    if (dims[a] >= 1 && dims[a] <= max_side) continue;
    // Without an inner full cell, every particle was voxelized and the states only skip
    // empty space: the grid an adapter builds over a far stray particle (1e6 x 1 x 1 cells).
    const std::size_t count = std::size_t(std::max(dims.x, 0)) * std::size_t(std::max(dims.y, 0)) *
                              std::size_t(std::max(dims.z, 0));
    if (std::none_of(cells.states, cells.states + count,
                     [](std::uint8_t c) { return c == cell::kInnerFull; })) {
      on_ = false;
      return;
    }
    throw make_error("cell states: grid of ", dims.x, "x", dims.y, "x", dims.z,
                     " cells has a side outside 1..", max_side,
                     " (the GL's 3D texture limit); coarsen the grid passed to the renderer");
  }
  if (texture_.id() == 0 || texture_.size() != dims) texture_ = gl::Texture3D(GL_R8UI, dims);
  texture_.upload(GL_RED_INTEGER, GL_UNSIGNED_BYTE, cells.states);
  gl::check_error("uploading cell states");
}

void CellStateTexture::bind(const gl::Program& program) const {
  (on_ ? texture_ : none_).bind_unit(binding::kCellStatesUnit);
  program.set("u_cells_on", on_ ? 1u : 0u);
  program.set("u_cells_origin",
              glm::vec3(float(view_.origin[0]), float(view_.origin[1]), float(view_.origin[2])));
  program.set("u_cells_size", float(view_.cell_size));
  program.set("u_cells_dims", glm::ivec3(view_.dims[0], view_.dims[1], view_.dims[2]));
}

}  // namespace voxspan
