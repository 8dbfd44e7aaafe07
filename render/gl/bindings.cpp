#include "render/gl/bindings.h"

#include "render/gl/shader_library.h"

namespace voxspan::binding {

std::string span_image_defines() {
  return gl::defines({{"SPAN_PIXELS_BINDING", kSpanPixels}, {"SPAN_DEPTHS_BINDING", kSpanDepths}});
}

std::string surface_defines() {
  return span_image_defines() + gl::defines({{"SPAN_OWNERS_BINDING", kSpanOwners},
                                             {"SPAN_LINKS_BINDING", kSpanLinks},
                                             {"SURFACE_DEPTHS_BINDING", kSurfaceDepths},
                                             {"SPAN_NORMALS_BINDING", kSpanNormals},
                                             {"PIXEL_AO_BINDING", kPixelAo},
                                             {"WALL_DEPTHS_BINDING", kWallDepths}});
}

std::string shade_defines() {
  return surface_defines() +
         gl::defines({{"SHADED_IMAGE_BINDING", kShadedImage}, {"BACKDROP_BINDING", kBackdrop}});
}

std::string cell_state_defines() { return gl::defines({{"CELL_STATES_UNIT", kCellStatesUnit}}); }

}  // namespace voxspan::binding
