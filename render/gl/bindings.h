// render/gl/bindings.h - the shader-storage bindings and texture units that several passes share,
// reserved once here, and their #defines for the shaders that include the GLSL declaring them.
// A pass names its own bindings in an enum in its .cpp, numbered on from the end of the last
// shared range its shader includes (from 0 when it includes none), and hands them to its shader
// with gl::defines(), so no shader writes a binding number. Binding numbers are per program:
// every pass binds all its buffers before it dispatches.
#pragma once

#include <epoxy/gl.h>

#include <string>

namespace voxspan::binding {

// The span image: render/gl/span_image.glsl, GpuSpanImage::bind().
enum SpanImage : GLuint { kSpanPixels, kSpanDepths, kSpanImageEnd };

// The surface data beside it: render/gl/passes/surface_data.glsl, GpuSurfaces::bind().
enum Surfaces : GLuint {
  kSpanOwners = kSpanImageEnd,
  kSpanLinks,
  kSurfaceDepths,
  kSpanNormals,
  kPixelAo,
  kWallDepths,  // the backdrop (render/backdrop.h), read by the normals pass for its depths
  kSurfacesEnd,
};

// The shading passes' output and the backdrop they read (render/backdrop.h):
// render/gl/passes/shade_common.glsl.
enum Shade : GLuint { kShadedImage = kSurfacesEnd, kBackdrop, kShadeEnd };

// Texture units: the cell states of render/gl/passes/cell_march.glsl, CellStateTexture::bind().
enum TextureUnit : GLuint { kCellStatesUnit };

// Each range's #defines, with those of the ranges it follows (its GLSL includes theirs).
std::string span_image_defines();
std::string surface_defines();
std::string shade_defines();
std::string cell_state_defines();

}  // namespace voxspan::binding
