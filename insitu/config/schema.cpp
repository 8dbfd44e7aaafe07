#include "insitu/config/schema.h"

#include <cctype>
#include <cmath>
#include <limits>

namespace voxspan::schema {
void emit_value(YAML::Emitter& e, bool v) { e << v; }
void emit_value(YAML::Emitter& e, int v) { e << v; }
void emit_value(YAML::Emitter& e, std::int64_t v) { e << v; }
// Exact and short: a loaded config written again reads back as the same numbers.
void emit_value(YAML::Emitter& e, double v) { e << yaml::number_text(v); }
void emit_value(YAML::Emitter& e, const std::string& v) { e << v; }

void emit_value(YAML::Emitter& e, const std::array<double, 3>& v) {
  e << YAML::Flow << YAML::BeginSeq;
  for (double x : v) emit_value(e, x);
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

}  // namespace voxspan::schema
