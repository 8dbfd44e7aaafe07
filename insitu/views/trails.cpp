#include "insitu/views/trails.h"

#include <algorithm>
#include <cmath>

#include "insitu/views/view_attributes.h"
#include "voxspan/error.h"

namespace voxspan {

void collect_trail_points(const ParticleView& particles, const TrailChoice& choice,
                          std::vector<TrailPoint>& out) {
  out.clear();
  if (!choice.any()) return;
  const AttributeView* id = &require_attribute(particles, choice.id, choice.key);
  for (std::size_t i = 0; i < particles.owned_count(); ++i) {
    const double v = id->magnitude(i);
    if (!std::isfinite(v) || !particles.position_finite(i)) continue;
    const auto n = std::int64_t(std::llround(v));
    const bool chosen = (choice.every > 0 && n % choice.every == 0) ||
                        std::binary_search(choice.ids.begin(), choice.ids.end(), n);
    if (!chosen) continue;
    const std::array<double, 3> p = particles.position(i);
    out.push_back({v, p[0], p[1], p[2]});
  }
}

void Trails::add_step(std::span<const TrailPoint> points) {
  ++step_;
  for (const TrailPoint& p : points) {
    Trail& t = trails_[std::llround(p.id)];
    if (t.points.size() == std::size_t(length_)) t.points.erase(t.points.begin());
    t.points.push_back({p.x, p.y, p.z});
    t.last_step = step_;
  }
  std::erase_if(trails_, [&](const auto& kv) { return step_ - kv.second.last_step >= length_; });
}

namespace {

// A segment in view space, clipped to depth >= near, drawn one sample per pixel step with the
// depth interpolated in 1/z (perspective-correct) and tested against the picture's.
void draw_segment(const ViewFrame& f, glm::dvec3 a, glm::dvec3 b, float alpha_a, float alpha_b,
                  std::span<const float> depth, glm::vec3 colour, FloatImage& picture) {
  const double near = 1e-6 * std::max(std::abs(a.z), std::abs(b.z));
  if (a.z < near && b.z < near) return;
  if (a.z < near) a += (b - a) * ((near - a.z) / (b.z - a.z));
  if (b.z < near) b += (a - b) * ((near - b.z) / (a.z - b.z));
  const auto screen = [&](glm::dvec3 p) {
    return glm::dvec2(f.pixel_x(p.x / p.z), f.pixel_y(p.y / p.z));
  };
  const glm::dvec2 sa = screen(a), sb = screen(b);
  const double length = std::max(std::abs(sb.x - sa.x), std::abs(sb.y - sa.y));
  if (!(length < 4.0 * (f.width + f.height))) return;  // far outside: not worth walking
  const int steps = int(std::ceil(length)) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = double(s) / steps;
    const glm::dvec2 q = sa + t * (sb - sa);
    const int x = int(std::lround(q.x)), y = int(std::lround(q.y));
    if (x < 0 || y < 0 || x >= f.width || y >= f.height) continue;
    const double z = 1 / ((1 - t) / a.z + t / b.z);
    const float d = depth[std::size_t(x) + std::size_t(f.width) * std::size_t(y)];
    if (d > 0 && !(z < d)) continue;
    const float alpha = alpha_a + float(t) * (alpha_b - alpha_a);
    const glm::vec4 under = picture.at(x, y);
    picture.set(x, y, glm::vec4(glm::mix(glm::vec3(under), colour, alpha), under.a));
  }
}

}  // namespace

void Trails::draw(const Camera& camera, std::span<const float> depth, glm::vec3 colour,
                  FloatImage& picture) const {
  const ViewFrame f(camera);
  for (const auto& [id, t] : trails_) {
    const std::size_t n = t.points.size();
    for (std::size_t k = 1; k < n; ++k) {
      // The newest point at full strength, the oldest kept one fading to nothing.
      const float a0 = float(k - 1 + length_ - n) / float(length_ - 1);
      const float a1 = float(k + length_ - n) / float(length_ - 1);
      draw_segment(f, f.to_view(t.points[k - 1]), f.to_view(t.points[k]), 0.9f * a0, 0.9f * a1,
                   depth, colour, picture);
    }
  }
}

}  // namespace voxspan
