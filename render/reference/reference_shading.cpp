#include "render/reference/reference_shading.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "render/model/cpp_host.h"
#include "render/model/shade_uniforms.h"

namespace voxspan {
namespace model {
namespace {

// The CPU host of the shared model files: the span data they read through sd_*, the uniforms
// as members, and the model files' functions as its own (render/model/cpp_host.h).
class ReferenceHost : public GridUniforms, public ShadeUniforms {
 public:
  ReferenceHost(const SpanImage& spans, const ShadeUniforms& shade)
      : GridUniforms(grid_uniforms(spans.grid)), ShadeUniforms(shade), spans_(spans) {}

  std::vector<uvec2> links_, normals_;
  std::vector<float> ao_;

  uint sd_count(ivec2 p) const { return record(p).count; }
  uint sd_offset(ivec2 p) const { return record(p).offset; }
  float sd_inside(ivec2 p) const { return record(p).inside; }
  vec2 sd_raw_depths(uint span) const { return vec2(spans_.spans[span].entry, spans_.spans[span].exit); }
  vec2 sd_depths(uint span) const { return sd_raw_depths(span); }
  uvec2 sd_links(uint span) const { return links_[span]; }
  uvec2 sd_normals(uint span) const { return normals_[span]; }
  float sd_ao(ivec2 p) const { return ao_[pixel_index(p)]; }

  std::size_t pixel_index(ivec2 p) const {
    return std::size_t(p.x) + std::size_t(p.y) * std::size_t(u_image.x);
  }

#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"
#include "render/model/environment.glsl"
#include "render/model/lighting.glsl"
#include "render/model/shade_modes.glsl"
#include "render/model/column_march.glsl"
#include "render/model/deep_ao.glsl"

  // f(p, span index) for every span, rows in parallel.
  template <class F>
  std::vector<uvec2> per_span(F&& f) {
    std::vector<uvec2> out(spans_.spans.size());
    each_pixel([&](ivec2 p) {
      for (uint k = 0; k < sd_count(p); ++k) out[sd_offset(p) + k] = f(p, sd_offset(p) + k);
    });
    return out;
  }

  template <class F>
  void each_pixel(F&& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, u_image.y), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y != rows.end(); ++y)
        for (int x = 0; x < u_image.x; ++x) f(ivec2(x, y));
    });
  }

 private:
  const PixelSpans& record(ivec2 p) const { return spans_.pixels[pixel_index(p)]; }
  const SpanImage& spans_;
};

}  // namespace
}  // namespace model

std::vector<glm::uvec2> reference_links(const SpanImage& spans) {
  model::ReferenceHost host(spans, model::ShadeUniforms{});
  return host.per_span([&](model::ivec2 p, model::uint s) { return host.connect_span(p, s - host.sd_offset(p)); });
}

std::vector<glm::uvec2> reference_normals(const SpanImage& spans, const std::vector<glm::uvec2>& links) {
  model::ReferenceHost host(spans, model::ShadeUniforms{});
  host.links_ = links;
  return host.per_span([&](model::ivec2 p, model::uint s) { return host.span_normal_words(p, s); });
}

std::vector<glm::uvec2> encode_exact_normals(const std::vector<SpanNormals>& normals,
                                             const std::vector<glm::uvec2>& sobel) {
  std::vector<glm::uvec2> out(sobel);
  const SpanImage empty;
  model::ReferenceHost host(empty, model::ShadeUniforms{});
  for (std::size_t s = 0; s < normals.size() && s < out.size(); ++s) {
    if (glm::length(normals[s].entry) > 0) out[s].x = host.encode_normal(normals[s].entry);
    if (glm::length(normals[s].exit) > 0) out[s].y = host.encode_normal(normals[s].exit);
  }
  return out;
}

std::vector<float> reference_ao(const SpanImage& spans, const std::vector<glm::uvec2>& links,
                                const std::vector<glm::uvec2>& normals, const ShadeOptions& options) {
  model::ReferenceHost host(spans, model::shade_uniforms(options));
  host.links_ = links;
  host.normals_ = normals;
  std::vector<float> ao(std::size_t(spans.width()) * std::size_t(spans.height()), 1.0f);
  host.each_pixel([&](model::ivec2 p) { ao[host.pixel_index(p)] = host.deep_ao(p); });
  return ao;
}

FloatImage reference_shading(const SpanImage& spans, const ShadeOptions& options,
                             const std::vector<glm::uvec2>* normals) {
  model::ReferenceHost host(spans, model::shade_uniforms(options));
  host.links_ = reference_links(spans);
  host.normals_ = normals != nullptr ? *normals : reference_normals(spans, host.links_);
  if (options.deep_ao) host.ao_ = reference_ao(spans, host.links_, host.normals_, options);
  FloatImage image(spans.width(), spans.height());
  const int dispatches = refract_dispatch_limit(spans.width(), spans.height(), options);
  host.each_pixel([&](model::ivec2 p) {
    model::vec3 c(0.0f);
    switch (options.mode) {
      case ShadeMode::opaque: c = host.shade_opaque(p); break;
      case ShadeMode::translucent: c = host.shade_translucent(p); break;
      case ShadeMode::refractive: {
        // The GPU's dispatches, one after the other: the same budget per resumption.
        model::ReferenceHost::RayState s = host.ray_start(p);
        for (int d = 0; d < dispatches && s.marching; ++d) s = host.march(s, options.march_budget);
        if (s.marching) s = host.ray_leave(s);
        c = s.color;
        break;
      }
    }
    image.set(p.x, p.y, glm::vec4(c, 1.0f));
  });
  return image;
}

}  // namespace voxspan
