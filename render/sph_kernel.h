// render/sph_kernel.h - the SPH smoothing kernels W(r, h) the views interpolate with, 3D (or 2D,
// for a run in a plane) and normalised to integrate to 1 over space: Monaghan's cubic spline,
// Wendland's C2 and Morris's quintic spline (the forms and constants of PySPH's kernels, support
// 2h, 2h and 3h), and Mueller's poly6 ([FAW10] sec. 6's fluid kernel, support h). The shape
// functions are inline: the volume renderers call them once per sample and particle.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "render/enum_names.h"

namespace voxspan {

enum class SphKernel : std::uint8_t { cubic_spline, wendland_c2, quintic, poly6 };
inline constexpr EnumName<SphKernel> kSphKernelNames[] = {{"cubic_spline", SphKernel::cubic_spline},
                                                          {"wendland_c2", SphKernel::wendland_c2},
                                                          {"quintic", SphKernel::quintic},
                                                          {"poly6", SphKernel::poly6}};

// The kernel's support radius in units of h.
constexpr double kernel_support(SphKernel kernel) {
  switch (kernel) {
    case SphKernel::quintic: return 3.0;
    case SphKernel::poly6: return 1.0;
    default: return 2.0;
  }
}

// max(x, 0) for finite x, exactly, without a comparison: GCC's vectorizer gives up on loops
// holding two std::max of doubles ("control flow"), not on fabs.
inline double truncated(double x) { return 0.5 * (x + std::abs(x)); }

// h^3 W(q h, h) at q = r / h (q >= 0; 0 past the support): W without its 1 / h^3. Written with
// truncated powers, max(x, 0)^n, and no branch, so that a loop over samples vectorizes.
template <SphKernel K> inline double kernel_shape(double q) {
  constexpr double pi = std::numbers::pi;
  if constexpr (K == SphKernel::cubic_spline) {
    const double a = truncated(2 - q), b = truncated(1 - q);
    return (0.25 / pi) * (a * a * a - 4 * b * b * b);
  } else if constexpr (K == SphKernel::wendland_c2) {
    const double t = truncated(1 - 0.5 * q);
    return (21.0 / (16.0 * pi)) * (t * t) * (t * t) * (2 * q + 1);
  } else if constexpr (K == SphKernel::quintic) {
    const auto p5 = [](double x) {
      const double y = truncated(x), y2 = y * y;
      return y2 * y2 * y;
    };
    return (1.0 / (120.0 * pi)) * (p5(3 - q) - 6 * p5(2 - q) + 15 * p5(1 - q));
  } else {
    const double t = truncated(1 - q * q);
    return (315.0 / (64.0 * pi)) * t * t * t;
  }
}

// d(h^3 W)/dq at q: the kernel's slope, for gradients of interpolated fields.
template <SphKernel K> inline double kernel_slope(double q) {
  constexpr double pi = std::numbers::pi;
  if constexpr (K == SphKernel::cubic_spline) {
    if (q < 1) return (-3 * q + 2.25 * q * q) / pi;
    if (q < 2) return -0.75 / pi * (2 - q) * (2 - q);
    return 0;
  } else if constexpr (K == SphKernel::wendland_c2) {
    if (q >= 2) return 0;
    const double t = 1 - 0.5 * q;
    return 21.0 / (16.0 * pi) * (-5 * q) * t * t * t;
  } else if constexpr (K == SphKernel::quintic) {
    if (q >= 3) return 0;
    const auto p4 = [](double x) { return x > 0 ? x * x * x * x : 0.0; };
    return -5.0 / (120.0 * pi) * (p4(3 - q) - 6 * p4(2 - q) + 15 * p4(1 - q));
  } else {
    if (q >= 1) return 0;
    const double t = 1 - q * q;
    return 315.0 / (64.0 * pi) * (-6 * q) * t * t;
  }
}

// f.template operator()<K>() for the kernel named at run time: one dispatch per call site, the
// kernel inlined in the loop inside.
template <class F> decltype(auto) with_kernel(SphKernel kernel, F&& f) {
  switch (kernel) {
    case SphKernel::wendland_c2: return f.template operator()<SphKernel::wendland_c2>();
    case SphKernel::quintic: return f.template operator()<SphKernel::quintic>();
    case SphKernel::poly6: return f.template operator()<SphKernel::poly6>();
    default: return f.template operator()<SphKernel::cubic_spline>();
  }
}

// The 2D kernel over the 3D one at the same r / h, times 1 / h: each kernel has one shape in both,
// with its own normalisation (PySPH's constants; cubic spline 10 / (7 pi) against 1 / pi).
constexpr double planar_ratio(SphKernel kernel) {
  switch (kernel) {
    case SphKernel::wendland_c2: return 4.0 / 3.0;      // 7 / (4 pi) against 21 / (16 pi)
    case SphKernel::quintic: return 120.0 * 7 / 478.0;  // 7 / (478 pi) against 1 / (120 pi)
    case SphKernel::poly6: return 256.0 / 315.0;        // 4 / pi against 315 / (64 pi)
    default: return 10.0 / 7.0;
  }
}

// W(r, h), normalised over 3D space, or over the plane (dimensions 2) for a run in a plane.
inline double kernel_value(SphKernel kernel, double r, double h, int dimensions = 3) {
  const double w =
      with_kernel(kernel, [&]<SphKernel K>() { return kernel_shape<K>(r / h) / (h * h * h); });
  return dimensions == 2 ? w * h * planar_ratio(kernel) : w;
}

}  // namespace voxspan
