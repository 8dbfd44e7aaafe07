// voxspan/particles.h - a zero-copy view of a solver's particles: positions (float or double,
// AoS with a byte stride or SoA), an optional per-particle radius (else one radius for all),
// optional named scalar and 3-vector attributes, and how many particles are owned (the rest
// are ghosts from neighbouring ranks, stored after the owned ones).
//
// The view only points at the solver's memory; it never copies or owns it, and building one
// never allocates, so a solver may rebuild it every step. Standard library only.
//
//   auto view = voxspan::ParticleView::soa(x, y, z, n).with_radius(0.5 * dx)
//                   .with_scalar("density", rho).with_vector("velocity", vx, vy, vz);
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace voxspan {

enum class ScalarType : std::uint8_t { float32, float64 };

// One value per particle: particle i's value is at data + i * stride (bytes), of type `type`.
struct StridedScalars {
  const void* data = nullptr;
  ScalarType type = ScalarType::float32;
  std::size_t stride = 0;

  bool present() const { return data != nullptr; }
  double operator[](std::size_t i) const {
    const char* p = static_cast<const char*>(data) + i * stride;
    return type == ScalarType::float32 ? double(*reinterpret_cast<const float*>(p))
                                       : *reinterpret_cast<const double*>(p);
  }

  static StridedScalars of(const float* d, std::size_t stride_bytes = sizeof(float)) {
    return {d, ScalarType::float32, stride_bytes};
  }
  static StridedScalars of(const double* d, std::size_t stride_bytes = sizeof(double)) {
    return {d, ScalarType::float64, stride_bytes};
  }
};

// A named per-particle attribute of 1 (scalar) or 3 (vector) components. The name is not
// copied: it must outlive the view (string literals do).
struct AttributeView {
  std::string_view name;
  int components = 0;
  std::array<StridedScalars, 3> component{};

  // Particle i's value: the scalar, or the vector's length.
  double magnitude(std::size_t i) const {
    if (components == 1) return component[0][i];
    const double x = component[0][i], y = component[1][i], z = component[2][i];
    return std::sqrt(x * x + y * y + z * z);
  }
};

class ParticleView {
 public:
  static constexpr int kMaxAttributes = 16;

  // Zero particles: a valid, empty step.
  ParticleView() = default;

  // Array of structures: particle i's x, y, z at xyz + i * stride_bytes (y and z follow x).
  static ParticleView aos(const float* xyz, std::size_t count,
                          std::size_t stride_bytes = 3 * sizeof(float)) {
    return from_aos(xyz, count, stride_bytes);
  }
  static ParticleView aos(const double* xyz, std::size_t count,
                          std::size_t stride_bytes = 3 * sizeof(double)) {
    return from_aos(xyz, count, stride_bytes);
  }
  // Structure of arrays: three dense arrays.
  static ParticleView soa(const float* x, const float* y, const float* z, std::size_t count) {
    return from_axes(StridedScalars::of(x), StridedScalars::of(y), StridedScalars::of(z), count);
  }
  static ParticleView soa(const double* x, const double* y, const double* z, std::size_t count) {
    return from_axes(StridedScalars::of(x), StridedScalars::of(y), StridedScalars::of(z), count);
  }
  // Any strided layout, one array per axis (all three of one scalar type).
  static ParticleView from_axes(StridedScalars x, StridedScalars y, StridedScalars z,
                                std::size_t count) {
    ParticleView v;
    v.position_ = {x, y, z};
    v.count_ = count;
    v.owned_ = count;
    return v;
  }

  // The first `owned` particles belong to this rank; the rest are ghosts. Default: all.
  ParticleView& with_owned(std::size_t owned) {
    owned_ = owned;
    return *this;
  }
  // One radius for every particle (world units).
  ParticleView& with_radius(double radius) {
    radius_ = radius;
    return *this;
  }
  // A radius per particle; overrides with_radius().
  ParticleView& with_radii(const float* r, std::size_t stride_bytes = sizeof(float)) {
    radii_ = StridedScalars::of(r, stride_bytes);
    return *this;
  }
  ParticleView& with_radii(const double* r, std::size_t stride_bytes = sizeof(double)) {
    radii_ = StridedScalars::of(r, stride_bytes);
    return *this;
  }
  ParticleView& with_radii(StridedScalars r) {
    radii_ = r;
    return *this;
  }

  // Named attributes. Past kMaxAttributes the view remembers the overflow and the step that
  // uses it fails with a message naming the attribute (the builder itself never throws).
  template <class T>
  ParticleView& with_scalar(std::string_view name, const T* values,
                            std::size_t stride_bytes = sizeof(T)) {
    return add({name, 1, {StridedScalars::of(values, stride_bytes), {}, {}}});
  }
  // A 3-vector stored AoS (x, y, z of a particle adjacent).
  template <class T>
  ParticleView& with_vector(std::string_view name, const T* xyz,
                            std::size_t stride_bytes = 3 * sizeof(T)) {
    return add({name,
                3,
                {StridedScalars::of(xyz, stride_bytes), StridedScalars::of(xyz + 1, stride_bytes),
                 StridedScalars::of(xyz + 2, stride_bytes)}});
  }
  // A 3-vector stored SoA.
  template <class T>
  ParticleView& with_vector(std::string_view name, const T* x, const T* y, const T* z) {
    return add({name, 3, {StridedScalars::of(x), StridedScalars::of(y), StridedScalars::of(z)}});
  }
  ParticleView& with_attribute(const AttributeView& attribute) { return add(attribute); }

  std::size_t size() const { return count_; }
  std::size_t owned_count() const { return owned_ < count_ ? owned_ : count_; }
  bool empty() const { return count_ == 0; }

  const StridedScalars& axis(int a) const { return position_[std::size_t(a)]; }
  std::array<double, 3> position(std::size_t i) const {
    return {position_[0][i], position_[1][i], position_[2][i]};
  }
  bool position_finite(std::size_t i) const {
    auto p = position(i);
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  }

  bool has_radii() const { return radii_.present(); }
  const StridedScalars& radii() const { return radii_; }
  // The uniform radius; 0 when the solver gave none.
  double uniform_radius() const { return radius_; }
  double radius(std::size_t i) const { return radii_.present() ? radii_[i] : radius_; }

  int attribute_count() const { return attribute_count_; }
  const AttributeView& attribute(int k) const { return attributes_[std::size_t(k)]; }
  const AttributeView* find_attribute(std::string_view name) const {
    for (int k = 0; k < attribute_count_; ++k)
      if (attributes_[std::size_t(k)].name == name) return &attributes_[std::size_t(k)];
    return nullptr;
  }
  // The name of the first attribute that did not fit (empty when none overflowed).
  std::string_view overflowed_attribute() const { return overflow_; }

 private:
  template <class T>
  static ParticleView from_aos(const T* xyz, std::size_t count, std::size_t stride) {
    return from_axes(StridedScalars::of(xyz, stride), StridedScalars::of(xyz + 1, stride),
                     StridedScalars::of(xyz + 2, stride), count);
  }
  ParticleView& add(const AttributeView& a) {
    if (attribute_count_ < kMaxAttributes) attributes_[std::size_t(attribute_count_++)] = a;
    else if (overflow_.empty()) overflow_ = a.name;
    return *this;
  }

  std::array<StridedScalars, 3> position_{};
  std::size_t count_ = 0;
  std::size_t owned_ = 0;
  double radius_ = 0;
  StridedScalars radii_{};
  std::array<AttributeView, kMaxAttributes> attributes_{};
  int attribute_count_ = 0;
  std::string_view overflow_;
};

}  // namespace voxspan
