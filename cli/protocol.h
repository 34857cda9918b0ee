// The JSON Lines protocol of `oblique apply` (and of every implementation `oblique verify` drives):
//   request: {"projection": [16 numbers, row-major], "plane": [4 numbers], "convention": "gl"}
//   answer:  {"status": "ok", "projection": [16 numbers]}  or  {"status": "<code>", "message":
//   "..."}
// A number may be a JSON number or a string: "nan", "inf", "-inf" or a hex float ("0x1.8p+1").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "oblique/depth_convention.h"
#include "oblique/oblique.h"
#include "oblique/status.h"

namespace oblique::protocol {

/// The scalar type a request is computed in.
enum class Precision { float32, float64, long_double };

std::string_view precision_name(Precision p) noexcept;  ///< "float", "double", "long_double"
std::optional<Precision> parse_precision(std::string_view name) noexcept;

/// A request as read, its numbers kept as text so each precision converts them exactly once.
struct Request {
  std::array<std::string, 16> projection;  ///< row-major
  std::array<std::string, 4> plane;
  std::optional<Convention> convention;
};

/// A request, or why the line is not one (with the JSON parser's line and column when relevant).
struct ParsedLine {
  std::optional<Request> request;
  std::string error;
};

ParsedLine parse_request(std::string_view line);

/// An answer line as read back (by tests, and by `oblique verify` from other implementations).
/// Unknown fields are ignored; `valid` is false (with `error`) when the line is not an answer.
struct ParsedAnswer {
  bool valid = false;
  std::string status;
  std::optional<std::array<std::string, 16>> projection;  ///< number tokens, for parse_number()
  std::string message;
  std::string error;
};

ParsedAnswer parse_answer(std::string_view line);

/// The value of a number token in type T, correctly rounded from its text: a JSON number,
/// or "nan", "inf", "-inf", or a hex float. Empty (with `error` set) for anything else, and for a
/// finite literal that overflows T.
template <class T>
std::optional<T> parse_number(const std::string& text, std::string* error);

/// Shortest text that reads back as the same value of T (std::to_chars).
template <class T>
std::string format_number(T value);

/// Options of one `oblique apply` run.
struct ApplyOptions {
  Convention convention = Convention::gl;  ///< used when a request names none
  Method method = Method::automatic;
  Precision precision = Precision::float64;
};

/// One answer line (no trailing newline) and the status it carries.
struct Answer {
  Status status = Status::invalid_input;
  std::string line;
};

/// Parses one request line, runs the core, and formats the answer.
Answer answer_request(std::string_view line, const ApplyOptions& options);

}  // namespace oblique::protocol
