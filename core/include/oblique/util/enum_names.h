// Names of enumerators, written once per enumeration: a table of (value, name) pairs that the
// command line, the protocol, the reports and the scene files all read and print through, so
// that a value cannot gain a name in one place and miss it in another.
//
//   inline constexpr EnumName<Status> status_names[] = {{Status::ok, "ok"}, ...};
//   name_in(status_names, s)        "ok"; "unknown" for a value the table lacks
//   value_in(status_names, "ok")    Status::ok; std::nullopt for a name the table lacks
//   values_in(status_names)         every value, in the table's order (a std::array)
//   names_in(status_names)          every name, in the table's order
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace oblique {

/// One enumerator and the name it is printed and parsed by.
template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

/// The name of `value` in `table`, or "unknown".
template <class E, std::size_t N>
constexpr std::string_view name_in(const EnumName<E> (&table)[N], E value) noexcept {
  for (const EnumName<E>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "unknown";
}

/// The value named `name` in `table`, or none.
template <class E, std::size_t N>
constexpr std::optional<E> value_in(const EnumName<E> (&table)[N], std::string_view name) noexcept {
  for (const EnumName<E>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

/// Every value of `table`, in its order.
template <class E, std::size_t N>
constexpr std::array<E, N> values_in(const EnumName<E> (&table)[N]) noexcept {
  std::array<E, N> values{};
  for (std::size_t i = 0; i < N; ++i) values[i] = table[i].value;
  return values;
}

/// The names of `table`, in its order (for a list of known names: protocol/names.h).
template <class E, std::size_t N>
std::vector<std::string> names_in(const EnumName<E> (&table)[N]) {
  std::vector<std::string> out;
  for (const EnumName<E>& entry : table) out.emplace_back(entry.name);
  return out;
}

}  // namespace oblique
