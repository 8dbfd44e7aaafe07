#include "insitu/views/sph_slice.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "insitu/views/view_attributes.h"
#include "voxspan/error.h"

namespace voxspan {

SlicePlane SlicePlane::make(glm::dvec3 origin, glm::dvec3 normal, double width, double height,
                            glm::dvec3 up) {
  SlicePlane p;
  p.origin = origin;
  p.normal = glm::normalize(normal);
  glm::dvec3 v = up - glm::dot(up, p.normal) * p.normal;
  if (glm::length(v) < 1e-9 * glm::length(up)) {
    // `up` along the normal: +y, or +x for a normal along y (a 2D run's plane z = 0 then reads
    // as its map: x right, y up).
    const glm::dvec3 axis = std::abs(p.normal.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    v = axis - glm::dot(axis, p.normal) * p.normal;
  }
  p.v = glm::normalize(v);
  p.u = glm::cross(p.v, p.normal);
  p.width = width;
  p.height = height;
  return p;
}

glm::dvec3 SlicePlane::pixel_centre(int i, int j, int image_width, int image_height) const {
  const double s = ((i + 0.5) / image_width - 0.5) * width;
  const double t = (0.5 - (j + 0.5) / image_height) * height;
  return origin + s * u + t * v;
}

std::size_t sph_terms(const ParticleView& particles, const SliceQuantity& q,
                      const std::function<bool(const glm::dvec3&, double)>& near,
                      std::vector<SphTerm>& out) {
  if (!(q.smoothing_length > 0))
    throw make_error("slice: the smoothing length must be positive; got ", q.smoothing_length);
  const AttributeView* quantity = &require_attribute(particles, q.name, q.key);
  const AttributeView* h_of =
      q.smoothing.empty() ? nullptr
                          : &require_attribute(particles, q.smoothing, "smoothing_attribute");
  const AttributeView* mass = particles.find_attribute(q.mass);
  const AttributeView* density = particles.find_attribute(q.density);
  const bool per_particle_volume = mass != nullptr && density != nullptr;
  if (!per_particle_volume && !(q.rest_volume > 0))
    throw make_error("slice: no \"", q.mass, "\" and \"", q.density,
                     "\" attributes and no rest volume (particle spacing)");
  // Particle i's term: kept, or left out (for its value: counted).
  enum Term { kept, left_out, not_finite };
  const auto term = [&](std::size_t i, SphTerm& t) {
    if (!particles.position_finite(i)) return left_out;
    const auto a = particles.position(i);
    const glm::dvec3 p(a[0], a[1], a[2]);
    const double h = h_of != nullptr ? h_of->magnitude(i) : q.smoothing_length;
    if (!(h > 0) || !std::isfinite(h) || !near(p, h)) return left_out;
    const double volume =
        per_particle_volume ? mass->magnitude(i) / density->magnitude(i) : q.rest_volume;
    const double value = quantity->magnitude(i);
    if (!std::isfinite(value)) return not_finite;
    if (!(volume > 0) || !std::isfinite(volume)) return left_out;
    t = {p, volume * value, volume, h};
    return kept;
  };
  // In parallel and in the particles' order (the sums do not depend on the thread count):
  // chunks count their terms, then write them from their offsets.
  constexpr std::size_t kChunks = 256;
  const std::size_t n = particles.owned_count();
  const std::size_t chunk = std::max<std::size_t>(4096, (n + kChunks - 1) / kChunks);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::array<std::size_t, kChunks + 1> offset{};
  std::array<std::size_t, kChunks> for_value{};
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    SphTerm t;
    std::size_t kept_here = 0;
    for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
      const Term r = term(i, t);
      kept_here += r == kept;
      for_value[c] += r == not_finite;
    }
    offset[c + 1] = kept_here;
  });
  for (std::size_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];
  out.resize(offset[chunks]);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    std::size_t k = offset[c];
    SphTerm t;
    for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
      if (term(i, t) == kept) out[k++] = t;
  });
  std::size_t left_for_value = 0;
  for (std::size_t c = 0; c < chunks; ++c) left_for_value += for_value[c];
  return left_for_value;
}

namespace {

// Each term adds itself to the pixels whose centres its support reaches (per-particle h): the
// rows in bands, in parallel, each band's pixels getting the terms in their order.
void scatter_slice(const std::vector<SphTerm>& near, const SliceQuantity& q,
                   const SlicePlane& plane, SliceImage& out) {
  const int width = out.width, height = out.height;
  const double px = plane.width / width, py = plane.height / height;
  constexpr int kBand = 8;
  // An index clamped in double first: a particle near the plane far outside the picture gives
  // indices no int holds.
  const auto index = [](double x, int lo, int hi) {
    return int(std::clamp(x, double(lo) - 1, double(hi) + 1));
  };
  tbb::parallel_for(0, (height + kBand - 1) / kBand, [&](int band) {
    const int j0 = band * kBand, j1 = std::min(height, j0 + kBand) - 1;
    for (const SphTerm& t : near) {
      const glm::dvec3 d = t.p - plane.origin;
      const double off = glm::dot(d, plane.normal), support = kernel_support(q.kernel) * t.h;
      const double reach = std::sqrt(std::max(0.0, support * support - off * off));
      // Pixel centres at s = ((i + 0.5) / W - 0.5) width, t = (0.5 - (j + 0.5) / H) height.
      const double s = glm::dot(d, plane.u), v = glm::dot(d, plane.v);
      const int i_lo =
          std::max(0, index(std::ceil((s - reach + 0.5 * plane.width) / px - 0.5), 0, width));
      const int i_hi = std::min(
          width - 1, index(std::floor((s + reach + 0.5 * plane.width) / px - 0.5), 0, width));
      const int jt_lo =
          std::max(j0, index(std::ceil((0.5 * plane.height - v - reach) / py - 0.5), j0, j1));
      const int jt_hi =
          std::min(j1, index(std::floor((0.5 * plane.height - v + reach) / py - 0.5), j0, j1));
      for (int j = jt_lo; j <= jt_hi; ++j)
        for (int i = i_lo; i <= i_hi; ++i) {
          const std::size_t pixel = std::size_t(i) + std::size_t(width) * std::size_t(j);
          SphSum sum{out.sum[pixel], out.weight[pixel]};
          sum.add(t, plane.pixel_centre(i, j, width, height), q, t.h);
          out.sum[pixel] = sum.sum;
          out.weight[pixel] = sum.weight;
        }
    }
  });
}

}  // namespace

void interpolate_slice(const ParticleView& particles, const SliceQuantity& q,
                       const SlicePlane& plane, int width, int height, SliceImage& out) {
  const double h = q.smoothing_length;
  const double support = kernel_support(q.kernel) * h;
  std::vector<SphTerm>& near = out.near;
  out.values_not_finite = sph_terms(
      particles, q,
      [&](const glm::dvec3& p, double hp) {
        return std::abs(glm::dot(p - plane.origin, plane.normal)) < kernel_support(q.kernel) * hp;
      },
      near);
  out.width = width;
  out.height = height;
  out.values.assign(std::size_t(width) * std::size_t(height), 0.0f);
  out.sum.assign(out.values.size(), 0.0);
  out.weight.assign(out.values.size(), 0.0);
  out.particles_near = near.size();
  if (!q.smoothing.empty()) {
    scatter_slice(near, q, plane, out);
    finish_slice(out, q.shepard);
    return;
  }

  // Bins of the support's size on the plane: a pixel's particles are in the 3x3 around it.
  const int bx = std::max(1, int(std::ceil(plane.width / support)));
  const int by = std::max(1, int(std::ceil(plane.height / support)));
  auto bin_of = [&](glm::dvec3 p, int& x, int& y) {
    const glm::dvec3 d = p - plane.origin;
    x = int(std::floor((glm::dot(d, plane.u) + 0.5 * plane.width) / support));
    y = int(std::floor((glm::dot(d, plane.v) + 0.5 * plane.height) / support));
    return x >= -1 && x <= bx && y >= -1 && y <= by;
  };
  // Counting sort of the near particles into (bx + 2) x (by + 2) bins (one ring outside).
  const auto bins = std::size_t(bx + 2) * std::size_t(by + 2);
  std::vector<std::uint32_t>& start = out.bin_start;
  std::vector<std::uint32_t>& bin = out.bin_of;
  start.assign(bins + 1, 0);
  bin.assign(near.size(), std::uint32_t(bins));
  for (std::size_t k = 0; k < near.size(); ++k) {
    int x, y;
    if (!bin_of(near[k].p, x, y)) continue;
    bin[k] = std::uint32_t(std::size_t(x + 1) + std::size_t(bx + 2) * std::size_t(y + 1));
    ++start[bin[k] + 1];
  }
  for (std::size_t b = 0; b < bins; ++b) start[b + 1] += start[b];
  // The terms themselves in bin order: a pixel reads each row of its bins as one run.
  std::vector<std::uint32_t>& fill = out.bin_fill;
  std::vector<SphTerm>& sorted = out.sorted;
  fill.assign(start.begin(), start.end() - 1);
  sorted.resize(start[bins]);
  for (std::size_t k = 0; k < near.size(); ++k)
    if (bin[k] < bins) sorted[fill[bin[k]]++] = near[k];

  tbb::parallel_for(0, height, [&](int j) {
    for (int i = 0; i < width; ++i) {
      const glm::dvec3 x = plane.pixel_centre(i, j, width, height);
      int cx, cy;
      bin_of(x, cx, cy);
      SphSum sum;
      const int x0 = std::max(cx - 1, -1), x1 = std::min(cx + 1, bx);
      for (int y = std::max(cy - 1, -1); y <= std::min(cy + 1, by) && x0 <= x1; ++y) {
        const std::size_t row = std::size_t(bx + 2) * std::size_t(y + 1);
        for (std::uint32_t s = start[row + std::size_t(x0 + 1)];
             s < start[row + std::size_t(x1 + 2)]; ++s)
          sum.add(sorted[s], x, q, h);
      }
      const std::size_t pixel = std::size_t(i) + std::size_t(width) * std::size_t(j);
      out.sum[pixel] = sum.sum;
      out.weight[pixel] = sum.weight;
    }
  });
  finish_slice(out, q.shepard);
}

void finish_slice(SliceImage& image, bool shepard) {
  image.pixels_reached = 0;
  for (std::size_t k = 0; k < image.values.size(); ++k) {
    const SphSum sum{image.sum[k], image.weight[k]};
    image.values[k] = float(sum.value(shepard));
    image.pixels_reached += sum.weight > 0 ? 1 : 0;
  }
}

}  // namespace voxspan
