// positions.h (internal) - typed, strided reads of a ParticleView's positions and radii for
// the hot loops (one branch on the scalar type per classification, not per particle).
#pragma once

#include <cmath>
#include <cstddef>

#include "voxspan/particles.h"

namespace voxspan::detail {

template <class T> struct Positions {
  const char* base[3];
  std::size_t stride[3];

  explicit Positions(const ParticleView& v) {
    for (int a = 0; a < 3; ++a) {
      base[a] = static_cast<const char*>(v.axis(a).data);
      stride[a] = v.axis(a).stride;
    }
  }
  T get(int a, std::size_t i) const { return *reinterpret_cast<const T*>(base[a] + i * stride[a]); }
  // Loads particle i; false when a coordinate is NaN or infinite.
  bool load(std::size_t i, T& x, T& y, T& z) const {
    x = get(0, i);
    y = get(1, i);
    z = get(2, i);
    return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
  }
};

// The radius of each particle: per particle from the view, else one value.
struct Radii {
  StridedScalars per_particle;
  float uniform = 0;

  bool varies() const { return per_particle.present(); }
  float get(std::size_t i) const {
    return per_particle.present() ? static_cast<float>(per_particle[i]) : uniform;
  }
  // A usable radius: finite and not negative.
  static bool usable(float r) { return std::isfinite(r) && r >= 0; }
};

}  // namespace voxspan::detail
