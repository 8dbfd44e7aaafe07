// insitu/config/condition.h - a trigger's condition (`when`): an expression over reductions of
// the particles' attributes, the step, the simulated time and the config's constants, parsed
// once at start-up (muparser) and then evaluated without allocating.
//
//   max(velocity) > 1 and time > 0.05      max(x) > 0.8 * tank_length
//   count(outlet) > 100 or not (mean(density, tank) < 1010)
//
// Reductions: min(a), max(a), sum(a), mean(a) of a particle attribute `a` (x, y, z: the
// positions' axes; a vector attribute: its length) and count(), over the owned particles or,
// with a box of the config's `boxes` as the last argument (max(velocity, outlet)), over those
// inside it. `and`, `or`, `not` are muparser's &&, ||, ! (`not` binds tightest: not (a > b)).
// The reductions' names take muparser's own min, max and sum of numbers; the rest of muparser
// is there (arithmetic, comparisons, ?:, abs, sqrt, sin...). The condition names its
// reductions and takes their values (insitu/runtime/particle_reductions.h computes them).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "render/enum_names.h"

namespace voxspan {

enum class ReductionOp : std::uint8_t { min, max, sum, mean, count };
inline constexpr EnumName<ReductionOp> kReductionNames[] = {{"min", ReductionOp::min},
                                                            {"max", ReductionOp::max},
                                                            {"sum", ReductionOp::sum},
                                                            {"mean", ReductionOp::mean},
                                                            {"count", ReductionOp::count}};

// A box of the config's `boxes`: the particles with lo <= position <= hi on every axis.
struct ConditionBox {
  std::array<double, 3> lo{0, 0, 0};
  std::array<double, 3> hi{0, 0, 0};
  bool operator==(const ConditionBox&) const = default;
};

struct Reduction {
  ReductionOp op = ReductionOp::count;
  std::string attribute;  // empty for count()
  std::string box;        // empty: every owned particle
  bool operator==(const Reduction&) const = default;
  std::string text() const;  // "max(velocity, outlet)"
};

// A problem with the expression, and the character of it (0-based) where it lies.
class ConditionError : public std::runtime_error {
 public:
  ConditionError(const std::string& what, std::size_t at)
      : std::runtime_error(what), position(at) {}
  std::size_t position;
};

// Why `name` cannot name a constant or a box of the config (a reserved word, a function of the
// expressions, not a name muparser reads), or empty when it can.
std::string name_problem(std::string_view name);

class Condition {
 public:
  // Throws ConditionError: a syntax error, an unknown name, function or box, a reduction of
  // something that is not an attribute's name.
  Condition(std::string_view text, const std::map<std::string, double>& constants,
            const std::map<std::string, ConditionBox>& boxes);
  Condition(Condition&&) noexcept;
  Condition& operator=(Condition&&) noexcept;
  ~Condition();

  // Each reduction once, in the order of first appearance.
  std::span<const Reduction> reductions() const;
  // The reductions' values for the next holds(), in reductions()' order.
  std::span<double> inputs();
  // Whether the expression is true (non-zero; NaN is false) with these inputs.
  bool holds(std::int64_t step, double time);

 private:
  struct Impl;  // muparser's parser, at a fixed address: it holds pointers to the inputs
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxspan
