// render/reference/reference_shading.h - the passes after the voxelization on the CPU, for the
// exact reference (render/reference/exact_spans.h): surface links (Listing 1), Sobel normals
// along them, deep AO and the three shading modes, computed by the very model files the GPU
// passes run (render/model/*.glsl, compiled as C++: render/model/glsl_cpp.h). Applied to the
// exact spans, the difference from the GPU's picture measures the voxelization alone; with the
// exact sphere normals instead of Sobel ones (exact_spans(..., &normals)), it also shows what
// screen-space normals cost. No filter: the reference's depths are exact already.
// Cost: O(pixels x spans) on oneTBB threads; refraction marches each pixel's ray to the end.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/float_image.h"
#include "render/reference/exact_spans.h"
#include "render/shade_options.h"
#include "render/span_image.h"

namespace voxspan {

// Listing 1 on a span image, not across folds deeper than `fold_step` (SurfaceOptions): per
// span the (entry, exit) link words, as ConnectPass writes them.
std::vector<glm::uvec2> reference_links(const SpanImage& spans, double fold_step = 0);

// Sobel normals along those links on the span depths (at crests, by `fold_step`, their
// neighbours'): per span the (entry, exit) octahedral words of the outward world normals, as
// NormalsPass writes them.
std::vector<glm::uvec2> reference_normals(const SpanImage& spans,
                                          const std::vector<glm::uvec2>& links,
                                          double fold_step = 0);

// The same words from exact normals (world space; a zero normal, e.g. a boundary from a cell or
// the near plane, falls back to the Sobel word in `sobel`).
std::vector<glm::uvec2> encode_exact_normals(const std::vector<SpanNormals>& normals,
                                             const std::vector<glm::uvec2>& sobel);

// The picture: links, normals (Sobel, or `normals` when given: per span the encoded words),
// deep AO when options.deep_ao, and the mode's shading, at every pixel.
FloatImage reference_shading(const SpanImage& spans, const ShadeOptions& options,
                             const std::vector<glm::uvec2>* normals = nullptr);

// Deep AO of every pixel (1 where there is no fluid), as DeepAoPass writes it.
std::vector<float> reference_ao(const SpanImage& spans, const std::vector<glm::uvec2>& links,
                                const std::vector<glm::uvec2>& normals,
                                const ShadeOptions& options);

}  // namespace voxspan
