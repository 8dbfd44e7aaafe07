#include "render/cpu/cpu_renderer.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "render/model/cpu_host.h"
#include "render/passes/filter.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

struct Tallies {
  std::int64_t unlinkable = 0;   // spans past the links' reach (VX_LINK_MAX_INDEX)
  std::uint32_t most_spans = 0;  // in one pixel
};

// What the connect and shade passes report or size themselves by, in one parallel pass over
// the pixels (serial, such a loop was about 0.5 % of the renderer's perf samples, each).
Tallies tally(const SpanImage& spans) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, spans.pixels.size(), 16384), Tallies{},
      [&](const tbb::blocked_range<std::size_t>& range, Tallies t) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const std::uint32_t n = spans.pixels[i].count;
          t.unlinkable += n > VX_LINK_MAX_INDEX + 1u ? n - VX_LINK_MAX_INDEX - 1u : 0;
          t.most_spans = std::max(t.most_spans, n);
        }
        return t;
      },
      [](Tallies a, const Tallies& b) {
        return Tallies{a.unlinkable + b.unlinkable, std::max(a.most_spans, b.most_spans)};
      });
}

}  // namespace

const SpanImage& CpuRenderer::cast(const Camera& camera, std::span<const ParticleSphere> particles,
                                   const CellStatesView& cells, const VoxelizeOptions& options,
                                   gl::PassTimer& timer, FrameStats& stats) {
  validate(options);
  const PerspectiveGrid grid = fit_frame(camera, particles, options, timer, stats);
  auto t = timer.cpu("cast");
  const CastCounts counts =
      caster_.run(grid, particles, cells,
                  {options.gap_bridging, options.max_spans, options.use_cell_states}, spans_);
  stats.set_count("tiles", counts.tiles);
  stats.set_count("cast.cell_boxes", counts.cell_boxes);
  stats.set_count("cast.chord_tests", counts.chord_tests);
  stats.set_count("spans.stored", std::int64_t(spans_.spans.size()));
  stats.set_count("spans.found", counts.spans_found);
  stats.set_count("pixels.capped", counts.capped_pixels);
  return spans_;
}

const FloatImage& CpuRenderer::shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                                     const ShadeOptions& shade, gl::PassTimer& timer,
                                     FrameStats& stats) {
  this->shade(spans, surfaces, shade, timer, stats, image_);
  return image_;
}

void CpuRenderer::shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                        const ShadeOptions& shade, gl::PassTimer& timer, FrameStats& stats,
                        FloatImage& image) {
  validate(surfaces);
  validate(shade);
  model::CpuHost host(spans, model::shade_uniforms(shade));
  // The buffers of the last frame, back to buffers_ however this one ends.
  struct Lend {
    model::CpuHost& host;
    model::HostBuffers& buffers;
    Lend(model::CpuHost& h, model::HostBuffers& b) : host(h), buffers(b) { host.swap_buffers(b); }
    ~Lend() { host.swap_buffers(buffers); }
  } lend(host, buffers_);
  host.depths_.clear();  // the span depths until the filter runs
  const Tallies tallies = tally(spans);
  {
    auto t = timer.cpu("connect");
    host.fill_per_span(host.links_, [&](model::ivec2 p, model::uint s) {
      return host.connect_span(p, s - host.sd_offset(p));
    });
    stats.set_count("links.unlinkable_spans", tallies.unlinkable);
  }
  {
    auto t = timer.cpu("filter");
    const int iterations = spans.spans.empty() ? 0 : FilterPass::iterations(spans.grid, surfaces);
    host.u_max_iterations = model::uint(surfaces.max_iterations);
    host.u_radius = float(surfaces.filter_radius);
    host.u_iteration_scale = float(FilterPass::iteration_scale(spans.grid, surfaces.filter_radius));
    for (int pass = 0; iterations > 0 && pass < FilterPass::kPasses; ++pass) {
      host.u_filter_pass = model::uint(pass);
      host.fill_per_span(next_depths_,
                         [&](model::ivec2 p, model::uint s) { return host.filter_span(p, s); });
      host.depths_.swap(next_depths_);  // pass 0 read the span depths (depths_ empty)
    }
    stats.set_count("filter.iterations", iterations);
  }
  {
    auto t = timer.cpu("normals");
    host.fill_per_span(host.normals_,
                       [&](model::ivec2 p, model::uint s) { return host.span_normal_words(p, s); });
  }
  if (shade.deep_ao) {
    auto t = timer.cpu("deep_ao");
    host.ao_.assign(spans.pixels.size(), 1.0f);
    host.each_pixel([&](model::ivec2 p) { host.ao_[host.pixel_index(p)] = host.deep_ao(p); });
  }
  auto t = timer.cpu("shade");
  const int dispatches =
      refract_dispatch_limit(spans.width(), spans.height(), tallies.most_spans, shade);
  if (shade.mode == ShadeMode::refractive) host.gather_block_bounds();
  else host.use_background(background_);
  if (image.width != spans.width() || image.height != spans.height())
    image = FloatImage(spans.width(), spans.height());
  std::atomic<std::int64_t> unfinished{0};
  host.each_pixel([&](model::ivec2 p) {
    bool left = false;
    const model::vec3 c = host.shade_pixel(p, shade.mode, dispatches, shade.march_budget, left);
    if (left) ++unfinished;
    image.set(p.x, p.y, glm::vec4(c, 1.0f));
  });
  if (shade.mode == ShadeMode::refractive) {
    stats.set_count("refract.dispatches", dispatches);
    stats.set_count("refract.unfinished", unfinished.load());
  }
}

void CpuRenderer::first_hit(const SpanImage& spans, FloatImage& out,
                            std::span<const glm::vec2> depths) {
  if (!depths.empty() && depths.size() != spans.spans.size())
    throw make_error("first_hit: ", depths.size(), " surface depths for ", spans.spans.size(),
                     " spans");
  if (out.width != spans.width() || out.height != spans.height())
    out = FloatImage(spans.width(), spans.height());
  const model::GridUniforms g = model::grid_uniforms(spans.grid);
  for (int y = 0; y < spans.height(); ++y)
    for (int x = 0; x < spans.width(); ++x) {
      const PixelSpans& p = spans.pixel(x, y);
      float distance = 0.0f;
      if (p.count > 0)
        distance = (depths.empty() ? spans.spans[p.offset].entry : depths[p.offset].x) *
                   g.ray_scale(model::ivec2(x, y));
      out.set(x, y, glm::vec4(distance, 0.0f, 0.0f, 0.0f));
    }
}

}  // namespace voxspan
