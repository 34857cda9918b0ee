// The closed form's expected answers kept as data (tests/data/closed_form_bits.txt): one request
// and what apply() answered to it per line, every number exact. make_closed_form_bits writes
// the file (once, from a version whose answers were checked); closed_form_bits_test reads it and
// asks apply() again, so that a change to the closed form that moves a bit shows.
//
// A line:  SCALAR CONVENTION METHOD M(16, row by row) C(4) STATUS RAN ROW3(4) Q(4) DETAIL
// with SCALAR float|double|long_double, CONVENTION and METHOD and RAN by their names
// (convention_name(), method_name()), STATUS by status_code(), numbers in C99 hexadecimal
// ("%La", which every finite value and infinity round-trip through) or nan:BITS (the value's bits
// in hexadecimal, sign and payload kept), ROW3 the answer's row 3 (the input's where the answer is
// a refusal), and DETAIL the rest of the line, "-" for an empty one.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

namespace oblique::test {

template <class T>
constexpr const char* scalar_token() {
  if constexpr (std::is_same_v<T, float>) return "float";
  if constexpr (std::is_same_v<T, double>) return "double";
  return "long_double";
}

/// The bytes that hold a T's value (x87 long double: 10, not the padding).
template <class T>
constexpr std::size_t value_bytes = std::numeric_limits<T>::digits == 64 ? 10 : sizeof(T);

/// x exactly, as one token without spaces.
template <class T>
std::string bits_token(T x) {
  char buffer[64];
  if (std::isnan(x)) {
    unsigned char bytes[sizeof(T)] = {};
    std::memcpy(bytes, &x, value_bytes<T>);
    std::string out = "nan:";
    for (std::size_t i = value_bytes<T>; i-- > 0;) {  // most significant byte first
      std::snprintf(buffer, sizeof buffer, "%02x", unsigned(bytes[i]));
      out += buffer;
    }
    return out;
  }
  std::snprintf(buffer, sizeof buffer, "%La", static_cast<long double>(x));
  return buffer;
}

/// The T a bits_token() wrote; nullopt for a token it cannot have written.
template <class T>
std::optional<T> parse_bits_token(const std::string& token) {
  if (token.rfind("nan:", 0) == 0) {
    const std::string hex = token.substr(4);
    if (hex.size() != 2 * value_bytes<T>) return std::nullopt;
    unsigned char bytes[sizeof(T)] = {};
    for (std::size_t i = 0; i < value_bytes<T>; ++i) {
      const std::string pair = hex.substr(2 * (value_bytes<T> - 1 - i), 2);
      char* end = nullptr;
      const unsigned long byte = std::strtoul(pair.c_str(), &end, 16);
      if (end != pair.c_str() + 2) return std::nullopt;
      bytes[i] = static_cast<unsigned char>(byte);
    }
    T x;
    std::memcpy(&x, bytes, sizeof(T));
    if (!std::isnan(x)) return std::nullopt;
    return x;
  }
  char* end = nullptr;
  const long double wide = std::strtold(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size()) return std::nullopt;
  const T x = static_cast<T>(wide);
  if (!(static_cast<long double>(x) == wide || std::isinf(wide))) return std::nullopt;  // not a T
  return x;
}

}  // namespace oblique::test
