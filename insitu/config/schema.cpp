#include "insitu/config/schema.h"

#include <cctype>
#include <cmath>
#include <limits>
#include <span>

namespace voxspan::schema {
void emit_value(YAML::Emitter& e, bool v) { e << v; }
void emit_value(YAML::Emitter& e, int v) { e << v; }
void emit_value(YAML::Emitter& e, std::int64_t v) { e << v; }
// Exact and short: a loaded config written again reads back as the same numbers.
void emit_value(YAML::Emitter& e, double v) { e << yaml::number_text(v); }
void emit_value(YAML::Emitter& e, const std::string& v) { e << v; }

namespace {
void emit_numbers(YAML::Emitter& e, std::span<const double> v) {
  e << YAML::Flow << YAML::BeginSeq;
  for (double x : v) emit_value(e, x);
  e << YAML::EndSeq;
}
}  // namespace

void emit_value(YAML::Emitter& e, const std::array<double, 2>& v) { emit_numbers(e, v); }
void emit_value(YAML::Emitter& e, const std::array<double, 3>& v) { emit_numbers(e, v); }

void emit_value(YAML::Emitter& e, const std::vector<std::array<double, 2>>& v) {
  e << YAML::BeginSeq;
  for (const std::array<double, 2>& pair : v) emit_numbers(e, pair);
  e << YAML::EndSeq;
}

void emit_value(YAML::Emitter& e, const std::vector<std::int64_t>& v) {
  e << YAML::Flow << YAML::BeginSeq;
  for (std::int64_t x : v) emit_value(e, x);
  e << YAML::EndSeq;
}

void emit_value(YAML::Emitter& e, const std::vector<std::string>& v) {
  e << YAML::Flow << YAML::BeginSeq;
  for (const std::string& name : v) e << name;
  e << YAML::EndSeq;
}

bool is_plain_name(std::string_view name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

std::string integer_type(std::int64_t min, std::int64_t max) {
  if (max == std::numeric_limits<std::int64_t>::max()) return "integer >= " + std::to_string(min);
  return "integer " + std::to_string(min) + ".." + std::to_string(max);
}

Range at_least(double min) { return {min, HUGE_VAL, false}; }
Range above(double min) { return {min, HUGE_VAL, true}; }
Range between(double min, double max) { return {min, max, false}; }
Range above_up_to(double min, double max) { return {min, max, true}; }
Range any_number() { return {-HUGE_VAL, HUGE_VAL, false}; }

bool read_interval(yaml::MapReader& r, const std::string& name, Interval& v) {
  if (!r.has(name)) return false;
  const YAML::Node n = r.find(name);
  if (n.IsScalar() && n.Scalar() == "auto") {
    v.reset();
    return true;
  }
  double lo = 0, hi = 0;
  bool ok = n.IsSequence() && n.size() == 2;
  try {
    if (ok) lo = n[0].as<double>(), hi = n[1].as<double>();
  } catch (const YAML::Exception&) {
    ok = false;
  }
  if (!ok || !std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    const bool finite = !ok || (std::isfinite(lo) && std::isfinite(hi));
    r.checker().error(n, r.path(name),
                      finite ? "expected `auto` or [min, max] with min < max"
                             : "expected `auto` or [min, max] of finite numbers; got [" +
                                   yaml::number_text(lo) + ", " + yaml::number_text(hi) + "]");
    return false;
  }
  v = std::array<double, 2>{lo, hi};
  return true;
}

}  // namespace voxspan::schema
