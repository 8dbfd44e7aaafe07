#include "tools/scenes/scenes.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace voxspan::test {
namespace {

constexpr double kGravity = 9.81;

ParticleSphere sphere(glm::dvec3 p, double r) {
  return {float(p.x), float(p.y), float(p.z), float(r)};
}

// Ritter's dam-break profile on a dry bed: water height at x for a column of height h0 whose
// dam stood at x0, at time t.
double ritter_height(double x, double x0, double h0, double t) {
  if (t <= 0) return x <= x0 ? h0 : 0;
  const double c0 = std::sqrt(kGravity * h0);
  const double xi = (x - x0) / t;
  if (xi <= -c0) return h0;
  if (xi >= 2 * c0) return 0;
  const double s = 2 * c0 - xi;
  return s * s / (9 * kGravity);
}

}  // namespace

Particles one_sphere(glm::dvec3 center, double radius) { return {sphere(center, radius)}; }

Particles lattice_block(glm::dvec3 lo, glm::ivec3 n, double spacing, double radius) {
  Particles out;
  out.reserve(static_cast<std::size_t>(n.x) * n.y * n.z);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)
        out.push_back(sphere(lo + (glm::dvec3(i, j, k) + 0.5) * spacing, radius));
  return out;
}

double dam_break_spacing(const DamBreak& s, double particles) {
  return std::cbrt(s.width * s.height * s.depth / particles);
}

Particles dam_break(const DamBreak& s, double t, std::uint32_t seed) {
  const int nx = static_cast<int>(std::floor(s.tank_length / s.spacing));
  const int ny = static_cast<int>(std::floor(s.height / s.spacing));
  const int nz = static_cast<int>(std::floor(s.depth / s.spacing));
  Particles out;
  double front = 0;
  for (int i = 0; i < nx; ++i) {
    const double x = (i + 0.5) * s.spacing;
    const double h = std::min(ritter_height(x, s.width, s.height, t), s.height);
    if (h > 0) front = x;
    for (int j = 0; j < ny && (j + 0.5) * s.spacing < h; ++j)
      for (int k = 0; k < nz; ++k)
        out.push_back(
            sphere(glm::dvec3(x, (j + 0.5) * s.spacing, (k + 0.5) * s.spacing), s.radius));
  }
  if (t > 0 && s.spray_fraction > 0) {
    // Droplets above and ahead of the front, as a splashing front throws them.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const auto n = static_cast<std::size_t>(out.size() * s.spray_fraction);
    for (std::size_t k = 0; k < n; ++k) {
      const glm::dvec3 p(std::min(front + 0.1 * s.height * u(rng), s.tank_length),
                         0.05 * s.height + 0.2 * s.height * u(rng), s.depth * u(rng));
      out.push_back(sphere(p, s.radius * (0.5 + 0.5 * u(rng))));
    }
  }
  return out;
}

Particles stacked_layers(int layers, int side, int thickness, double spacing, double radius,
                         double pitch) {
  Particles out;
  for (int l = 0; l < layers; ++l) {
    const Particles sheet =
        lattice_block({0, 0, l * pitch}, {side, side, thickness}, spacing, radius);
    out.insert(out.end(), sheet.begin(), sheet.end());
  }
  return out;
}

Particles checkerboard(int cells, int block, double spacing, double radius) {
  Particles out;
  const int n = cells * block;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if ((i / block + j / block + k / block) % 2 == 0)
          out.push_back(sphere((glm::dvec3(i, j, k) + 0.5) * spacing, radius));
  return out;
}

Particles random_cloud(std::size_t n, glm::dvec3 lo, glm::dvec3 hi, double r0, double r1,
                       std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Particles out(n);
  for (ParticleSphere& p : out) {
    const glm::dvec3 c = lo + (hi - lo) * glm::dvec3(u(rng), u(rng), u(rng));
    p = sphere(c, r0 + (r1 - r0) * u(rng));
  }
  return out;
}

Camera look_at(glm::dvec3 eye, glm::dvec3 target, int width, int height, double fov_y_degrees) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_y_degrees = fov_y_degrees;
  c.width = width;
  c.height = height;
  return c;
}

Camera frame_scene(const Particles& particles, glm::dvec3 direction, int width, int height,
                   double fov_y_degrees, double margin) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const ParticleSphere& p : particles) {
    lo = glm::min(lo, glm::dvec3(p.x, p.y, p.z) - double(p.radius));
    hi = glm::max(hi, glm::dvec3(p.x, p.y, p.z) + double(p.radius));
  }
  const glm::dvec3 center = (lo + hi) * 0.5;
  const double radius = glm::length(hi - lo) * 0.5 * margin;
  const double half = glm::radians(fov_y_degrees) / 2 * std::min(1.0, double(width) / height);
  const double distance = radius / std::sin(half);
  Camera c;
  c.target = center;
  c.eye = center - glm::normalize(direction) * distance;
  c.up = std::abs(glm::normalize(direction).y) > 0.99 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  c.fov_y_degrees = fov_y_degrees;
  c.width = width;
  c.height = height;
  return c;
}

}  // namespace voxspan::test
