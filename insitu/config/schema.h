// insitu/config/schema.h - a config section's keys, each written once: its name, the member
// it fills, its type and range, its default (the member's own initializer) and its help text.
// One table drives the reading (unknown keys, types and ranges are errors naming the file,
// the line and the key path: insitu/config/yaml_reader.h), the effective config as YAML
// (to_yaml) and the reference tables of docs/runtime.md (`voxspan-config --reference`, which a
// test holds the docs to).
//
//   const schema::Section<WriterConfig>& writer_section() {
//     static const schema::Section<WriterConfig> s{"writer", {
//         schema::integer("queue_size", &WriterConfig::queue_size, 1, 4096, "jobs waiting"),
//         schema::choice("when_full", &WriterConfig::when_full, kQueuePolicyNames, "..."),
//         schema::flag("fsync", &WriterConfig::fsync, "files are fsynced before ...")}};
//     return s;
//   }
//
// Rules across keys (a manual camera needs eye and target) go in the section's `check`, run
// after its keys are read. Internal to insitu/ (includes yaml-cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <functional>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/yaml_reader.h"
#include "render/enum_names.h"

namespace voxspan::schema {

// One key of a section whose values live in a T.
template <class T> struct Key {
  std::string name;
  std::string type;  // for the reference: "integer 1..16384", "`wait` `drop`", "bool"
  std::string help;
  std::string shown_default;  // for the reference; empty: T{}'s value as YAML
  // Reads the key from the section (absent: leaves `out` as it is). Errors go to the checker.
  std::function<void(yaml::MapReader&, T& out)> read;
  // Emits the key's value (not the key).
  std::function<void(YAML::Emitter&, const T&)> emit;
  // When set, the key is written by to_yaml only where it holds (camera.eye for manual ones).
  std::function<bool(const T&)> applies;

  Key&& default_shown_as(std::string text) && {
    shown_default = std::move(text);
    return std::move(*this);
  }
  Key&& only_when(std::function<bool(const T&)> holds) && {
    applies = std::move(holds);
    return std::move(*this);
  }
};

template <class T> class Section {
 public:
  using Check = std::function<void(yaml::MapReader&, T&)>;
  // `path` names the section in messages and in the reference ("views[i].camera").
  Section(std::string path, std::vector<Key<T>> keys, Check check = {})
      : path_(std::move(path)), keys_(std::move(keys)), check_(std::move(check)) {
    for (const Key<T>& k : keys_) names_.push_back(k.name);
  }
  Section(const Section&) = delete;  // names_ views keys_
  Section& operator=(const Section&) = delete;

  const std::string& path() const { return path_; }
  const std::vector<Key<T>>& keys() const { return keys_; }
  std::span<const std::string_view> names() const { return names_; }

  // Reads a map node into `out`: keys absent keep out's values. A missing or null node is an
  // empty map. `path` is the node's key path in messages ("views[2].camera").
  void read(yaml::Checker& checker, const YAML::Node& node, const std::string& path, T& out) const {
    yaml::MapReader r(checker, node, path, names_);
    read(r, out);
  }
  void read(yaml::MapReader& r, T& out) const {
    for (const Key<T>& k : keys_) k.read(r, out);
    if (check_) check_(r, out);
  }

  // The keys and values as a YAML map (BeginMap ... EndMap).
  void emit(YAML::Emitter& e, const T& value) const {
    e << YAML::BeginMap;
    emit_keys(e, value);
    e << YAML::EndMap;
  }
  // The keys and values without the enclosing map, for sections that share one.
  void emit_keys(YAML::Emitter& e, const T& value) const {
    for (const Key<T>& k : keys_) {
      if (k.applies && !k.applies(value)) continue;
      e << YAML::Key << k.name << YAML::Value;
      k.emit(e, value);
    }
  }

  // The markdown reference table: | key | type | default | meaning |, defaults from `defaults`.
  std::string reference(const T& defaults = T{}) const;

 private:
  std::string path_;
  std::vector<Key<T>> keys_;
  std::vector<std::string_view> names_;  // views of keys_' names, for the reader
  Check check_;
};

// ---- values as YAML and as reference text

void emit_value(YAML::Emitter& e, bool v);
void emit_value(YAML::Emitter& e, int v);
void emit_value(YAML::Emitter& e, std::int64_t v);
void emit_value(YAML::Emitter& e, double v);
void emit_value(YAML::Emitter& e, const std::string& v);
void emit_value(YAML::Emitter& e, const std::array<double, 2>& v);
void emit_value(YAML::Emitter& e, const std::array<double, 3>& v);
void emit_value(YAML::Emitter& e, const std::vector<std::string>& v);
void emit_value(YAML::Emitter& e, const std::vector<std::int64_t>& v);
void emit_value(YAML::Emitter& e, const std::vector<std::array<double, 2>>& v);
template <class V> void emit_value(YAML::Emitter& e, const std::optional<V>& v) {
  if (v) emit_value(e, *v);
  else e << "auto";
}

// A value as the reference shows it: `the YAML`, in flow style.
template <class F> std::string shown(F&& emit) {
  YAML::Emitter e;
  e << YAML::Flow;
  emit(e);
  std::string text = "`";  // appended, not "`" + ...: GCC 12 warns falsely (-Wrestrict) there
  text.append(e.c_str()).append("`");
  return text;
}

using yaml::Range;
Range at_least(double min);                 // [min, inf)
Range above(double min);                    // (min, inf)
Range between(double min, double max);      // [min, max]
Range above_up_to(double min, double max);  // (min, max]
Range any_number();                         // finite

// "integer 1..16384", "integer >= 0".
std::string integer_type(std::int64_t min, std::int64_t max);

// ---- key builders; `help` is the reference's "meaning" column

// A key of member `member`, read by `read`, written by `emit` (emit_value when not given).
template <class T, class M>
Key<T> make_key(std::string name, M T::*member, std::string type, std::string help,
                std::function<void(yaml::MapReader&, M&)> read,
                std::function<void(YAML::Emitter&, const M&)> emit = {}) {
  Key<T> k;
  k.name = name;
  k.type = std::move(type);
  k.help = std::move(help);
  k.read = [member, read = std::move(read)](yaml::MapReader& r, T& out) { read(r, out.*member); };
  if constexpr (!std::is_enum_v<M>)
    if (!emit) emit = [](YAML::Emitter& e, const M& v) { emit_value(e, v); };
  k.emit = [member, emit = std::move(emit)](YAML::Emitter& e, const T& v) { emit(e, v.*member); };
  return k;
}

template <class T> Key<T> flag(std::string name, bool T::*member, std::string help) {
  return make_key<T, bool>(name, member, "bool", std::move(help),
                           [name](yaml::MapReader& r, bool& v) { r.get(name, v); });
}

template <class T> Key<T> text(std::string name, std::string T::*member, std::string help) {
  return make_key<T, std::string>(name, member, "text", std::move(help),
                                  [name](yaml::MapReader& r, std::string& v) { r.get(name, v); });
}

template <class T, class I>
Key<T> integer(std::string name, I T::*member, I min, I max, std::string help) {
  std::string type = integer_type(min, max);
  return make_key<T, I>(name, member, std::move(type), std::move(help),
                        [name, min, max](yaml::MapReader& r, I& v) {
                          std::int64_t value = v;
                          if (r.get_int(name, value, min, max)) v = static_cast<I>(value);
                        });
}

template <class T>
Key<T> integer_or_auto(std::string name, std::optional<std::int64_t> T::*member, std::int64_t min,
                       std::int64_t max, std::string help) {
  std::string type = integer_type(min, max) + " or `auto`";
  return make_key<T, std::optional<std::int64_t>>(
      name, member, std::move(type), std::move(help),
      [name, min, max](yaml::MapReader& r, std::optional<std::int64_t>& v) {
        r.get_auto_int(name, v, min, max);
      });
}

template <class T>
Key<T> number(std::string name, double T::*member, Range range, std::string help) {
  return make_key<T, double>(
      name, member, range.text(), std::move(help),
      [name, range](yaml::MapReader& r, double& v) { r.get_double(name, v, range); });
}

template <class T>
Key<T> number_or_auto(std::string name, std::optional<double> T::*member, Range range,
                      std::string help) {
  return make_key<T, std::optional<double>>(
      name, member, range.text() + " or `auto`", std::move(help),
      [name, range](yaml::MapReader& r, std::optional<double>& v) {
        r.get_auto_double(name, v, range);
      });
}

template <class T>
Key<T> vec3(std::string name, std::array<double, 3> T::*member, std::string help) {
  return make_key<T, std::array<double, 3>>(
      name, member, "[x, y, z]", std::move(help),
      [name](yaml::MapReader& r, std::array<double, 3>& v) { r.get_vec3(name, v); });
}

template <class T>
Key<T> vec3_or_auto(std::string name, std::optional<std::array<double, 3>> T::*member,
                    std::string help) {
  return make_key<T, std::optional<std::array<double, 3>>>(
      name, member, "[x, y, z] or `auto`", std::move(help),
      [name](yaml::MapReader& r, std::optional<std::array<double, 3>>& v) {
        r.get_auto_vec3(name, v);
      });
}

// `auto` or [min, max] with finite min < max.
using Interval = std::optional<std::array<double, 2>>;
bool read_interval(yaml::MapReader& r, const std::string& name, Interval& v);

template <class T>
Key<T> interval_or_auto(std::string name, Interval T::*member, std::string help) {
  return make_key<T, Interval>(
      name, member, "[min, max] or `auto`", std::move(help),
      [name](yaml::MapReader& r, Interval& v) { read_interval(r, name, v); });
}

// A list of distinct integers in [min, max] (kept sorted).
template <class T>
Key<T> integers(std::string name, std::vector<std::int64_t> T::*member, std::int64_t min,
                std::int64_t max, std::string help) {
  return make_key<T, std::vector<std::int64_t>>(
      name, member, "list of " + integer_type(min, max), std::move(help),
      [name, min, max](yaml::MapReader& r, std::vector<std::int64_t>& v) {
        r.get_integers(name, v, min, max);
      });
}

// A list of distinct, non-empty names.
template <class T>
Key<T> names(std::string name, std::vector<std::string> T::*member, std::string help) {
  return make_key<T, std::vector<std::string>>(
      name, member, "list of names", std::move(help),
      [name](yaml::MapReader& r, std::vector<std::string>& v) { r.get_names(name, v); });
}

// A list of [a, b] pairs of finite numbers (a transfer function's points).
template <class T>
Key<T> pairs(std::string name, std::vector<std::array<double, 2>> T::*member, std::string help) {
  return make_key<T, std::vector<std::array<double, 2>>>(
      name, member, "list of [a, b]", std::move(help),
      [name](yaml::MapReader& r, std::vector<std::array<double, 2>>& v) { r.get_pairs(name, v); });
}
template <class T, class E, std::size_t N>
Key<T> choice(std::string name, E T::*member, const EnumName<E> (&table)[N], std::string help) {
  const std::span<const EnumName<E>> names(table);
  std::string type;
  for (const EnumName<E>& e : names)
    type += (type.empty() ? "`" : " `") + std::string(e.name) + "`";
  return make_key<T, E>(
      name, member, std::move(type), std::move(help),
      [name, names](yaml::MapReader& r, E& v) { r.get_enum(name, v, names); },
      [names](YAML::Emitter& e, const E& v) { e << std::string(name_of(names, v)); });
}

// A nested map read by its own section. `fresh`: a map given replaces the default as a whole
// (keys it leaves out take M{}'s values, as a trigger's conditions are off unless given).
template <class T, class M>
Key<T> map(std::string name, M T::*member, const Section<M>& section, std::string help,
           bool fresh = false) {
  Key<T> k;
  k.name = name;
  k.type = "map";
  k.help = std::move(help);
  k.shown_default = "see `" + section.path() + "`";
  k.read = [name, member, &section, fresh](yaml::MapReader& r, T& out) {
    if (!r.has(name)) return;
    if (fresh) out.*member = M{};
    section.read(r.checker(), r.find(name), r.path(name), out.*member);
  };
  k.emit = [member, &section](YAML::Emitter& e, const T& v) { section.emit(e, v.*member); };
  return k;
}

// A list of at most `most` maps, each read by `section` from M{} (a view's iso surfaces).
template <class T, class M>
Key<T> maps(std::string name, std::vector<M> T::*member, const Section<M>& section,
            std::size_t most, std::string help) {
  Key<T> k;
  k.name = name;
  k.type = "list of maps (at most " + std::to_string(most) + ")";
  k.help = std::move(help);
  k.shown_default = "see `" + section.path() + "`";
  k.read = [name, member, &section, most](yaml::MapReader& r, T& out) {
    if (!r.has(name)) return;
    const YAML::Node list = r.find(name);
    if (!list.IsSequence() || list.size() > most) {
      r.checker().error(list, r.path(name),
                        "expected a list of at most " + std::to_string(most) + " maps; got " +
                            (list.IsSequence() ? "a list of " + std::to_string(list.size())
                                               : yaml::describe(list)));
      return;
    }
    std::vector<M> items(list.size());
    for (std::size_t i = 0; i < list.size(); ++i)
      section.read(r.checker(), list[i], r.path(name) + "[" + std::to_string(i) + "]", items[i]);
    out.*member = std::move(items);
  };
  k.emit = [member, &section](YAML::Emitter& e, const T& v) {
    e << YAML::BeginSeq;
    for (const M& m : v.*member) section.emit(e, m);
    e << YAML::EndSeq;
  };
  return k;
}

// A key of an Inner as a key of T, where `part(t)` is t's Inner (const or not).
template <class T, class Inner, class Part> Key<T> rebased(Key<Inner> k, Part part) {
  Key<T> out;
  out.name = std::move(k.name);
  out.type = std::move(k.type);
  out.help = std::move(k.help);
  out.shown_default = std::move(k.shown_default);
  out.read = [part, read = std::move(k.read)](yaml::MapReader& r, T& t) { read(r, part(t)); };
  out.emit = [part, emit = std::move(k.emit)](YAML::Emitter& e, const T& t) { emit(e, part(t)); };
  if (k.applies)
    out.applies = [part, applies = std::move(k.applies)](const T& t) { return applies(part(t)); };
  return out;
}

// A key of a member struct (a writer's own settings inside an output's) as a key of T.
template <class T, class Inner> Key<T> lifted(Inner T::*member, Key<Inner> k) {
  return rebased<T>(
      std::move(k), [member](auto& t) -> auto& { return t.*member; });
}

// The keys of a base struct as keys of T, which derives from it (a view kind's settings that
// share their keys with another kind's nested map).
template <class T, class Base> std::vector<Key<T>> from_base(std::vector<Key<Base>> keys) {
  struct AsBase {
    Base& operator()(T& t) const { return t; }
    const Base& operator()(const T& t) const { return t; }
  };
  std::vector<Key<T>> out;
  for (Key<Base>& k : keys) out.push_back(rebased<T>(std::move(k), AsBase{}));
  return out;
}

// The keys of `lists`, one after another (a kind's own keys after keys shared with others).
template <class T, class... Lists>
std::vector<Key<T>> joined(std::vector<Key<T>> first, Lists... lists) {
  (first.insert(first.end(), std::make_move_iterator(lists.begin()),
                std::make_move_iterator(lists.end())),
   ...);
  return first;
}

// Names that become parts of file names: letters, digits, '_', '-', '.' (not "." or "..").
bool is_plain_name(std::string_view name);

template <class T> std::string Section<T>::reference(const T& defaults) const {
  std::string s = "| key | type | default | meaning |\n|---|---|---|---|\n";
  for (const Key<T>& k : keys_) {
    std::string shown_value = k.shown_default;
    if (shown_value.empty()) shown_value = shown([&](YAML::Emitter& e) { k.emit(e, defaults); });
    s += "| `" + k.name + "` | " + k.type + " | " + shown_value + " | " + k.help + " |\n";
  }
  return s;
}

}  // namespace voxspan::schema
