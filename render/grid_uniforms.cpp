#include "render/grid_uniforms.h"

namespace voxspan {

void set_grid_uniforms(const gl::Program& program, const PerspectiveGrid& grid) {
  const ViewFrame& v = grid.view();
  program.set("u_eye", glm::vec3(v.eye));
  program.set("u_right", glm::vec3(v.right));
  program.set("u_up", glm::vec3(v.up));
  program.set("u_forward", glm::vec3(v.forward));
  program.set("u_tan_half", glm::vec2(float(v.tan_half_x), float(v.tan_half_y)));
  program.set("u_image", glm::ivec2(v.width, v.height));
  program.set("u_near", float(grid.near()));
  program.set("u_log2_step", float(grid.log2_step()));
  program.set("u_inv_log2_step", grid.empty() ? 0.0f : float(1.0 / grid.log2_step()));
  program.set("u_layers", static_cast<unsigned>(grid.layers()));
  program.set("u_grid_far", float(grid.grid_far()));
}

}  // namespace voxspan
