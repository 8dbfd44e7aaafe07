#include "render/gl/gpu_surfaces.h"

#include <algorithm>

#include "render/gl/bindings.h"

namespace voxspan {
namespace {
// Every buffer holds at least this much, so a frame without spans still binds real storage.
constexpr std::size_t kMinBytes = 16;
}  // namespace

void GpuSurfaces::prepare(const GpuSpanImage& image) {
  const std::size_t spans = image.span_count();
  const std::size_t pixels = std::size_t(image.width()) * std::size_t(image.height());
  owners_.reserve(std::max(kMinBytes, spans * 4));
  links_.reserve(std::max(kMinBytes, spans * 8));
  normals_.reserve(std::max(kMinBytes, spans * 8));
  ao_.reserve(std::max(kMinBytes, pixels * 4));
  filtered_ = -1;
}

const gl::Buffer& GpuSurfaces::depths(const GpuSpanImage& image) const {
  return filtered_ >= 0 ? filter_[filtered_] : image.spans();
}

void GpuSurfaces::bind(const GpuSpanImage& image) const {
  image.bind();
  gl::bind_storage({{owners_, binding::kSpanOwners},
                    {links_, binding::kSpanLinks},
                    {depths(image), binding::kSurfaceDepths},
                    {normals_, binding::kSpanNormals},
                    {ao_, binding::kPixelAo}});
}

std::vector<glm::uvec2> GpuSurfaces::download_links(std::size_t spans) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return links_.read<glm::uvec2>(spans);
}

std::vector<glm::uvec2> GpuSurfaces::download_normals(std::size_t spans) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return normals_.read<glm::uvec2>(spans);
}

std::vector<glm::vec2> GpuSurfaces::download_depths(const GpuSpanImage& image) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return depths(image).read<glm::vec2>(image.span_count());
}

std::vector<float> GpuSurfaces::download_ao(std::size_t pixels) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return ao_.read<float>(pixels);
}

}  // namespace voxspan
