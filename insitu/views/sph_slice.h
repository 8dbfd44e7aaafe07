// insitu/views/sph_slice.h - a particle quantity interpolated with the SPH kernel on a plane at
// any position and orientation ([BIDDISCOMBE] sec. 2, ../shared/papers/003): at each pixel x,
//   A(x) = sum_j (m_j / rho_j) A_j W(|x - x_j|, h)
// over the particles whose support reaches x, optionally divided by sum_j (m_j / rho_j) W
// (Shepard normalisation: a uniform field is exactly flat, also near the free surface where the
// plain sum falls off). m and rho come from named attributes; without them every particle has
// the rest volume spacing^3. A vector attribute contributes its magnitude. Only owned
// particles count (ghosts are another rank's), so the sum over ranks is the one-process sum.
// What the `slice` view kind will draw; the sums are done in double, stored as float.
// Costs: one pass over the particles (those within the support of the plane are binned on
// it), then per pixel the particles of the 3x3 bins around it; rows in parallel (oneTBB). With
// each particle's own h (astrophysics codes' adaptive smoothing lengths, spanning decades, which
// one bin size cannot serve) each particle adds itself to the pixels its support's disc on the
// plane covers instead, per band of rows in parallel, in the particles' order.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "render/sph_kernel.h"
#include "voxspan/particles.h"

namespace voxspan {

// A rectangle of the plane through `origin` with unit normal `normal`: `width` along u and
// `height` along v (u, v, normal right-handed; v is the projection of `up` onto the plane, or
// where `up` is along the normal of +y, else of +x: a plane z = const seen from +z reads as a
// 2D run's map, +x right and +y up). Pixel (i, j) of a W x H image, row 0 at the
// top, has its centre at (the picture shows the plane as seen from the side its normal points
// to: with normal -y and up +z, +x is to the right)
//   origin + ((i + 0.5) / W - 0.5) * width * u + (0.5 - (j + 0.5) / H) * height * v.
struct SlicePlane {
  glm::dvec3 origin{0};
  glm::dvec3 normal{0, 1, 0};
  glm::dvec3 u{1, 0, 0}, v{0, 0, 1};
  double width = 1, height = 1;

  static SlicePlane make(glm::dvec3 origin, glm::dvec3 normal, double width, double height,
                         glm::dvec3 up = {0, 0, 1});
  glm::dvec3 pixel_centre(int i, int j, int image_width, int image_height) const;
};

struct SliceQuantity {
  std::string_view name;              // the interpolated attribute (scalar, or vector: magnitude)
  std::string_view key = "quantity";  // the key that names it, for messages
  std::string_view mass = "mass";     // attribute names; when either is missing, m / rho is
  std::string_view density = "density";  // rest_volume for every particle
  double rest_volume = 0;
  SphKernel kernel = SphKernel::cubic_spline;
  double smoothing_length = 0;  // h, world units (> 0)
  std::string_view smoothing;   // the attribute with each particle's h; empty: smoothing_length
  bool shepard = false;
  // 2: the particles lie in a plane (a 2D run): its kernel (sph_kernel.h), and rest_volume an
  // area.
  int dimensions = 3;
};

// One owned particle's part of an SPH sum: its position, (m / rho) A, m / rho and its h.
struct SphTerm {
  glm::dvec3 p;
  double volume_value, volume, h;
};

// The sums at one point x: sum_j (m_j / rho_j) A_j W and sum_j (m_j / rho_j) W.
struct SphSum {
  double sum = 0, weight = 0;
  void add(const SphTerm& t, glm::dvec3 x, const SliceQuantity& q, double h) {
    const glm::dvec3 d = x - t.p;
    const double r2 = glm::dot(d, d), support = kernel_support(q.kernel) * h;
    if (r2 >= support * support) return;  // W is 0 there: most of a neighbourhood's particles
    const double w = kernel_value(q.kernel, std::sqrt(r2), h, q.dimensions);
    sum += t.volume_value * w;
    weight += t.volume * w;
  }
  // The interpolated value: 0 where no particle reaches.
  double value(bool shepard) const { return weight > 0 ? (shepard ? sum / weight : sum) : 0.0; }
};

// The terms of `q` of the owned particles at finite positions for which near(position, h)
// holds, those with a positive finite volume m / rho (as the volume views take them), a finite
// value and a positive h, into `out` (cleared first); returns how many were left out for a NaN
// or infinite value. Throws voxspan::Error naming the attribute when the quantity or
// q.smoothing is missing, or when h is not positive.
std::size_t sph_terms(const ParticleView& particles, const SliceQuantity& q,
                      const std::function<bool(const glm::dvec3&, double)>& near,
                      std::vector<SphTerm>& out);

struct SliceImage {
  int width = 0, height = 0;
  std::vector<float> values;          // row 0 at the top; 0 where no particle reaches
  std::vector<double> sum;            // sum_j (m_j / rho_j) A_j W (what ranks add up)
  std::vector<double> weight;         // sum_j (m_j / rho_j) W: 0 where no particle reaches
  std::size_t particles_near = 0;     // owned particles whose support reaches the plane
  std::size_t pixels_reached = 0;     // pixels with a positive weight
  std::size_t values_not_finite = 0;  // near particles left out for a NaN or infinite value

  // Working storage, kept from step to step (a step with stable sizes allocates nothing).
  std::vector<SphTerm> near;
  std::vector<std::uint32_t> bin_start, bin_fill, bin_of;
  std::vector<SphTerm> sorted;  // the near terms in bin order
};

// Interpolates `q` on `plane` into a width x height image, reusing out's storage. Throws
// voxspan::Error naming the attribute when the quantity is missing, or when h is not positive.
void interpolate_slice(const ParticleView& particles, const SliceQuantity& q,
                       const SlicePlane& plane, int width, int height, SliceImage& out);
// The values (and pixels_reached) from the sums, as interpolate_slice leaves them: again after
// the sums of every rank's owned particles were added up, which gives one process's slice.
void finish_slice(SliceImage& image, bool shepard);

}  // namespace voxspan
