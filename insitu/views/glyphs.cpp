#include "insitu/views/glyphs.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <limits>

#include "insitu/views/view_attributes.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// What one pass over the particles adds up (threads join theirs).
struct Tally {
  GlyphCounts counts;
  ValueSpan values;  // the selected particles'

  void join(const Tally& o) {
    counts += o.counts;
    values.add(o.values);
  }
  // parallel_reduce's join.
  static Tally joined(Tally a, const Tally& b) {
    a.join(b);
    return a;
  }
};

// The attributes a selection names, found once per step.
struct Sources {
  const AttributeView* color = nullptr;
  const AttributeView* cull = nullptr;
};

Sources sources(const ParticleView& particles, const GlyphSelection& s) {
  if (!(s.radius > 0) || !std::isfinite(s.radius))
    throw make_error("particles: the glyph radius must be positive; got ", s.radius);
  if (particles.owned_count() > std::size_t(std::numeric_limits<std::uint32_t>::max()))
    throw make_error("particles: more than 2^32 - 1 owned particles on one rank");
  Sources src;
  if (!s.color_by.empty()) src.color = &require_attribute(particles, s.color_by, s.color_by_key);
  const std::string_view cull = s.cull_by.empty() ? s.color_by : s.cull_by;
  if (s.cull_range) {
    if (cull.empty()) throw make_error("particles: cull_range needs cull_by or color_by");
    src.cull =
        &require_attribute(particles, cull, s.cull_by.empty() ? s.color_by_key : s.cull_by_key);
  }
  return src;
}

// The cell holding p, or -1 outside the grid (or without one).
std::int64_t cell_of(const CellStatesView& cells, const std::array<double, 3>& p) {
  if (cells.empty()) return -1;
  std::int64_t index = 0, scale = 1;
  for (int a = 0; a < 3; ++a) {
    const double f =
        std::floor((p[std::size_t(a)] - cells.origin[std::size_t(a)]) / cells.cell_size);
    if (!(f >= 0 && f < cells.dims[std::size_t(a)])) return -1;
    index += std::int64_t(f) * scale;
    scale *= cells.dims[std::size_t(a)];
  }
  return index;
}

std::uint8_t state_at(const CellStatesView& cells, std::int64_t cell) {
  return cell < 0 ? cell::kPartial : cells.states[std::size_t(cell)];
}

// The pixels whose centres a view-space box [lo, hi] (in front of the eye) can cover, clamped
// to the image, with one pixel of margin against rounding: x0 > x1 when none.
struct PixelRect {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

PixelRect rect_of(const ViewFrame& f, double sx_min, double sx_max, double sy_min, double sy_max) {
  const auto clamp_int = [](double v, int hi) { return int(std::clamp(v, -1.0, double(hi))); };
  PixelRect r;
  r.x0 = std::max(0, clamp_int(std::ceil(f.pixel_x(sx_min)) - 1, f.width));
  r.x1 = std::min(f.width - 1, clamp_int(std::floor(f.pixel_x(sx_max)) + 1, f.width));
  r.y0 = std::max(0, clamp_int(std::ceil(f.pixel_y(sy_max)) - 1, f.height));
  r.y1 = std::min(f.height - 1, clamp_int(std::floor(f.pixel_y(sy_min)) + 1, f.height));
  return r;
}

// The pixels a view-space sphere can cover: its bounding box's projection (the box is in front
// of the eye), or the whole image when the sphere reaches the eye's plane.
PixelRect sphere_rect(const ViewFrame& f, glm::dvec3 c, double r) {
  if (!(c.z - r > 1e-12 * r)) return {0, f.width - 1, 0, f.height - 1};
  const double zn = c.z - r, zf = c.z + r;
  const double sx[4] = {(c.x - r) / zn, (c.x - r) / zf, (c.x + r) / zn, (c.x + r) / zf};
  const double sy[4] = {(c.y - r) / zn, (c.y - r) / zf, (c.y + r) / zn, (c.y + r) / zf};
  return rect_of(f, *std::min_element(sx, sx + 4), *std::max_element(sx, sx + 4),
                 *std::min_element(sy, sy + 4), *std::max_element(sy, sy + 4));
}

void keep_nearest(std::uint64_t& slot, std::uint64_t key) {
  std::atomic_ref<std::uint64_t> a(slot);
  std::uint64_t current = a.load(std::memory_order_relaxed);
  while (key < current && !a.compare_exchange_weak(current, key, std::memory_order_relaxed)) {}
}

float key_depth(std::uint64_t key) { return std::bit_cast<float>(std::uint32_t(key >> 32)); }

// The steps every pass over the particles shares: the filters, then what the pass does with a
// selected particle (`visit(i, state, cell, tally)`).
class Passes {
 public:
  Passes(const ParticleView& p, const CellStatesView& cells, const GlyphSelection& s,
         const Sources& src)
      : particles_(p), cells_(cells), selection_(s), src_(src) {}

  template <class Visit> Tally each_selected(Visit visit) const {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, particles_.owned_count(), 4096), Tally{},
        [&](const tbb::blocked_range<std::size_t>& range, Tally t) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            if (!particles_.position_finite(i)) continue;
            ++t.counts.owned;
            if (src_.cull != nullptr) {
              const double v = src_.cull->magnitude(i);
              if (!(v >= (*selection_.cull_range)[0] && v <= (*selection_.cull_range)[1])) {
                ++t.counts.range_culled;
                continue;
              }
            }
            if (selection_.cut) {
              const std::array<double, 3> p = particles_.position(i);
              if (glm::dot(selection_.cut->normal, glm::dvec3(p[0], p[1], p[2])) >
                  selection_.cut->offset) {
                ++t.counts.cut;
                continue;
              }
            }
            const std::int64_t cell = cell_of(cells_, particles_.position(i));
            const std::uint8_t state = state_at(cells_, cell);
            if (selection_.boundary_only && cell::is_inner(state)) {
              ++t.counts.inner_skipped;
              continue;
            }
            visit(i, state, cell, t);
          }
          return t;
        },
        Tally::joined);
  }

  const ParticleView& particles() const { return particles_; }
  const Sources& sources() const { return src_; }

 private:
  const ParticleView& particles_;
  const CellStatesView& cells_;
  const GlyphSelection& selection_;
  const Sources& src_;
};

void add_value(const Sources& src, std::size_t i, Tally& t) {
  if (src.color == nullptr) return;
  t.values.add(src.color->magnitude(i));
}

glm::dvec3 view_centre(const ViewFrame& f, const ParticleView& p, std::size_t i) {
  const std::array<double, 3> x = p.position(i);
  return f.to_view({x[0], x[1], x[2]});
}

// Projects one particle and tests its pixels; counts what became of it.
void draw(const ViewFrame& f, const GlyphSelection& s, glm::dvec3 c, std::size_t i,
          std::vector<std::uint64_t>& nearest, Tally& t) {
  const double r2 = s.radius * s.radius;
  if (glm::dot(c, c) <= r2) {
    ++t.counts.holding_eye;
    return;
  }
  if (s.culling != GlyphCulling::none && !f.meets_pyramid(c, s.radius)) {
    ++t.counts.frustum_culled;
    return;
  }
  ++t.counts.drawn;
  const PixelRect r = sphere_rect(f, c, s.radius);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      float z = 0;
      if (glyph_hit(f, x, y, c, r2, z))
        keep_nearest(nearest[std::size_t(x) + std::size_t(f.width) * std::size_t(y)],
                     glyph_key(z, i));
    }
}

enum CellVerdict : std::uint8_t { kDraw = 0, kHidden = 1, kOutside = 2 };

// An inner-full cell's box grown by the radius, in view space: its nearest depth and the pixels
// it can cover (none when it is outside the view; the whole image when it reaches the eye's
// plane, with depth 0 so that it is drawn first and never hidden).
struct CellFootprint {
  double z_min = 0;
  PixelRect pixels;
};

CellFootprint footprint(const ViewFrame& f, const CellStatesView& cells, std::size_t cell,
                        double radius) {
  const std::size_t nx = std::size_t(cells.dims[0]), ny = std::size_t(cells.dims[1]);
  const glm::dvec3 index(double(cell % nx), double((cell / nx) % ny), double(cell / (nx * ny)));
  const glm::dvec3 origin(cells.origin[0], cells.origin[1], cells.origin[2]);
  const glm::dvec3 lo = origin + index * cells.cell_size - radius;
  const glm::dvec3 hi = lo + cells.cell_size + 2 * radius;
  double z_min = kInf, sx0 = kInf, sx1 = -kInf, sy0 = kInf, sy1 = -kInf;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 v =
        f.to_view({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    if (!(v.z > 0)) return {0, {0, f.width - 1, 0, f.height - 1}};
    z_min = std::min(z_min, v.z);
    sx0 = std::min(sx0, v.x / v.z), sx1 = std::max(sx1, v.x / v.z);
    sy0 = std::min(sy0, v.y / v.z), sy1 = std::max(sy1, v.y / v.z);
  }
  return {z_min, rect_of(f, sx0, sx1, sy0, sy1)};
}

// Hidden when every pixel the footprint covers already shows a glyph nearer than its nearest
// point: then none of its particles can be the nearest anywhere.
CellVerdict verdict(const CellFootprint& c, const GlyphImage& img) {
  if (c.pixels.empty()) return kOutside;
  if (!(c.z_min > 0)) return kDraw;
  for (int y = c.pixels.y0; y <= c.pixels.y1; ++y)
    for (int x = c.pixels.x0; x <= c.pixels.x1; ++x) {
      const std::uint64_t k = img.nearest[std::size_t(x) + std::size_t(img.width) * std::size_t(y)];
      if (k == kNoGlyph || !(double(key_depth(k)) < c.z_min)) return kDraw;
    }
  return kHidden;
}

void start(const Camera& camera, GlyphImage& out) {
  out.width = camera.width;
  out.height = camera.height;
  out.nearest.assign(std::size_t(camera.width) * std::size_t(camera.height), kNoGlyph);
}

// Depth, normal and value of each pixel's nearest glyph.
void resolve(const ViewFrame& f, const Passes& passes, const Tally& t, GlyphImage& out) {
  const std::size_t n = out.nearest.size();
  out.depth.assign(n, 0.0f);
  out.normal.assign(n, glm::vec3(0));
  out.value.assign(n, 0.0f);
  const AttributeView* color = passes.sources().color;
  tbb::parallel_for(0, out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const std::size_t k = std::size_t(x) + std::size_t(out.width) * std::size_t(y);
      if (out.nearest[k] == kNoGlyph) continue;
      const std::size_t i = std::size_t(out.nearest[k] & 0xffffffffu);
      const float z = key_depth(out.nearest[k]);
      const glm::dvec3 c = view_centre(f, passes.particles(), i);
      out.depth[k] = z;
      out.normal[k] = glm::vec3(glm::normalize(double(z) * f.view_ray(x, y) - c));
      out.value[k] = color != nullptr ? float(color->magnitude(i)) : 0.0f;
    }
  });
  out.counts = t.counts;
  out.values = t.values;
}

// The selected particles of the inner-full cells, sorted by cell (a counting sort), then the cells
// front to back in kBatches batches: each batch's cells are tested against the picture the
// shell and the batches before it made (the test of one batch runs before any of it is drawn,
// so that the result does not depend on the threads), and only those that can show are drawn.
constexpr int kBatches = 4;

Tally draw_inner_cells(const ViewFrame& f, const CellStatesView& cells, const GlyphSelection& s,
                       const Passes& passes, GlyphImage& out) {
  GlyphImage::CellScratch& w = out.scratch;
  w.start.assign(cells.cell_count() + 1, 0);
  passes.each_selected([&](std::size_t, std::uint8_t state, std::int64_t cell, Tally&) {
    if (state == cell::kInnerFull)
      std::atomic_ref<std::uint32_t>(w.start[std::size_t(cell) + 1])
          .fetch_add(1, std::memory_order_relaxed);
  });
  w.cells.clear();
  for (std::size_t c = 0; c < cells.cell_count(); ++c) {
    if (w.start[c + 1] > 0) w.cells.push_back({0, std::uint32_t(c), kDraw});
    w.start[c + 1] += w.start[c];
  }
  w.fill.assign(w.start.begin(), w.start.end() - 1);
  w.sorted.resize(w.start.back());
  passes.each_selected([&](std::size_t i, std::uint8_t state, std::int64_t cell, Tally&) {
    if (state != cell::kInnerFull) return;
    const std::uint32_t slot = std::atomic_ref<std::uint32_t>(w.fill[std::size_t(cell)])
                                   .fetch_add(1, std::memory_order_relaxed);
    w.sorted[slot] = std::uint32_t(i);
  });
  tbb::parallel_for(std::size_t(0), w.cells.size(), [&](std::size_t k) {
    w.cells[k].z_min = footprint(f, cells, w.cells[k].cell, s.radius).z_min;
  });
  // Front to back; equal depths in cell order (a total order: the batches do not depend on
  // the sort's threads).
  tbb::parallel_sort(w.cells.begin(), w.cells.end(), [](const auto& a, const auto& b) {
    return a.z_min < b.z_min || (a.z_min == b.z_min && a.cell < b.cell);
  });
  Tally total;
  const std::size_t n = w.cells.size();
  for (int batch = 0; batch < kBatches; ++batch) {
    const std::size_t b0 = n * std::size_t(batch) / kBatches,
                      b1 = n * std::size_t(batch + 1) / kBatches;
    tbb::parallel_for(b0, b1, [&](std::size_t k) {
      w.cells[k].verdict = verdict(footprint(f, cells, w.cells[k].cell, s.radius), out);
    });
    total.join(tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(b0, b1, 16), Tally{},
        [&](const tbb::blocked_range<std::size_t>& range, Tally t) {
          for (std::size_t k = range.begin(); k != range.end(); ++k) {
            const auto& c = w.cells[k];
            const std::uint32_t first = w.start[c.cell], last = w.start[c.cell + 1];
            if (c.verdict == kHidden) {
              t.counts.occlusion_culled += last - first;
              ++t.counts.cells_hidden;
            } else if (c.verdict == kOutside) {
              t.counts.frustum_culled += last - first;
            } else {
              for (std::uint32_t p = first; p < last; ++p)
                draw(f, s, view_centre(f, passes.particles(), w.sorted[p]), w.sorted[p],
                     out.nearest, t);
            }
          }
          return t;
        },
        Tally::joined));
  }
  return total;
}

}  // namespace

void rasterize_glyphs(const ParticleView& particles, const CellStatesView& cells,
                      const Camera& camera, const GlyphSelection& selection, GlyphImage& out) {
  const Sources src = sources(particles, selection);
  const ViewFrame f(camera);
  start(camera, out);
  const Passes passes(particles, cells, selection, src);
  const bool occlusion = selection.culling == GlyphCulling::occlusion && !cells.empty();
  // The shell first (with occlusion culling; otherwise every particle).
  Tally t =
      passes.each_selected([&](std::size_t i, std::uint8_t state, std::int64_t, Tally& tally) {
        add_value(src, i, tally);
        if (occlusion && state == cell::kInnerFull) return;  // drawn by draw_inner_cells
        draw(f, selection, view_centre(f, particles, i), i, out.nearest, tally);
      });
  if (occlusion) t.join(draw_inner_cells(f, cells, selection, passes, out));
  resolve(f, passes, t, out);
}

void reference_glyphs(const ParticleView& particles, const CellStatesView& cells,
                      const Camera& camera, const GlyphSelection& selection, GlyphImage& out) {
  const Sources src = sources(particles, selection);
  const ViewFrame f(camera);
  start(camera, out);
  const Passes passes(particles, cells, selection, src);
  const double r2 = selection.radius * selection.radius;
  std::vector<std::uint8_t> chosen(particles.owned_count(), 0);  // each thread its own indices
  const Tally t =
      passes.each_selected([&](std::size_t i, std::uint8_t, std::int64_t, Tally& tally) {
        add_value(src, i, tally);
        const glm::dvec3 c = view_centre(f, particles, i);
        if (glm::dot(c, c) <= r2) {
          ++tally.counts.holding_eye;
          return;
        }
        ++tally.counts.drawn;
        chosen[i] = 1;
      });
  std::vector<std::pair<std::size_t, glm::dvec3>> drawn;  // index, view-space centre
  for (std::size_t i = 0; i < chosen.size(); ++i)
    if (chosen[i] != 0) drawn.emplace_back(i, view_centre(f, particles, i));
  tbb::parallel_for(0, out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      std::uint64_t& slot = out.nearest[std::size_t(x) + std::size_t(out.width) * std::size_t(y)];
      for (const auto& [i, c] : drawn) {
        float z = 0;
        if (glyph_hit(f, x, y, c, r2, z)) slot = std::min(slot, glyph_key(z, i));
      }
    }
  });
  resolve(f, passes, t, out);
}

namespace {

// [ZD15]'s point occlusion (render/model/deep_ao.glsl): the elevation of the occluder above the
// receiver's tangent plane, less a bias, fading out to the radius.
double point_occlusion(glm::dvec3 receiver, glm::dvec3 normal, glm::dvec3 occluder, double radius) {
  const glm::dvec3 v = occluder - receiver;
  const double dist = glm::length(v);
  if (!(dist > 1e-6 * receiver.z) || dist > radius) return 0;
  const double r = dist / radius;
  return std::max(glm::dot(normal, v) / dist - 0.1, 0.0) * (1 - r * r);
}

double glyph_ao(const GlyphImage& g, const ViewFrame& f, const GlyphShading& s, int x, int y,
                glm::dvec3 receiver, glm::dvec3 normal) {
  const double pixel_size = 2 * f.tan_half_y / f.height * receiver.z;
  const double radius_px = s.ao_radius / pixel_size;
  const double turn = 6.2831853 * std::fmod(0.7548777 * x + 0.5698403 * y, 1.0);
  double occlusion = 0;
  for (int i = 0; i < s.ao_samples; ++i) {
    const double r = std::sqrt((i + 0.5) / s.ao_samples) * radius_px;
    const double a = turn + 2.3999632 * i;  // the golden angle
    const int qx = x + int(std::lround(r * std::cos(a))),
              qy = y + int(std::lround(r * std::sin(a)));
    if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
    const std::size_t q = std::size_t(qx) + std::size_t(g.width) * std::size_t(qy);
    if (g.nearest[q] == kNoGlyph) continue;
    occlusion +=
        point_occlusion(receiver, normal, double(g.depth[q]) * f.view_ray(qx, qy), s.ao_radius);
  }
  return 1 - s.ao_strength * occlusion / std::max(1, s.ao_samples);
}

}  // namespace

void shade_glyphs(const GlyphImage& g, const Camera& camera, const GlyphShading& s,
                  FloatImage& picture) {
  if (picture.width != g.width || picture.height != g.height)
    picture = FloatImage(g.width, g.height);
  const ViewFrame f(camera);
  const glm::dvec3 light = glm::normalize(glm::dvec3(-0.35, 0.6, -0.7));  // view space
  tbb::parallel_for(0, g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t k = std::size_t(x) + std::size_t(g.width) * std::size_t(y);
      if (g.nearest[k] == kNoGlyph) {
        picture.set(x, y, glm::vec4(s.background, 1.0f));
        continue;
      }
      const glm::dvec3 receiver = double(g.depth[k]) * f.view_ray(x, y);
      const glm::dvec3 n = glm::dvec3(g.normal[k]);
      const double ao = s.ao_radius > 0 ? glyph_ao(g, f, s, x, y, receiver, n) : 1.0;
      const glm::dvec3 base =
          s.by_value ? glm::dvec3(map_color(s.map, s.axis.t(g.value[k]))) : glm::dvec3(s.colour);
      const double diffuse = std::max(glm::dot(n, light), 0.0);
      const glm::dvec3 half = glm::normalize(light - glm::normalize(receiver));
      const double highlight = 0.25 * std::pow(std::max(glm::dot(n, half), 0.0), 48.0);
      const glm::dvec3 c = base * (0.3 * ao + 0.7 * diffuse * (0.5 + 0.5 * ao)) + highlight * ao;
      picture.set(x, y, glm::vec4(glm::vec3(c), 1.0f));
    }
  });
}

}  // namespace voxspan
