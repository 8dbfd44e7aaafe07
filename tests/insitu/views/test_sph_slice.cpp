// The SPH slice's interpolation (insitu/views/sph_slice.h) against the sum computed in double
// over every particle, kernel by kernel; a uniform field flat under Shepard normalisation; the
// kernels normalised; a plane that misses the fluid; the sums at any points (sph_points.h); and
// the colour maps' ends.
#include "insitu/views/sph_slice.h"
#include "insitu/views/sph_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "insitu/views/color_map.h"
#include "insitu/views/slice_layer.h"
#include "tests/support/log_capture.h"
#include "voxspan/error.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.1;

// A jittered lattice block of nx x ny x nz particles with mass, density and a smooth field.
struct Particles {
  std::vector<double> x, y, z, mass, density, field;
  std::vector<float> velocity;  // AoS, float: a vector attribute of the other scalar type

  explicit Particles(int nx, int ny, int nz) {
    std::uint64_t seed = 12345;
    auto jitter = [&] {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return (double(seed >> 11) / double(1ULL << 53) - 0.5) * 0.3 * kSpacing;
    };
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          x.push_back((i + 0.5) * kSpacing + jitter());
          y.push_back((j + 0.5) * kSpacing + jitter());
          z.push_back((k + 0.5) * kSpacing + jitter());
          density.push_back(1000 + 20 * std::sin(7 * x.back()));
          mass.push_back(1000 * kSpacing * kSpacing * kSpacing *
                         (1 + 0.1 * std::cos(5 * y.back())));
          field.push_back(std::sin(3 * x.back()) + z.back() * z.back());
          for (double c : {1.0 + x.back(), -2.0 * y.back(), 0.5}) velocity.push_back(float(c));
        }
  }
  ParticleView view() const {
    return ParticleView::soa(x.data(), y.data(), z.data(), x.size())
        .with_scalar("mass", mass.data())
        .with_scalar("density", density.data())
        .with_scalar("field", field.data())
        .with_vector("velocity", velocity.data());
  }
};

// The quantity `name` with h = 1.3 spacings and the defaults otherwise.
SliceQuantity quantity(const char* name) {
  SliceQuantity q;
  q.name = name;
  q.smoothing_length = 1.3 * kSpacing;
  return q;
}

// The SPH sum at `p` over every particle, in double, by brute force.
double reference(const Particles& s, const SliceQuantity& q, glm::dvec3 p, bool vector) {
  double sum = 0, weight = 0;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double r = glm::length(p - glm::dvec3(s.x[i], s.y[i], s.z[i]));
    const double w = kernel_value(q.kernel, r, q.smoothing_length);
    double a = s.field[i];
    if (vector) {
      const float* v = &s.velocity[3 * i];
      a = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
    }
    sum += s.mass[i] / s.density[i] * a * w;
    weight += s.mass[i] / s.density[i] * w;
  }
  return q.shepard ? (weight > 0 ? sum / weight : 0) : sum;
}

TEST(SphSlice, EqualsTheDoubleSumAtSamplePointsForEveryKernel) {
  const Particles s(16, 12, 10);
  const SlicePlane plane = SlicePlane::make({0.8, 0.6, 0.5}, {0.3, 1, 0.2}, 1.8, 1.2);
  for (const auto& [name, kernel] : kSphKernelNames)
    for (bool shepard : {false, true})
      for (const char* name_of_quantity : {"field", "velocity"}) {
        SliceQuantity q = quantity(name_of_quantity);
        q.kernel = kernel;
        q.shepard = shepard;
        SliceImage image;
        interpolate_slice(s.view(), q, plane, 45, 30, image);
        ASSERT_GT(image.pixels_reached, 300u);
        double worst = 0;
        for (int j = 0; j < 30; j += 3)
          for (int i = 0; i < 45; i += 4) {
            const double want =
                reference(s, q, plane.pixel_centre(i, j, 45, 30), name_of_quantity[0] == 'v');
            const double got = image.values[std::size_t(i + 45 * j)];
            if (std::abs(want) > 1e-3)
              worst = std::max(worst, std::abs(got - want) / std::abs(want));
            else EXPECT_NEAR(got, want, 1e-8);
          }
        EXPECT_LT(worst, 1e-5) << name << (shepard ? " with Shepard " : " ") << name_of_quantity;
      }
}

// Each particle's own h (q.smoothing, astrophysics codes): the particles scatter into the pixels
// their supports' discs cover, which gives the brute-force sum with each particle's h, for every
// kernel, h varying fourfold across the block; and with one h for all, the gather's picture.
TEST(SphSlice, EachParticlesOwnHIsTheDoubleSumWithIt) {
  const Particles s(16, 12, 10);
  std::vector<double> h(s.x.size());
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = (0.8 + 2.4 * s.x[i] / 1.6) * kSpacing;
  const ParticleView view = s.view().with_scalar("h", h.data());
  const SlicePlane plane = SlicePlane::make({0.8, 0.6, 0.5}, {0.3, 1, 0.2}, 1.8, 1.2);
  for (const auto& [name, kernel] : kSphKernelNames) {
    SliceQuantity q = quantity("field");
    q.kernel = kernel;
    q.smoothing = "h";
    SliceImage image;
    interpolate_slice(view, q, plane, 45, 30, image);
    double worst = 0;
    for (int j = 0; j < 30; j += 3)
      for (int i = 0; i < 45; i += 4) {
        const glm::dvec3 p = plane.pixel_centre(i, j, 45, 30);
        double want = 0;
        for (std::size_t k = 0; k < h.size(); ++k)
          want += s.mass[k] / s.density[k] * s.field[k] *
                  kernel_value(kernel, glm::length(p - glm::dvec3(s.x[k], s.y[k], s.z[k])), h[k]);
        const double got = image.values[std::size_t(i + 45 * j)];
        if (std::abs(want) > 1e-3) worst = std::max(worst, std::abs(got - want) / std::abs(want));
        else EXPECT_NEAR(got, want, 1e-8);
      }
    EXPECT_LT(worst, 1e-5) << name;
  }
  std::vector<double> same(h.size(), 1.3 * kSpacing);
  SliceQuantity q = quantity("field");
  q.shepard = true;
  SliceImage gathered, scattered;
  interpolate_slice(s.view(), q, plane, 45, 30, gathered);
  q.smoothing = "h";
  interpolate_slice(s.view().with_scalar("h", same.data()), q, plane, 45, 30, scattered);
  ASSERT_EQ(scattered.pixels_reached, gathered.pixels_reached);
  for (std::size_t k = 0; k < gathered.values.size(); ++k)
    EXPECT_NEAR(scattered.values[k], gathered.values[k], 1e-5 * (1 + std::abs(gathered.values[k])));
  q.smoothing = "hh";
  EXPECT_THROW(interpolate_slice(s.view(), q, plane, 45, 30, scattered), Error);
}

// interpolate_at_points (insitu/views/sph_points.h, a surface view's colours) leaves out the
// particles of cells no point reads, and of a point's cells those its support cannot reach: its
// sums are the full double sum's, at points on a sheet (a first surface: most particles far
// from every point) and at a few scattered ones (larger cells), for every kernel.
TEST(SphPoints, EqualsTheDoubleSumOnASheetAndAtScatteredPoints) {
  const Particles s(16, 12, 30);
  std::vector<glm::dvec3> sheet, scattered;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 60; ++i)
      sheet.push_back(
          {0.02 + 1.6 * i / 59.0, 0.02 + 1.2 * j / 39.0, 0.85 + 0.1 * std::sin(i * 0.3)});
  for (int k = 0; k < 7; ++k) scattered.push_back({0.23 * k, 1.3 - 0.17 * k, 0.1 + 0.4 * k});
  scattered.push_back({50, 50, 50});  // far from every particle: reached by none
  for (const auto& [name, kernel] : kSphKernelNames)
    for (const std::vector<glm::dvec3>* points : {&sheet, &scattered}) {
      SliceQuantity q = quantity("field");
      q.kernel = kernel;
      q.shepard = false;
      SphPoints out;
      interpolate_at_points(s.view(), q, *points, out);
      ASSERT_EQ(out.sum.size(), points->size());
      double worst = 0;
      std::size_t reached = 0;
      for (std::size_t k = 0; k < points->size(); ++k) {
        const double want = reference(s, q, (*points)[k], false);
        reached += out.weight[k] > 0;
        if (std::abs(want) > 1e-3)
          worst = std::max(worst, std::abs(out.sum[k] - want) / std::abs(want));
        else EXPECT_NEAR(out.sum[k], want, 1e-10);
      }
      EXPECT_LT(worst, 1e-12) << name;
      EXPECT_GT(reached, points->size() / 2) << name;
      if (points == &sheet) {
        EXPECT_LT(out.particles_near, 2 * s.x.size() / 3) << name;
      }
    }
}

// The picture's right (u) and up (v): up's projection onto the plane, and where up is along the
// normal a map's axes, so that a 2D run's plane z = 0 reads x right, y up.
TEST(SphSlice, ThePlanesAxesFollowUpOrReadAsAMap) {
  SlicePlane p = SlicePlane::make({0, 0, 0}, {0, -1, 0}, 1, 1);
  EXPECT_EQ(p.u, glm::dvec3(1, 0, 0));
  EXPECT_EQ(p.v, glm::dvec3(0, 0, 1));
  p = SlicePlane::make({0, 0, 0}, {0, 0, 1}, 1, 1);
  EXPECT_EQ(p.u, glm::dvec3(1, 0, 0));
  EXPECT_EQ(p.v, glm::dvec3(0, 1, 0));
  p = SlicePlane::make({0, 0, 0}, {0, 1, 0}, 1, 1, {0, 1, 0});
  EXPECT_EQ(p.v, glm::dvec3(1, 0, 0));
  EXPECT_EQ(p.u, glm::dvec3(0, 0, 1));
}

TEST(SphSlice, AUniformFieldIsFlatWithShepardAwayFromTheFreeSurface) {
  const Particles s(20, 20, 20);
  std::vector<double> three(s.x.size(), 3.0);
  const ParticleView view = s.view().with_scalar("three", three.data());
  const SlicePlane plane = SlicePlane::make({1.0, 1.0, 1.0}, {0, 0, 1}, 2.0, 2.0);
  SliceQuantity q = quantity("three");
  q.shepard = true;
  SliceImage image;
  interpolate_slice(view, q, plane, 40, 40, image);
  double flat = 0;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      const glm::dvec3 p = plane.pixel_centre(i, j, 40, 40);
      const double margin = std::min({p.x, 2.0 - p.x, p.y, 2.0 - p.y});
      if (margin > 0.3)
        flat = std::max(flat, std::abs(image.values[std::size_t(i + 40 * j)] - 3.0));
    }
  EXPECT_LT(flat, 1e-6);
}

TEST(SphSlice, KernelsIntegrateToOne) {
  for (const auto& [name, kernel] : kSphKernelNames) {
    const double h = 0.7, support = kernel_support(kernel) * h;
    double integral = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {  // 4 pi r^2 W(r) dr, midpoint rule
      const double r = (k + 0.5) / n * support;
      integral += 4 * std::numbers::pi * r * r * kernel_value(kernel, r, h) * support / n;
    }
    EXPECT_NEAR(integral, 1.0, 1e-6) << name;
    EXPECT_EQ(kernel_value(kernel, support * 1.0001, h), 0.0) << name;
    double planar = 0;  // 2 pi r W2(r) dr: the 2D kernel over the plane
    for (int k = 0; k < n; ++k) {
      const double r = (k + 0.5) / n * support;
      planar += 2 * std::numbers::pi * r * kernel_value(kernel, r, h, 2) * support / n;
    }
    EXPECT_NEAR(planar, 1.0, 1e-6) << name;
  }
}

// A run in a plane (a 2D lattice, volumes the particles' areas) sums with the 2D kernel: the
// weight, sum_j (m_j / rho_j) W, is 1 inside the fluid without Shepard, as in 3D (the 3D kernel
// gave 12 times that on PySPH's 2D dam break).
TEST(SphSlice, ARunInAPlaneSumsWithThe2DKernel) {
  std::vector<double> x, y, z;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i) {
      x.push_back((i + 0.5) * kSpacing);
      y.push_back((j + 0.5) * kSpacing);
      z.push_back(0);
    }
  const std::vector<double> one(x.size(), 1.0);
  const ParticleView view =
      ParticleView::soa(x.data(), y.data(), z.data(), x.size()).with_scalar("one", one.data());
  const SlicePlane plane = SlicePlane::make({1.5, 1.5, 0}, {0, 0, 1}, 1.0, 1.0, {0, 1, 0});
  for (const auto& [name, kernel] : kSphKernelNames) {
    SliceQuantity q = quantity("one");
    q.kernel = kernel;
    q.dimensions = 2;
    q.rest_volume = kSpacing * kSpacing;
    SliceImage image;
    interpolate_slice(view, q, plane, 20, 20, image);
    for (const double w : image.weight) EXPECT_NEAR(w, 1.0, 0.03) << name;
  }
}

TEST(SphSlice, APlaneThatMissesTheFluidReachesNoPixel) {
  const Particles s(8, 8, 8);
  const SliceQuantity q = quantity("field");
  SliceImage image;
  interpolate_slice(s.view(), q, SlicePlane::make({0, 0, 5}, {0, 0, 1}, 1, 1), 16, 16, image);
  EXPECT_EQ(image.pixels_reached, 0u);
  EXPECT_EQ(image.particles_near, 0u);
}

TEST(SphSlice, AMissingQuantityOrVolumeIsAnErrorNamingIt) {
  const Particles s(4, 4, 4);
  SliceQuantity q = quantity("pressure");
  SliceImage image;
  const SlicePlane plane = SlicePlane::make({0.2, 0.2, 0.2}, {0, 1, 0}, 1, 1);
  EXPECT_THROW(
      {
        try {
          interpolate_slice(s.view(), q, plane, 8, 8, image);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("\"pressure\""), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  q.name = "field";
  q.mass = "m";  // the solver passes none by that name, and no rest volume was given
  EXPECT_THROW(interpolate_slice(s.view(), q, plane, 8, 8, image), Error);
  q.rest_volume = kSpacing * kSpacing * kSpacing;
  EXPECT_NO_THROW(interpolate_slice(s.view(), q, plane, 8, 8, image));
}

// Particles whose value is not a number are left out and counted (the slice view says so once);
// those whose m / rho is not positive (a negative density) are left out as the volume views
// leave them: the slice is then the sum over the others.
TEST(SphSlice, NanValuesAreCountedAndNonPositiveVolumesLeftOut) {
  Particles s(8, 8, 8), kept = s;
  const SliceQuantity q = quantity("field");
  const SlicePlane plane = SlicePlane::make({0.4, 0.4, 0.4}, {0, 0, 1}, 0.8, 0.8);
  SliceImage with_bad, without;
  for (std::size_t i = 0; i < s.x.size(); i += 5) s.field[i] = std::nan("");
  for (std::size_t i = 1; i < s.x.size(); i += 5) s.density[i] = -s.density[i];
  for (std::size_t i = 0; i < s.x.size(); i += 5) kept.mass[i] = kept.mass[i + 1] = 0;
  interpolate_slice(s.view(), q, plane, 16, 16, with_bad);
  interpolate_slice(kept.view(), q, plane, 16, 16, without);
  EXPECT_GT(with_bad.values_not_finite, 0u);
  EXPECT_EQ(without.values_not_finite, 0u);
  EXPECT_EQ(with_bad.values, without.values);
}

// A log scale's automatic range on a slice without Shepard normalisation starts inside the fluid,
// not in the kernel's tail at its edge; a field with no value above 0 is said once.
TEST(SliceLayer, ALogScalesAutomaticRangeStartsInsideTheFluid) {
  Particles s(20, 8, 8);
  for (std::size_t i = 0; i < s.x.size(); ++i) s.field[i] = std::pow(10.0, 1 + 1.5 * s.x[i]);
  Bounds box;
  box.lo = {0, 0, 0}, box.hi = {2, 0.8, 0.8};
  for (const bool shepard : {false, true}) {
    SliceField f;
    f.quantity = "field";
    f.scale = ColorScale::log;
    f.shepard = shepard;
    SliceLayer layer(f, "s", "views[0]", kSpacing, nullptr);
    layer.interpolate(s.view(), box, -1, {0, 0, 1}, 1, 96, 48);
    const ColorAxis axis = layer.axis();
    EXPECT_GT(axis.lo, 5.0) << "shepard " << shepard;  // the field's least is 10 or so
    EXPECT_LT(axis.hi, 1e4) << "shepard " << shepard;
  }
  for (double& v : s.field) v = -v;
  SliceField f;
  f.quantity = "field";
  f.scale = ColorScale::log;
  SliceLayer layer(f, "s", "views[0]", kSpacing, nullptr);
  test::LogCapture log;
  for (std::int64_t step = 1; step <= 2; ++step) {
    layer.interpolate(s.view(), box, -1, {0, 0, 1}, step, 96, 48);
    const ColorAxis axis = layer.axis();
    EXPECT_EQ(axis.lo, 1.0);
  }
  const std::vector<std::string> warnings = log.at(LogLevel::warning);
  ASSERT_EQ(warnings.size(), 1u) << log.all();
  EXPECT_NE(warnings[0].find("view s: scale log, but no value of \"field\" is above 0"),
            std::string::npos)
      << warnings[0];
}

TEST(ColorMap, EndsAreThePublishedColoursAndLuminanceRisesAlongViridis) {
  const glm::vec3 low = map_color(ColorMap::viridis, 0), high = map_color(ColorMap::viridis, 1);
  EXPECT_NEAR(low.r, std::pow((0x44 / 255.0 + 0.055) / 1.055, 2.4), 1e-5);
  EXPECT_NEAR(high.g, std::pow((0xe7 / 255.0 + 0.055) / 1.055, 2.4), 1e-5);
  auto luminance = [](glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; };
  for (int k = 0; k < 100; ++k)
    EXPECT_LT(luminance(map_color(ColorMap::viridis, k / 100.0)),
              luminance(map_color(ColorMap::viridis, (k + 1) / 100.0)));
  EXPECT_EQ(map_color(ColorMap::gray, -1), glm::vec3(0));
  EXPECT_EQ(map_color(ColorMap::gray, std::nan("")), glm::vec3(0));
  EXPECT_EQ(map_color(ColorMap::gray, 2), glm::vec3(1));
}

// A log scale spreads decades evenly; values at or under 0 lie below it; its automatic range
// starts at the smallest value above 0, and the legend's middle is the geometric mean.
TEST(ColorMap, ALogAxisSpreadsDecadesEvenly) {
  const ColorAxis axis{1e-3, 10, ColorScale::log};
  EXPECT_NEAR(axis.t(1e-3), 0, 1e-12);
  EXPECT_NEAR(axis.t(1e-1), 0.5, 1e-12);
  EXPECT_NEAR(axis.t(10), 1, 1e-12);
  EXPECT_EQ(axis.t(0), -INFINITY);
  EXPECT_EQ(axis.t(-1), -INFINITY);
  EXPECT_NEAR(axis.value(0.5), 0.1, 1e-15);
  ValueSpan seen;
  for (double v : {-2.0, 0.0, 4e-3, 7.0, std::nan(""), double(INFINITY)}) seen.add(v);
  const ColorAxis log = display_axis(seen, ColorScale::log);
  EXPECT_EQ(log.lo, 4e-3);
  EXPECT_EQ(log.hi, 7);
  EXPECT_EQ(display_axis(seen, ColorScale::linear).lo, -2);
  const ColorAxis none = display_axis(ValueSpan{}, ColorScale::log);
  EXPECT_EQ(none.lo, 1);
  EXPECT_EQ(none.hi, 10);
  ValueSpan one;
  one.add(5);
  EXPECT_LT(display_axis(one, ColorScale::log).lo, 5);  // widened, still above 0
  EXPECT_GT(display_axis(one, ColorScale::log).lo, 0);
  EXPECT_EQ(color_axis(std::array<double, 2>{2, 3}, seen, ColorScale::log).lo, 2);
}

}  // namespace
}  // namespace voxspan
