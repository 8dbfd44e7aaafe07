// kernel.h - the cubic B-spline smoothing kernel in 3D (Monaghan 1992), support 2h.
// W(q) = sigma * (1 - 1.5 q^2 + 0.75 q^3) for q < 1, sigma * 0.25 (2 - q)^3 for q < 2, else 0,
// with q = r / h and sigma = 1 / (pi h^3).
#pragma once

#include <numbers>

namespace dambreak {

struct CubicSpline {
  float h = 0, inv_h = 0, sigma = 0;

  explicit CubicSpline(float smoothing_length)
      : h(smoothing_length),
        inv_h(1.0f / smoothing_length),
        sigma(1.0f / (std::numbers::pi_v<float> * smoothing_length * smoothing_length *
                      smoothing_length)) {}

  float support() const { return 2 * h; }

  float w(float r) const {
    const float q = r * inv_h, a = 2 - q;
    return sigma * (q < 1   ? 1 - 1.5f * q * q + 0.75f * q * q * q
                    : q < 2 ? 0.25f * a * a * a
                            : 0.0f);
  }
  // dW/dr divided by r: the gradient is grad_i W_ij = (x_i - x_j) * dw_over_r(r). Finite at
  // r = 0 and 0 beyond the support, and branch-free, so pair loops can run it in SIMD lanes
  // without testing for the particle itself or for distant candidates.
  float dw_over_r(float r) const {
    const float q = r * inv_h, a = 2 - q;
    const float inner = -3 + 2.25f * q;
    const float outer = -0.75f * a * a / (q > 1 ? q : 1);
    return sigma * inv_h * inv_h * (q < 1 ? inner : q < 2 ? outer : 0.0f);
  }
};

}  // namespace dambreak
