// The JSON Lines protocol of `oblique apply` (and of every implementation `oblique verify` drives),
// both directions:
//   request: {"projection": [16 numbers, row-major], "plane": [4 numbers], "convention": "gl"}
//   answer:  {"status": "ok", "projection": [16 numbers]}  or  {"status": "<code>", "message":
//   "..."}
// A number may be a JSON number or a string: "nan", "inf", "-inf" or a hex float ("0x1.8p+1").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/projection.h"
#include "oblique/protocol/json.h"
#include "oblique/protocol/numbers.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique::protocol {

/// A request as read, its numbers kept as text so each precision converts them exactly once.
struct Request {
  std::array<std::string, 16> projection;  ///< row-major number tokens, for parse_number()
  std::array<std::string, 4> plane;
  std::optional<Convention> convention;
};

/// The request of a line, or why the line is not one (with the JSON parser's line and column
/// when relevant). Refuses (with a message) what is not JSON, what is not a request, unknown and
/// repeated fields, anything after a NUL byte, nesting deeper than 8 levels and more JSON values
/// than kMaxValuesPerLine, so the memory a line takes stays a small multiple of its length.
Expected<Request> parse_request(std::string_view line);

/// The most JSON values (numbers, strings, arrays, ...) a request or answer line may hold: a
/// request holds 24.
inline constexpr std::size_t kMaxValuesPerLine = 256;

/// The one request writer: a request line (no trailing newline) from JSON number tokens
/// (json_number()), the convention omitted when empty.
std::string request_line(const std::array<std::string, 16>& projection,
                         const std::array<std::string, 4>& plane,
                         std::optional<Convention> convention);

/// A request line for M (row-major) and C, numbers in the given notation (json_number()).
template <class T>
std::string request_line(const Matrix4<T>& projection, const Vector4<T>& plane,
                         std::optional<Convention> convention,
                         Notation notation = Notation::shortest);

/// An answer line as read back, its numbers kept as text (read_answer() converts them).
struct AnswerText {
  std::string status;
  std::optional<std::array<std::string, 16>> projection;  ///< number tokens, for parse_number()
  std::string message;
};

/// The answer of a line, or why the line is not one. Unknown fields are ignored.
Expected<AnswerText> parse_answer(std::string_view line);

/// The one reader of another program's answers (oblique verify, oblique check --impl): the line
/// made strict JSON first (normalise_non_finite()), then parsed; an entry beyond T's range is an
/// infinity to judge, not a protocol error. Fails, saying why, on a line that is no answer. The
/// common line, {"status": "ok", "projection": [16 JSON numbers]} in that order (any JSON
/// whitespace), is read without building its JSON tree (plain_ok_answer()); the same answer as
/// read_answer_in_full() gives, which reads every other line.
template <class T>
Expected<Answer<T>> read_answer(std::string_view line);

/// read_answer() through the JSON tree alone: the reference its shortcut is tested against.
template <class T>
Expected<Answer<T>> read_answer_in_full(std::string_view line);

/// The token of a JSON value for parse_number(): a number's text, or a string's contents marked
/// by a leading '"'; empty for any other value.
std::optional<std::string> number_token(const JsonValue& value);

/// A number of another program's answer in T: parse_number(), except that a finite number beyond
/// T's range is an infinity of its sign, to judge rather than a protocol error.
template <class T>
Expected<T> read_answer_number(const std::string& token);

/// The answer line of an ok result: each entry the shortest text that reads back as it in T.
template <class T>
std::string ok_answer_line(const Matrix4<T>& projection);

/// The answer line of a refusal.
std::string refusal_line(Status status, std::string_view message);

/// The JSON Lines answer of an implementation, made strict JSON first: the bare tokens NaN, -NaN,
/// Infinity, -Infinity (Python's json module, .NET), nan, -nan, inf, -inf (C's printf) and null
/// (JavaScript's JSON.stringify(NaN)) outside strings become the protocol's "nan", "inf", "-inf",
/// so each reads as a non-finite number wherever a number is expected.
std::string normalise_non_finite(std::string_view line);

}  // namespace oblique::protocol
