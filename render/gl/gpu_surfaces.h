// render/gl/gpu_surfaces.h - the per-span surface data the passes after the voxelization build
// beside the span image ([ZD15] sec. 3.3-3.6, 4.5), on the GPU, indexed by span number like
// the span image's depths:
//   owners   uint per span: its pixel x + y * width (connect)
//   links    uvec2 per span: the entry's and the exit's link words (connect; the byte layout is
//            in render/model/links.glsl)
//   depths   vec2 per span: the filtered (entry, exit) depths (filter; when the filter is off
//            the span image's own depths serve)
//   normals  uvec2 per span: the entry's and the exit's outward world normals, octahedral
//            (normals; render/model/octahedral.glsl)
//   ao       float per pixel: deep ambient occlusion of the front surface (deep AO)
// render/gl/passes/surface_data.glsl declares the same buffers for shaders; bind() puts them and
// the span image at the bindings render/gl/bindings.h reserves.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl/gpu_span_image.h"
#include "render/gl/objects.h"

namespace voxspan {

class GpuSurfaces {
 public:
  // Sizes every buffer for the image's spans and pixels (grows only) and forgets the filtered
  // depths.
  void prepare(const GpuSpanImage& image);

  // Binds the span image and the surface buffers for a pass.
  void bind(const GpuSpanImage& image) const;

  const gl::Buffer& owners() const { return owners_; }
  const gl::Buffer& links() const { return links_; }
  const gl::Buffer& normals() const { return normals_; }
  const gl::Buffer& ao() const { return ao_; }
  // The surface depths the normals and shading read: filtered, or the span image's.
  const gl::Buffer& depths(const GpuSpanImage& image) const;
  bool filtered() const { return filtered_ >= 0; }

  // For the filter: its two ping-pong buffers, and which holds the result (-1: none).
  gl::Buffer& filter_buffer(int i) { return filter_[i]; }
  void set_filtered(int i) { filtered_ = i; }

  // Read-backs for tests and the CPU paths.
  std::vector<glm::uvec2> download_links(std::size_t spans) const;
  std::vector<glm::uvec2> download_normals(std::size_t spans) const;
  std::vector<glm::vec2> download_depths(const GpuSpanImage& image) const;
  std::vector<float> download_ao(std::size_t pixels) const;

 private:
  gl::Buffer owners_, links_, normals_, ao_;
  gl::Buffer filter_[2];
  int filtered_ = -1;
};

}  // namespace voxspan
