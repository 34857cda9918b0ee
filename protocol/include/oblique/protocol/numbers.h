// Numbers on the wire and in reports: the scalar types' names, the one number printer (shortest
// round-trip text, or exact hex) and the number reader of the protocol.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "oblique/expected.h"
#include "oblique/util/enum_names.h"

namespace oblique::protocol {

/// The scalar type a request is computed in.
enum class Precision { float32, float64, long_double };

inline constexpr EnumName<Precision> precision_names[] = {
    {Precision::float32, "float"},
    {Precision::float64, "double"},
    {Precision::long_double, "long_double"},
};
inline constexpr auto all_precisions = values_in(precision_names);

/// "float", "double", "long_double": the one table of scalar names (the CLI's --precision values,
/// the reports' "precision" field).
constexpr std::string_view precision_name(Precision value) noexcept {
  return name_in(precision_names, value);
}
/// Inverse of precision_name(); none for an unknown name.
constexpr std::optional<Precision> parse_precision(std::string_view name) noexcept {
  return value_in(precision_names, name);
}

/// The Precision of a scalar type.
template <class T>
constexpr Precision precision_of() noexcept;
template <>
constexpr Precision precision_of<float>() noexcept {
  return Precision::float32;
}
template <>
constexpr Precision precision_of<double>() noexcept {
  return Precision::float64;
}
template <>
constexpr Precision precision_of<long double>() noexcept {
  return Precision::long_double;
}

/// precision_name(precision_of<T>()).
template <class T>
constexpr std::string_view scalar_name() noexcept {
  return precision_name(precision_of<T>());
}

enum class Notation {
  shortest,  ///< the shortest decimal that reads back as the same value of T (std::to_chars)
  hex,       ///< exact hexadecimal (printf's %a)
};

/// The number printer. Non-finite values print as "nan", "-nan", "inf", "-inf".
template <class T>
std::string format_number(T value, Notation notation = Notation::shortest);

/// A number as a request carries it, any JSON reader taking it exactly:
///   shortest: a JSON number (floats as the shortest double equal to them, so readers of doubles
///             and of floats both get the float; -0 as "-0.0", which readers of integers keep
///             negative);
///   hex:      a hex-float string ("0x1.8p+1").
/// Non-finite values are the protocol's strings "nan", "inf", "-inf" in either notation.
template <class T>
std::string json_number(T value, Notation notation = Notation::shortest);

/// The value of a number token in type T, correctly rounded from its text: a JSON number's text,
/// or a JSON string's contents marked by a leading '"' ("nan", "-nan", "inf", "-inf", "NaN",
/// "-NaN", "+inf", "Infinity", "+Infinity", "-Infinity" or a hex float). A failure, saying why,
/// for anything else, and for a finite literal that overflows T.
template <class T>
Expected<T> parse_number(const std::string& token);

}  // namespace oblique::protocol
