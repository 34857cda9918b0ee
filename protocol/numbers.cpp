#include "oblique/protocol/numbers.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace oblique::protocol {

namespace {

bool is_hex_float(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
  if (s.substr(i, 2) != "0x" && s.substr(i, 2) != "0X") return false;
  i += 2;
  auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
  std::size_t digits = 0;
  while (i < s.size() && hex(s[i])) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && hex(s[i])) ++i, ++digits;
  }
  if (digits == 0 || i >= s.size() || (s[i] != 'p' && s[i] != 'P')) return false;
  ++i;
  if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
  std::size_t exponent_digits = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i, ++exponent_digits;
  return exponent_digits > 0 && i == s.size();
}

template <class T>
T string_to(const char* begin, char** end);
template <>
float string_to<float>(const char* begin, char** end) {
  return std::strtof(begin, end);
}
template <>
double string_to<double>(const char* begin, char** end) {
  return std::strtod(begin, end);
}
template <>
long double string_to<long double>(const char* begin, char** end) {
  return std::strtold(begin, end);
}

}  // namespace

template <class T>
std::string format_number(T value, Notation notation) {
  char buffer[64];
  if (notation == Notation::hex && std::isfinite(value)) {
    if constexpr (std::is_same_v<T, long double>) {
      std::snprintf(buffer, sizeof buffer, "%La", value);
    } else {
      std::snprintf(buffer, sizeof buffer, "%a", static_cast<double>(value));
    }
    return buffer;
  }
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

template <class T>
std::string json_number(T value, Notation notation) {
  if (std::isnan(value)) return "\"nan\"";
  if (std::isinf(value)) return value > 0 ? "\"inf\"" : "\"-inf\"";
  if (notation == Notation::hex) return "\"" + format_number(value, Notation::hex) + "\"";
  // -0 as "-0.0": many JSON readers (Python's, nlohmann's) read the integer -0 as +0.
  if (value == 0 && std::signbit(value)) return "-0.0";
  if constexpr (std::is_same_v<T, float>) return format_number(static_cast<double>(value));
  return format_number(value);
}

template <class T>
Expected<T> parse_number(const std::string& token) {
  const bool quoted_string = !token.empty() && token[0] == '"';
  const std::string text = quoted_string ? token.substr(1) : token;
  if (quoted_string) {
    // The protocol's spellings, and those of writers that quote non-finite numbers (Jackson,
    // Newtonsoft: "NaN", "Infinity", "-Infinity").
    if (text == "nan" || text == "-nan" || text == "NaN" || text == "-NaN")
      return std::numeric_limits<T>::quiet_NaN();
    if (text == "inf" || text == "+inf" || text == "Infinity" || text == "+Infinity")
      return std::numeric_limits<T>::infinity();
    if (text == "-inf" || text == "-Infinity") return -std::numeric_limits<T>::infinity();
    if (!is_hex_float(text)) {
      return Expected<T>::failure("the string \"" + text +
                                  "\" is not a number (use \"nan\", \"inf\", \"-inf\" or a hex "
                                  "float such as \"0x1.8p+1\")");
    }
  }
  char* end = nullptr;
  errno = 0;
  const T value = string_to<T>(text.c_str(), &end);
  if (end != text.c_str() + text.size()) {
    return Expected<T>::failure("\"" + text + "\" is not a number");
  }
  if (std::isinf(value)) {
    return Expected<T>::failure(text + " overflows the scalar type");
  }
  return value;
}

#define OBLIQUE_PROTOCOL_NUMBERS(T)                   \
  template std::string format_number<T>(T, Notation); \
  template std::string json_number<T>(T, Notation);   \
  template Expected<T> parse_number<T>(const std::string&);
OBLIQUE_PROTOCOL_NUMBERS(float)
OBLIQUE_PROTOCOL_NUMBERS(double)
OBLIQUE_PROTOCOL_NUMBERS(long double)
#undef OBLIQUE_PROTOCOL_NUMBERS

}  // namespace oblique::protocol
