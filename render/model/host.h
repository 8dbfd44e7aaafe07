// render/model/host.h - the shared model files (render/model/*.glsl, written in
// render/model/glsl_cpp.h's subset) compiled as C++: a span image in host memory and its
// per-span surface data, read through the sd_* accessors the model files call, the uniforms as
// members, and the model files' functions as its own. The CPU renderer
// (render/cpu/cpu_renderer.h) runs every pass after its cast through it, the exact reference
// (render/reference/reference_shading.h) the same rules, and tests call single model functions
// on it.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "render/backdrop.h"
#include "render/float_image.h"
#include "render/model/glsl_cpp.h"
#include "render/model/shade_uniforms.h"
#include "render/shade_options.h"
#include "render/span_image.h"

namespace voxspan::model {

// How a refracted ray ended: what render/model/column_march.glsl's end_light reads of its RayState.
struct RayEnd {
  vec4 end;  // ray_end's, which the neighbours read too
  vec3 throughput;
  vec3 anchor;  // view space: where it left from, when it left
  bool bent;    // by the fluid, once at least
};

// The host's per-frame vectors, which a caller keeps from frame to frame and swaps in and out
// (Host::swap_buffers), so that a steady frame allocates nothing.
struct HostBuffers {
  std::vector<uvec2> links, normals;
  std::vector<float> ao;
  std::vector<vec2> depths, block_bounds, block_inside;
  std::vector<RayEnd> ends;
};

// What lies behind every pixel (shade_modes.glsl's sd_background), which a caller keeps from
// frame to frame: in situ a view's camera seldom moves, and the environment behind the pixels
// was about 3/4 of the opaque shade. Filled on the second frame in a row with the same rays
// and environment, so that a camera that moves every frame pays a comparison and no fill.
struct BackgroundCache {
  GridUniforms rays;         // the last frame's (GridUniforms::same_rays)
  ShadeUniforms shade;       // the last frame's: any change drops the colours
  std::vector<vec3> colors;  // per pixel; empty: not filled for `rays` and `shade`
};

class Host : public GridUniforms, public ShadeUniforms {
 public:
  Host(const SpanImage& spans, const ShadeUniforms& shade)
      : GridUniforms(grid_uniforms(spans.grid)), ShadeUniforms(shade), spans_(spans) {}

  // Per span (entry, exit) link and normal words; per pixel deep AO; per span the surface
  // depths after the filter (empty: the span depths): filled by the caller.
  std::vector<uvec2> links_, normals_;
  std::vector<float> ao_;
  std::vector<vec2> depths_;
  // render/model/surface_filter.glsl's uniforms.
  uint u_filter_pass = 0u, u_max_iterations = 0u;
  float u_radius = 0.0f, u_iteration_scale = 0.0f;
  // render/model/links.glsl's: 0, no folds.
  float u_fold_step = 0.0f;
  // Refraction's, per pixel (shade fills them): how its ray ended.
  std::vector<RayEnd> ends_;

  uint sd_count(ivec2 p) const { return record(p).count; }
  uint sd_offset(ivec2 p) const { return record(p).offset; }
  float sd_inside(ivec2 p) const { return record(p).inside; }
  vec2 sd_raw_depths(uint span) const {
    return vec2(spans_.spans[span].entry, spans_.spans[span].exit);
  }
  vec2 sd_depths(uint span) const { return depths_.empty() ? sd_raw_depths(span) : depths_[span]; }
  uvec2 sd_links(uint span) const { return links_[span]; }
  uvec2 sd_normals(uint span) const { return normals_[span]; }
  uint sd_normal_word(uint span, uint end) const { return normals_[span][int(end)]; }
  float sd_ao(ivec2 p) const { return ao_[pixel_index(p)]; }
  vec2 sd_block_bounds(ivec2 block) const {
    return block_bounds_[std::size_t(block.x) + std::size_t(block.y) * std::size_t(blocks_x_)];
  }
  vec2 sd_block_inside(ivec2 block) const {
    return block_inside_[std::size_t(block.x) + std::size_t(block.y) * std::size_t(blocks_x_)];
  }

  std::size_t pixel_index(ivec2 p) const {
    return std::size_t(p.x) + std::size_t(p.y) * std::size_t(u_image.x);
  }
  vec4 sd_backdrop(ivec2 p) const { return (*backdrop_)[pixel_index(p)]; }
  vec4 sd_backdrop_texel(uint i) const { return (*backdrop_)[i]; }
  vec4 sd_ray_end(ivec2 p) const { return ends_[pixel_index(p)].end; }
  float sd_wall_depth(ivec2 p) const {
    return backdrop_ != nullptr ? (*backdrop_)[pixel_index(p)].w : 3.0e38f;
  }
  vec3 sd_background(ivec2 p, vec3 dir) {
    if (u_use_backdrop != 0) return vec3(sd_backdrop(p));
    return background_ != nullptr ? (*background_)[pixel_index(p)] : environment(u_eye, dir);
  }
  // The frame's backdrop with its pyramid (render/backdrop.h, backdrop_pyramid; null: none),
  // kept by the caller while it shades.
  void use_backdrop(const std::vector<vec4>* pixels) {
    backdrop_ = pixels;
    u_use_backdrop = pixels != nullptr ? 1 : 0;
  }
  // Looks sd_background up in `cache` when this frame's rays and environment are the last
  // frame's (filling it the first time), else computes it per pixel.
  void use_background(BackgroundCache& cache) {
    background_ = nullptr;
    if (!same_rays(cache.rays) || !(cache.shade == static_cast<const ShadeUniforms&>(*this))) {
      cache.rays = *this;
      cache.shade = *this;
      cache.colors.clear();
      return;
    }
    if (cache.colors.empty()) {
      cache.colors.resize(std::size_t(u_image.x) * std::size_t(u_image.y));
      each_pixel(
          [&](ivec2 p) { cache.colors[pixel_index(p)] = environment(u_eye, pixel_direction(p)); });
    }
    background_ = &cache.colors;
  }

#include "render/model/links.glsl"
#include "render/model/octahedral.glsl"
#include "render/model/surface_geometry.glsl"
#include "render/model/surface_filter.glsl"
#include "render/model/environment.glsl"
#include "render/model/lighting.glsl"
#include "render/model/shade_modes.glsl"
#include "render/model/column_march.glsl"
#include "render/model/deep_ao.glsl"

  // Per block of VX_BLOCK^2 columns, for the march: the nearest entry and farthest exit, and
  // the largest entry and smallest exit of the columns' first spans.
  void gather_block_bounds() {
    blocks_x_ = (u_image.x + VX_BLOCK - 1) / VX_BLOCK;
    const int blocks_y = (u_image.y + VX_BLOCK - 1) / VX_BLOCK;
    const std::size_t blocks = std::size_t(blocks_x_) * std::size_t(blocks_y);
    block_bounds_.assign(blocks, vec2(3.0e38f, -3.0e38f));
    block_inside_.assign(blocks, vec2(-3.0e38f, 3.0e38f));
    for (int y = 0; y < u_image.y; ++y)
      for (int x = 0; x < u_image.x; ++x) {
        const std::size_t k =
            std::size_t(x / VX_BLOCK) + std::size_t(y / VX_BLOCK) * std::size_t(blocks_x_);
        const uint n = sd_count(ivec2(x, y));
        if (u_use_backdrop != 0 && sd_backdrop(ivec2(x, y)).w < 3.0e38f)
          block_bounds_[k] = vec2(min(block_bounds_[k].x, sd_backdrop(ivec2(x, y)).w), 3.0e38f);
        vec2& inside = block_inside_[k];
        if (n == 0) {
          inside.x = 3.0e38f;  // a column without fluid: the ray cannot stay inside
          continue;
        }
        const vec2 first = sd_depths(sd_offset(ivec2(x, y)));
        inside = vec2(max(inside.x, first.x), min(inside.y, first.y));
        vec2& b = block_bounds_[k];
        b.x = min(b.x, first.x);
        b.y = max(b.y, sd_depths(sd_offset(ivec2(x, y)) + n - 1).y);
      }
  }

  void swap_buffers(HostBuffers& b) {
    links_.swap(b.links);
    normals_.swap(b.normals);
    ao_.swap(b.ao);
    depths_.swap(b.depths);
    block_bounds_.swap(b.block_bounds);
    ends_.swap(b.ends);
    block_inside_.swap(b.block_inside);
  }

  // f(p, span index) for every span, rows in parallel.
  template <class F> void each_span(F&& f) {
    each_pixel([&](ivec2 p) {
      for (uint k = 0; k < sd_count(p); ++k) f(p, sd_offset(p) + k);
    });
  }
  template <class F> std::vector<uvec2> per_span(F&& f) {
    std::vector<uvec2> out;
    fill_per_span(out, f);
    return out;
  }
  // out[s] = f(p, s) for every span s (of pixel p), `out` resized.
  template <class T, class F> void fill_per_span(std::vector<T>& out, F&& f) {
    out.resize(spans_.spans.size());
    each_span([&](ivec2 p, uint s) { out[s] = f(p, s); });
  }

  // The normals pass (render/gl/passes/normals.h) into normals_: the Sobel normals of every span,
  // then, where folds are on, the crests' from their neighbours in place, as its two dispatches do.
  void build_normals() {
    fill_per_span(normals_, [&](ivec2 p, uint s) { return span_normal_words(p, s); });
    if (!(u_fold_step > 0.0f)) return;
    each_span([&](ivec2 p, uint s) {
      const SurfacePoint entry = surface_point(p, s, 0u);
      const SurfacePoint exit = surface_point(p, s, 1u);
      if (on_crest(entry)) normals_[s].x = crest_normal_word(entry);
      if (on_crest(exit)) normals_[s].y = crest_normal_word(exit);
    });
  }

  template <class F> void each_pixel(F&& f) {
    tbb::parallel_for(tbb::blocked_range<int>(0, u_image.y),
                      [&](const tbb::blocked_range<int>& rows) {
                        for (int y = rows.begin(); y != rows.end(); ++y)
                          for (int x = 0; x < u_image.x; ++x) f(ivec2(x, y));
                      });
  }

  // Every pixel's colour in `mode` into `image` (the span image's size). Refraction runs the
  // GPU's dispatches one after the other (at most `dispatches`, each `budget` column events),
  // then, as its resolve dispatch, adds what each ray sees where it ended (end_light reads the
  // neighbouring pixels' ends). Returns the rays still marching after the
  // dispatches, sent to the environment.
  std::int64_t shade(ShadeMode mode, int dispatches, int budget, FloatImage& image) {
    if (mode != ShadeMode::refractive) {
      each_pixel([&](ivec2 p) {
        const vec3 c = mode == ShadeMode::opaque ? shade_opaque(p) : shade_translucent(p);
        image.set(p.x, p.y, vec4(c, 1.0f));
      });
      return 0;
    }
    const std::size_t pixels = std::size_t(u_image.x) * std::size_t(u_image.y);
    ends_.resize(pixels);
    std::atomic<std::int64_t> unfinished{0};
    each_pixel([&](ivec2 p) {
      RayState s = ray_start(p);
      for (int d = 0; d < dispatches && s.marching; ++d) s = march(s, budget);
      if (s.marching) {
        ++unfinished;
        s = ray_leave(s);
      }
      image.set(p.x, p.y, vec4(s.color, 1.0f));
      ends_[pixel_index(p)] = {ray_end(s), s.throughput, s.anchor, s.bounces <= u_bounces};
    });
    each_pixel([&](ivec2 p) {
      const RayEnd& e = ends_[pixel_index(p)];
      const vec3 light = e.throughput * end_light(p, e.end, e.anchor, e.bent);
      image.set(p.x, p.y, image.at(p.x, p.y) + vec4(light, 0.0f));
    });
    return unfinished.load();
  }

 private:
  const PixelSpans& record(ivec2 p) const { return spans_.pixels[pixel_index(p)]; }
  const SpanImage& spans_;
  const std::vector<vec3>* background_ = nullptr;  // use_background's, or none
  const std::vector<vec4>* backdrop_ = nullptr;    // use_backdrop's, or none
  std::vector<vec2> block_bounds_, block_inside_;
  int blocks_x_ = 1;
};

static_assert(VX_BACKDROP_LEVELS == kBackdropLevels, "render/backdrop.h and column_march.glsl");

}  // namespace voxspan::model
