#include "insitu/config/yaml_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <span>
#include <string_view>
#include <utility>

#include "sim_adapter/near_name.h"
#include "voxspan/error.h"

namespace voxspan::yaml {

std::string Checker::where(const YAML::Mark& mark, const std::string& path) const {
  std::ostringstream s;
  s << source_;
  if (!mark.is_null()) s << ":" << mark.line + 1 << ":" << mark.column + 1;
  s << ": " << (path.empty() ? "(top level)" : path);
  return s.str();
}

void Checker::error(const YAML::Mark& mark, const std::string& path, const std::string& message) {
  errors_.push_back(where(mark, path) + ": " + message);
}

void Checker::throw_if_errors() const {
  if (errors_.empty()) return;
  std::string text = errors_.size() == 1 ? "invalid configuration: "
                                         : "invalid configuration (" +
                                               std::to_string(errors_.size()) + " errors):\n  ";
  for (std::size_t i = 0; i < errors_.size(); ++i) text += (i ? "\n  " : "") + errors_[i];
  throw Error(text);
}

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return "\"" + node.Scalar() + "\"";
    case YAML::NodeType::Sequence: {
      // A short list of scalars as written, [0.1, 0.5]; any other as what it is.
      if (node.size() > 6) return "a list";
      std::string text = "[";
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar()) return "a list";
        text += (i ? ", " : "") + node[i].Scalar();
      }
      return text + "]";
    }
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Undefined: break;
  }
  return "nothing";
}

namespace {

// ", whose item k + 1 is ..." for a list whose item k is the one found wrong; "" otherwise.
std::string item_text(const YAML::Node& list, std::size_t k) {
  if (!list.IsSequence() || k >= list.size()) return "";
  return ", whose item " + std::to_string(k + 1) + " is " + describe(list[k]);
}

}  // namespace

std::string number_text(double v) {
  char text[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

bool Range::contains(double v) const {
  return std::isfinite(v) && (min_open ? v > min : v >= min) && v <= max;
}

std::string Range::text() const {
  if (std::isinf(min) && std::isinf(max)) return "number";
  if (std::isinf(max))
    return (min_open ? "number above " : "number of at least ") + number_text(min);
  return "number in " + std::string(min_open ? "(" : "[") + number_text(min) + ", " +
         number_text(max) + "]";
}

namespace {

// Keys renamed since a release, old name first: a config that still says the old one is told
// the new name where the new one belongs.
constexpr std::pair<std::string_view, std::string_view> kRenamedKeys[] = {
    {"alpha", "layer_angle"},  // a surface view's: `alpha` read as opacity
};

std::string_view renamed(std::string_view key, std::span<const std::string_view> allowed) {
  for (const auto& [old_name, new_name] : kRenamedKeys)
    if (key == old_name && std::find(allowed.begin(), allowed.end(), new_name) != allowed.end())
      return new_name;
  return {};
}

}  // namespace

MapReader::MapReader(Checker& checker, const YAML::Node& node, std::string path,
                     std::span<const std::string_view> allowed)
    : checker_(checker), node_(node), path_(std::move(path)) {
  if (!node || node.IsNull()) return;
  mark_ = node.Mark();
  if (!node.IsMap()) {
    checker_.error(node, path_, "expected a map of settings; got " + describe(node));
    return;
  }
  // By value: yaml-cpp's iterator returns its (key, value) pair as a temporary, so a reference
  // to it->first dangles by the next line (AddressSanitizer: stack-use-after-scope).
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key_node = it->first;
    if (!key_node.IsScalar()) {
      checker_.error(key_node, path_, "keys must be plain names; got " + describe(key_node));
      continue;
    }
    const std::string& key = key_node.Scalar();
    std::string key_path = path_.empty() ? key : path_ + "." + key;
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      if (const std::string_view now = renamed(key, allowed); !now.empty()) {
        checker_.error(key_node, key_path, "was renamed '" + std::string(now) + "'");
        continue;
      }
      std::string hint = near_name(key, allowed);
      std::string known;
      for (std::string_view k : allowed) known += (known.empty() ? "" : ", ") + std::string(k);
      checker_.error(key_node, key_path,
                     "unknown key" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                         "; known keys here: " + known);
      continue;
    }
    bool duplicate = std::any_of(entries_.begin(), entries_.end(),
                                 [&](const auto& e) { return e.first == key; });
    if (duplicate) {
      checker_.error(key_node, key_path, "given twice");
      continue;
    }
    entries_.emplace_back(key, it->second);
  }
}

YAML::Node MapReader::find(std::string_view key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return v;
  return YAML::Node(YAML::NodeType::Undefined);
}

std::string MapReader::path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool MapReader::scalar(std::string_view key, YAML::Node& value, const char* expected) {
  value = find(key);
  if (!value.IsDefined()) return false;
  if (!value.IsScalar()) {
    checker_.error(value, path(key),
                   std::string("expected ") + expected + "; got " + describe(value));
    return false;
  }
  return true;
}

bool MapReader::get(std::string_view key, bool& out) {
  YAML::Node value;
  if (!scalar(key, value, "true or false")) return false;
  bool b = false;
  if (!YAML::convert<bool>::decode(value, b)) {
    checker_.error(value, path(key), "expected true or false; got " + describe(value));
    return false;
  }
  out = b;
  return true;
}

bool MapReader::get(std::string_view key, std::string& out) {
  YAML::Node value;
  if (!scalar(key, value, "a text")) return false;
  out = value.Scalar();
  return true;
}

bool MapReader::get_int(std::string_view key, std::int64_t& out, std::int64_t min,
                        std::int64_t max) {
  YAML::Node value;
  if (!scalar(key, value, "an integer")) return false;
  std::int64_t v = 0;
  std::string range = "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  if (!YAML::convert<std::int64_t>::decode(value, v) || v < min || v > max) {
    checker_.error(value, path(key), "expected " + range + "; got " + describe(value));
    return false;
  }
  out = v;
  return true;
}

bool MapReader::get_double(std::string_view key, double& out, const Range& range) {
  YAML::Node value;
  if (!scalar(key, value, "a number")) return false;
  double v = 0;
  if (!YAML::convert<double>::decode(value, v) || !range.contains(v)) {
    checker_.error(value, path(key), "expected a " + range.text() + "; got " + describe(value));
    return false;
  }
  out = v;
  return true;
}

bool MapReader::get_auto_double(std::string_view key, std::optional<double>& out,
                                const Range& range) {
  YAML::Node value = find(key);
  if (value.IsDefined() && value.IsScalar() && value.Scalar() == "auto") {
    out.reset();
    return true;
  }
  double v = 0;
  if (!get_double(key, v, range)) return false;
  out = v;
  return true;
}

bool MapReader::get_auto_int(std::string_view key, std::optional<std::int64_t>& out,
                             std::int64_t min, std::int64_t max) {
  YAML::Node value = find(key);
  if (value.IsDefined() && value.IsScalar() && value.Scalar() == "auto") {
    out.reset();
    return true;
  }
  std::int64_t v = 0;
  if (!get_int(key, v, min, max)) return false;
  out = v;
  return true;
}

bool MapReader::get_vec3(std::string_view key, std::array<double, 3>& out) {
  YAML::Node value = find(key);
  if (!value.IsDefined()) return false;
  std::array<double, 3> v{};
  bool ok = value.IsSequence() && value.size() == 3;
  for (std::size_t i = 0; ok && i < 3; ++i)
    ok =
        value[i].IsScalar() && YAML::convert<double>::decode(value[i], v[i]) && std::isfinite(v[i]);
  if (!ok) {
    checker_.error(value, path(key), "expected three numbers [x, y, z]; got " + describe(value));
    return false;
  }
  out = v;
  return true;
}

bool MapReader::get_auto_vec3(std::string_view key, std::optional<std::array<double, 3>>& out) {
  YAML::Node value = find(key);
  if (value.IsDefined() && value.IsScalar() && value.Scalar() == "auto") {
    out.reset();
    return true;
  }
  std::array<double, 3> v{};
  if (!get_vec3(key, v)) return false;
  out = v;
  return true;
}

bool MapReader::get_names(std::string_view key, std::vector<std::string>& out) {
  YAML::Node value = find(key);
  if (!value.IsDefined()) return false;
  std::vector<std::string> v;
  bool ok = value.IsSequence() || value.IsNull();
  for (std::size_t i = 0; ok && value.IsSequence() && i < value.size(); ++i) {
    ok = value[i].IsScalar() && !value[i].Scalar().empty();
    if (ok) v.push_back(value[i].Scalar());
  }
  if (!ok) {
    checker_.error(value, path(key), "expected a list of names; got " + describe(value));
    return false;
  }
  for (std::size_t i = 0; i < v.size(); ++i)
    if (std::find(v.begin(), v.begin() + i, v[i]) != v.begin() + i) {
      checker_.error(value, path(key), "\"" + v[i] + "\" given twice");
      return false;
    }
  out = std::move(v);
  return true;
}

bool MapReader::get_integers(std::string_view key, std::vector<std::int64_t>& out, std::int64_t min,
                             std::int64_t max) {
  YAML::Node value = find(key);
  if (!value.IsDefined()) return false;
  std::vector<std::int64_t> v;
  bool ok = value.IsSequence() || value.IsNull();
  std::size_t i = 0;
  for (; ok && value.IsSequence() && i < value.size(); ++i) {
    try {
      v.push_back(value[i].as<std::int64_t>());
      ok = v.back() >= min && v.back() <= max;
    } catch (const YAML::Exception&) {
      ok = false;
    }
  }
  if (!ok) {
    checker_.error(value, path(key),
                   "expected a list of integers in [" + std::to_string(min) + ", " +
                       std::to_string(max) + "]; got " + describe(value) + item_text(value, i - 1));
    return false;
  }
  std::sort(v.begin(), v.end());
  if (std::adjacent_find(v.begin(), v.end()) != v.end()) {
    checker_.error(value, path(key), "an integer given twice");
    return false;
  }
  out = std::move(v);
  return true;
}

bool MapReader::get_pairs(std::string_view key, std::vector<std::array<double, 2>>& out) {
  YAML::Node value = find(key);
  if (!value.IsDefined()) return false;
  std::vector<std::array<double, 2>> v;
  bool ok = value.IsSequence();
  std::size_t i = 0;
  for (; ok && i < value.size(); ++i) {
    const YAML::Node pair = value[i];
    ok = pair.IsSequence() && pair.size() == 2;
    try {
      if (ok) v.push_back({pair[0].as<double>(), pair[1].as<double>()});
      ok = ok && std::isfinite(v.back()[0]) && std::isfinite(v.back()[1]);
    } catch (const YAML::Exception&) {
      ok = false;
    }
  }
  if (!ok) {
    checker_.error(value, path(key),
                   "expected a list of [a, b] pairs of numbers; got " + describe(value) +
                       item_text(value, i - 1));
    return false;
  }
  out = std::move(v);
  return true;
}

}  // namespace voxspan::yaml
