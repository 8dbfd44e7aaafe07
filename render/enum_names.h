// render/enum_names.h - one {name, value} table per enum, beside the enum: the names a config
// file, a log line and a stats record use, written once. Standard library only.
//
//   enum class ShadeMode { opaque, translucent, refractive };
//   inline constexpr EnumName<ShadeMode> kShadeModeNames[] = {
//       {"opaque", ShadeMode::opaque}, {"translucent", ShadeMode::translucent}, ...};
//   name_of(kShadeModeNames, mode)             // "opaque"
//   value_of(kShadeModeNames, "translucent")   // ShadeMode::translucent, or nullopt
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace voxspan {

template <class E> struct EnumName {
  std::string_view name;
  E value;
};

// "?" for a value the table lacks (only a cast from an integer makes one).
template <class E> constexpr std::string_view name_of(std::span<const EnumName<E>> table, E value) {
  for (const EnumName<E>& e : table)
    if (e.value == value) return e.name;
  return "?";
}

template <class E>
constexpr std::optional<E> value_of(std::span<const EnumName<E>> table, std::string_view name) {
  for (const EnumName<E>& e : table)
    if (e.name == name) return e.value;
  return std::nullopt;
}

// The names joined by `separator`, in table order: "opaque, translucent, refractive".
template <class E>
std::string names_of(std::span<const EnumName<E>> table, std::string_view separator = ", ") {
  std::string text;
  for (const EnumName<E>& e : table) {
    if (!text.empty()) text += separator;
    text += e.name;
  }
  return text;
}

// The same on the tables as they are declared (arrays), where E cannot be deduced for a span.
template <class E, std::size_t N>
constexpr std::string_view name_of(const EnumName<E> (&table)[N], E value) {
  return name_of(std::span<const EnumName<E>>(table), value);
}
template <class E, std::size_t N>
constexpr std::optional<E> value_of(const EnumName<E> (&table)[N], std::string_view name) {
  return value_of(std::span<const EnumName<E>>(table), name);
}
template <class E, std::size_t N>
std::string names_of(const EnumName<E> (&table)[N], std::string_view separator = ", ") {
  return names_of(std::span<const EnumName<E>>(table), separator);
}

}  // namespace voxspan
