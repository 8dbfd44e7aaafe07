#include "tests/render/gl/shading_fixture.h"

#include <algorithm>
#include <cmath>

#include "render/gl/gpu_recorder.h"

namespace voxspan::test {

Renderer& renderer() {
  static Renderer r(shaders());
  return r;
}

SpanImage hand_made(int width, int height, const std::vector<std::vector<Span>>& columns,
                    double near, double far) {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.width = width;
  camera.height = height;
  SpanImage image;
  image.grid = PerspectiveGrid::over(camera, near, far, GridOptions{});
  image.pixels.resize(std::size_t(width) * std::size_t(height));
  for (std::size_t p = 0; p < image.pixels.size(); ++p) {
    const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
    const double scale = image.grid.view().ray_scale(x, y);
    PixelSpans& r = image.pixels[p];
    r.offset = static_cast<std::uint32_t>(image.spans.size());
    double inside = 0;
    for (const Span& s : columns[p]) {
      image.spans.push_back(s);
      inside += (double(s.exit) - double(s.entry)) * scale;
    }
    r.count = r.total = static_cast<std::uint32_t>(columns[p].size());
    r.inside = float(inside);
  }
  return image;
}

GpuResult shade_on_gpu(const SpanImage& spans, const SurfaceOptions& surfaces,
                       const ShadeOptions& shade) {
  Renderer& passes = renderer();  // makes the context first
  static GpuSpanImage gpu;
  gpu.upload(spans);
  GpuResult r;
  gl::GpuRecorder recorder(r.stats, context().has_gpu_timers());
  r.image = passes.shade(gpu, surfaces, shade, recorder).download();
  recorder.collect();
  const GpuSurfaces& s = passes.surfaces();
  r.links = s.download_links(gpu.span_count());
  r.normals = s.download_normals(gpu.span_count());
  r.depths = s.download_depths(gpu);
  if (shade.deep_ao) r.ao = s.download_ao(spans.pixels.size());
  return r;
}

double degrees_between(glm::vec3 a, glm::vec3 b) {
  const glm::dvec3 u = glm::normalize(glm::dvec3(a)), v = glm::normalize(glm::dvec3(b));
  return glm::degrees(2 * std::asin(std::min(1.0, glm::length(u - v) / 2)));
}

}  // namespace voxspan::test
