// voxspan/attribute.h - a named float attribute of particles (velocity, density...), owned and
// as a view: 1 (scalar) or 3 (vector) interleaved components, one tuple per particle, in the
// particles' order. What the classifier compacts for the boundary particles, what the outputs
// copy and write, and what the particle-file readers return. (voxspan/particles.h's
// AttributeView is the other thing: a strided view of the solver's own arrays.) Standard
// library only.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace voxspan {

struct AttributeSpan {
  std::string_view name;
  int components = 1;  // 1 or 3
  std::span<const float> values;
  std::size_t count() const { return components > 0 ? values.size() / components : 0; }
};

struct Attribute {
  std::string name;
  int components = 1;
  std::vector<float> values;

  AttributeSpan view() const { return {name, components, values}; }
  // Copies `a` in, keeping this attribute's storage (no allocation once it is large enough).
  void assign(const AttributeSpan& a) {
    name.assign(a.name);
    components = a.components;
    values.assign(a.values.begin(), a.values.end());
  }
};

// Throws voxspan::Error naming the attribute unless every attribute has 1 or 3 components and
// exactly `count` tuples.
void check_attributes(std::span<const AttributeSpan> attributes, std::size_t count);

}  // namespace voxspan
