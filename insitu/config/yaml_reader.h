// insitu/config/yaml_reader.h - checking YAML maps against a schema (insitu/config/schema.h):
// typed getters that record an error naming the key path, the file, the line and the column
// instead of throwing, so that one load reports every problem at once. Internal to insitu/
// (includes yaml-cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "render/enum_names.h"

namespace voxspan::yaml {

// Collects errors "<source>:<line>:<column>: <key path>: <message>".
class Checker {
 public:
  explicit Checker(std::string source) : source_(std::move(source)) {}
  void error(const YAML::Mark& mark, const std::string& path, const std::string& message);
  // "<source>:<line>:<column>: <key path>", as error() starts its messages.
  std::string where(const YAML::Mark& mark, const std::string& path) const;
  void error(const YAML::Node& node, const std::string& path, const std::string& message) {
    error(node.Mark(), path, message);
  }
  const std::vector<std::string>& errors() const { return errors_; }
  const std::string& source() const { return source_; }
  // Throws voxspan::Error listing every error, one per line.
  void throw_if_errors() const;

 private:
  std::string source_;
  std::vector<std::string> errors_;
};

// A YAML node as text for messages: scalars quoted, maps and sequences by kind.
std::string describe(const YAML::Node& node);

// The shortest text that reads back as exactly v ("0.8", not "0.80000000000000004").
std::string number_text(double v);

// The numbers a key takes, as messages and the reference say it: "number in (0, 45]",
// "number of at least 0", "number above 0".
struct Range {
  double min = 0;
  double max = 0;  // +inf: unbounded
  bool min_open = false;
  bool contains(double v) const;
  std::string text() const;
};

// One map of the schema. A missing or null node is an empty map (every key at its default).
// Keys outside `allowed` and duplicated keys are errors, reported at the key's line.
class MapReader {
 public:
  MapReader(Checker& checker, const YAML::Node& node, std::string path,
            std::span<const std::string_view> allowed);

  // Each getter leaves `out` untouched when the key is absent or its value is invalid, and
  // returns true only when the key was present and valid.
  bool get(std::string_view key, bool& out);
  bool get(std::string_view key, std::string& out);
  bool get_int(std::string_view key, std::int64_t& out, std::int64_t min, std::int64_t max);
  bool get_double(std::string_view key, double& out, const Range& range);
  // `auto` (std::nullopt) or a number as get_double or get_int checks it.
  bool get_auto_double(std::string_view key, std::optional<double>& out, const Range& range);
  bool get_auto_int(std::string_view key, std::optional<std::int64_t>& out, std::int64_t min,
                    std::int64_t max);
  bool get_vec3(std::string_view key, std::array<double, 3>& out);
  // `auto` (std::nullopt) or three numbers as get_vec3 checks them.
  bool get_auto_vec3(std::string_view key, std::optional<std::array<double, 3>>& out);
  // A list of distinct, non-empty names.
  bool get_names(std::string_view key, std::vector<std::string>& out);
  // A list of distinct integers in [min, max], sorted.
  bool get_integers(std::string_view key, std::vector<std::int64_t>& out, std::int64_t min,
                    std::int64_t max);
  // A list of [a, b] pairs of finite numbers, in the order given.
  bool get_pairs(std::string_view key, std::vector<std::array<double, 2>>& out);
  template <class E>
  bool get_enum(std::string_view key, E& out, std::span<const EnumName<E>> names) {
    std::string text;
    YAML::Node value = find(key);
    if (!value || !get(key, text)) return false;
    if (const std::optional<E> e = value_of(names, text)) {
      out = *e;
      return true;
    }
    checker_.error(value, path(key),
                   "expected one of " + names_of(names) + "; got " + describe(value));
    return false;
  }

  bool has(std::string_view key) const { return static_cast<bool>(find(key)); }
  // The value node of key (an invalid node when absent) and its key path, for nested maps
  // and sequences.
  YAML::Node find(std::string_view key) const;
  std::string path(std::string_view key) const;
  const std::string& path() const { return path_; }  // this map's own key path
  const YAML::Node& node() const { return node_; }
  Checker& checker() { return checker_; }
  const YAML::Mark& mark() const { return mark_; }

 private:
  bool scalar(std::string_view key, YAML::Node& value, const char* expected);

  Checker& checker_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark mark_;
  std::vector<std::pair<std::string, YAML::Node>> entries_;
};

}  // namespace voxspan::yaml
