#include "render/cpu/cpu_renderer.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "render/model/host.h"
#include "render/stat_names.h"
#include "render/surface_passes.h"
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

SpanImage& CpuRenderer::cast(const Camera& camera, std::span<const ParticleSphere> particles,
                             const CellStatesView& cells, const SpanOptions& options,
                             Recorder& recorder) {
  validate(options);
  const PerspectiveGrid grid = fit_frame(camera, particles, options, recorder);
  auto t = recorder.host(pass::cast);
  const CastCounts counts =
      caster_.run(grid, particles, cells,
                  {options.gap_bridging, options.max_spans, options.use_cell_states}, spans_);
  recorder.count(counter::tiles, counts.tiles);
  recorder.count(counter::cast_cell_boxes, counts.cell_boxes);
  recorder.count(counter::cast_chord_tests, counts.chord_tests);
  recorder.count(counter::spans_stored, std::int64_t(spans_.spans.size()));
  recorder.count(counter::spans_found, counts.spans_found);
  recorder.count(counter::pixels_capped, counts.capped_pixels);
  return spans_;
}

const FloatImage& CpuRenderer::shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                                     const ShadeOptions& shade, Recorder& recorder) {
  this->shade(spans, surfaces, shade, recorder, image_);
  return image_;
}

// The steps of render/surface_passes.h as loops over the model files on the host.
class CpuRenderer::Passes final : public SurfacePasses {
 public:
  Passes(CpuRenderer& r, const SpanImage& spans, model::Host& host, const Tallies& tallies,
         FloatImage& image)
      : r_(r), spans_(spans), host_(host), tallies_(tallies), image_(image) {}

 private:
  Recorder::Scope time(Recorder& recorder, StatName pass) override { return recorder.host(pass); }

  // Each step names its objects as locals: the loops' lambdas then reach them directly, not
  // through this object's members.
  std::int64_t connect(const SurfaceOptions& options) override {
    model::Host& host = host_;
    host.u_fold_step = float(options.fold_step);
    host.fill_per_span(host.links_, [&](model::ivec2 p, model::uint s) {
      return host.connect_span(p, s - host.sd_offset(p));
    });
    return tallies_.unlinkable;
  }

  void filter(int iterations, const SurfaceOptions& options) override {
    if (iterations <= 0) return;
    model::Host& host = host_;
    std::vector<model::vec2>& next = r_.next_depths_;
    host.u_max_iterations = model::uint(filter_iteration_cap(spans_.grid, options));
    host.u_radius = float(options.filter_radius);
    host.u_iteration_scale = float(filter_iteration_scale(spans_.grid, options.filter_radius));
    for (int pass = 0; pass < kFilterPasses; ++pass) {
      host.u_filter_pass = model::uint(pass);
      host.fill_per_span(next,
                         [&](model::ivec2 p, model::uint s) { return host.filter_span(p, s); });
      host.depths_.swap(next);  // pass 0 read the span depths (depths_ empty)
    }
  }

  void normals(const SurfaceOptions& options) override {
    model::Host& host = host_;
    host.u_fold_step = float(options.fold_step);
    host.use_backdrop(r_.backdrop_ != nullptr ? &r_.backdrop_->pixels : nullptr);
    host.build_normals();
  }

  void deep_ao() override {
    model::Host& host = host_;
    host.ao_.assign(spans_.pixels.size(), 1.0f);
    host.each_pixel([&](model::ivec2 p) { host.ao_[host.pixel_index(p)] = host.deep_ao(p); });
  }

  RefractTally shade(const ShadeOptions& options) override {
    model::Host& host = host_;
    const SpanImage& spans = spans_;
    FloatImage& image = image_;
    RefractTally tally;
    tally.dispatches =
        refract_dispatch_limit(spans.width(), spans.height(), tallies_.most_spans, options);
    const bool refractive = options.mode == ShadeMode::refractive;
    const Backdrop* walls = r_.backdrop_;
    if (walls != nullptr && refractive) r_.pyramid_.update(*walls);
    host.use_backdrop(walls == nullptr ? nullptr
                      : refractive     ? &r_.pyramid_.texels()
                                       : &walls->pixels);
    if (refractive) host.gather_block_bounds();
    else if (walls == nullptr) host.use_background(r_.background_);
    if (image.width != spans.width() || image.height != spans.height())
      image = FloatImage(spans.width(), spans.height());
    tally.unfinished = host.shade(options.mode, tally.dispatches, options.march_budget, image);
    return tally;
  }

  CpuRenderer& r_;
  const SpanImage& spans_;
  model::Host& host_;
  const Tallies& tallies_;
  FloatImage& image_;
};

void CpuRenderer::shade(const SpanImage& spans, const SurfaceOptions& surfaces,
                        const ShadeOptions& shade, Recorder& recorder, FloatImage& image) {
  validate(surfaces);
  model::Host host(spans, model::shade_uniforms(shade));
  // The buffers of the last frame, back to buffers_ however this one ends.
  struct Lend {
    model::Host& host;
    model::HostBuffers& buffers;
    Lend(model::Host& h, model::HostBuffers& b) : host(h), buffers(b) { host.swap_buffers(b); }
    ~Lend() { host.swap_buffers(buffers); }
  } lend(host, buffers_);
  host.depths_.clear();  // the span depths until the filter runs
  const Tallies tallies = tally(spans);
  Passes passes(*this, spans, host, tallies, image);
  passes.run(spans.grid, !spans.spans.empty(), surfaces, shade, recorder);
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
