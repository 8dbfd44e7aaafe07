#include "render/reference/reference_shading.h"

#include <algorithm>
#include <utility>

#include "render/model/host.h"

namespace voxspan {

std::vector<glm::uvec2> reference_links(const SpanImage& spans, double fold_step) {
  model::Host host(spans, model::ShadeUniforms{});
  host.u_fold_step = float(fold_step);
  return host.per_span(
      [&](model::ivec2 p, model::uint s) { return host.connect_span(p, s - host.sd_offset(p)); });
}

std::vector<glm::uvec2> reference_normals(const SpanImage& spans,
                                          const std::vector<glm::uvec2>& links, double fold_step) {
  model::Host host(spans, model::ShadeUniforms{});
  host.links_ = links;
  host.u_fold_step = float(fold_step);
  host.build_normals();
  return std::move(host.normals_);
}

std::vector<glm::uvec2> encode_exact_normals(const std::vector<SpanNormals>& normals,
                                             const std::vector<glm::uvec2>& sobel) {
  std::vector<glm::uvec2> out(sobel);
  const SpanImage empty;
  model::Host host(empty, model::ShadeUniforms{});
  for (std::size_t s = 0; s < normals.size() && s < out.size(); ++s) {
    if (glm::length(normals[s].entry) > 0) out[s].x = host.encode_normal(normals[s].entry);
    if (glm::length(normals[s].exit) > 0) out[s].y = host.encode_normal(normals[s].exit);
  }
  return out;
}

std::vector<float> reference_ao(const SpanImage& spans, const std::vector<glm::uvec2>& links,
                                const std::vector<glm::uvec2>& normals,
                                const ShadeOptions& options) {
  model::Host host(spans, model::shade_uniforms(options));
  host.links_ = links;
  host.normals_ = normals;
  std::vector<float> ao(std::size_t(spans.width()) * std::size_t(spans.height()), 1.0f);
  host.each_pixel([&](model::ivec2 p) { ao[host.pixel_index(p)] = host.deep_ao(p); });
  return ao;
}

FloatImage reference_shading(const SpanImage& spans, const ShadeOptions& options,
                             const std::vector<glm::uvec2>* normals) {
  model::Host host(spans, model::shade_uniforms(options));
  host.links_ = reference_links(spans);
  host.normals_ = normals != nullptr ? *normals : reference_normals(spans, host.links_);
  if (options.deep_ao) host.ao_ = reference_ao(spans, host.links_, host.normals_, options);
  FloatImage image(spans.width(), spans.height());
  std::uint32_t most_spans = 0;
  for (const PixelSpans& p : spans.pixels) most_spans = std::max(most_spans, p.count);
  const int dispatches = refract_dispatch_limit(spans.width(), spans.height(), most_spans, options);
  if (options.mode == ShadeMode::refractive) host.gather_block_bounds();
  host.shade(options.mode, dispatches, options.march_budget, image);
  return image;
}

}  // namespace voxspan
