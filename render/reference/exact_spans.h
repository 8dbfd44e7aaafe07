// render/reference/exact_spans.h - the exact CPU reference for the span image: for each pixel's
// centre ray, the exact depth intervals of the union of the particle spheres (analytic
// ray-sphere, in double), with inner-full simulation cells counted as inside and the same gap
// bridging and span cap as the GPU ([ZD15] sec. 3.1, 3.2, 4.3, 4.4). It is the yardstick
// for every accuracy figure: the GPU's spans differ from these by the voxelization alone.
//
// Same convention as the GPU (render/span_image.h): depths are view z, clipped to the grid's
// [near, grid_far]; `inside` is the length along the ray. Inner-empty cells are not consulted:
// the classification guarantees no particle reaches into them, so they hold no fluid anyway.
// Candidates come from 8x8-pixel screen bins; rows run in parallel with oneTBB.
// Cost: O(pixels x candidates per bin), fine for test images and benchmark accuracy checks.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/perspective_grid.h"
#include "render/span_image.h"
#include "voxspan/cell_states.h"

namespace voxspan {

struct ReferenceOptions {
  double gap_bridging = 0;      // g: gaps shorter than this along the ray (world units) close
  std::uint32_t max_spans = 0;  // cap on stored spans per pixel; 0 = no cap
};

// Spans in the frame of `grid` (usually the GPU image's grid, so both share near and layers).
SpanImage exact_spans(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                      const CellStatesView& cells, const ReferenceOptions& options);

// The exact outward world normals of a span's entry and exit: the normal of the sphere whose
// surface the boundary lies on (for a capped pixel's extended span, the exit of the last span
// found); zero where the boundary lies on no sphere (an inner-full cell, the near or far plane).
struct SpanNormals {
  glm::vec3 entry{0.0f};
  glm::vec3 exit{0.0f};
};

// The same spans, and in `normals` (resized to the span count) each span's exact normals.
SpanImage exact_spans(const PerspectiveGrid& grid, std::span<const ParticleSphere> particles,
                      const CellStatesView& cells, const ReferenceOptions& options,
                      std::vector<SpanNormals>* normals);

}  // namespace voxspan
