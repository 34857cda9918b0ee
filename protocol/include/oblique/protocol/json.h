// The project's one strict JSON reader, for requests, answers, contracts and scenes: a tree that
// keeps each number's text (so every scalar type converts it exactly once, and a long double
// beyond double's range or the integer -0 survive), refuses repeated fields, a NUL byte, nesting
// and sizes beyond its limits, and says where the text stops being JSON.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <optional>

#include "oblique/expected.h"

namespace oblique::protocol {

struct JsonValue {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  std::string text;  ///< a number's text, a string's contents, "true" or "false"
  std::vector<JsonValue> items;
  std::vector<std::pair<std::string, JsonValue>> members;  ///< in the text's order, keys unique

  /// The member named `key`, or nullptr.
  const JsonValue* find(std::string_view key) const;
  /// The member named `key`; precondition: find(key) is not nullptr.
  const JsonValue& at(std::string_view key) const { return *find(key); }
  bool is(Kind k) const { return kind == k; }
  bool is_object() const { return kind == Kind::object; }
  bool is_array() const { return kind == Kind::array; }
  bool is_number() const { return kind == Kind::number; }
  bool is_string() const { return kind == Kind::string; }
  bool is_boolean() const { return kind == Kind::boolean; }
  /// Items of an array, members of an object, 0 otherwise.
  std::size_t size() const { return kind == Kind::object ? members.size() : items.size(); }
  /// Item i of an array; precondition: i < size().
  const JsonValue& operator[](std::size_t i) const { return items[i]; }
};

/// "a number", "an array", ...: for messages.
const char* kind_name(JsonValue::Kind kind);

struct JsonLimits {
  std::size_t max_values = 256;  ///< numbers, strings, arrays, ... in the whole text
  std::size_t max_depth = 8;
  std::size_t max_numbers = static_cast<std::size_t>(-1);  ///< numbers alone (max_values too)
};

/// The tree of `text`, or why it is not JSON within `limits` (with the line and column).
Expected<JsonValue> parse_json(std::string_view text, JsonLimits limits = {});

/// The JSON number tokens of a text, for readers that need a number's text rather than the double
/// a JSON parser makes of it (a long double beyond double's range, the integer -0, an overflow
/// named by its field): `masked` is the text with each token that is a valid JSON number replaced
/// by "0" and spaces (same length, so a parser's line and column still hold, and no number can
/// overflow it), and `texts` holds every number-like token's text, in order, viewing `text`.
/// Outside strings, a number is the only JSON token that starts with '-' or a digit.
struct JsonNumbers {
  std::string masked;
  std::vector<std::string_view> texts;
};

/// Whether `s` is one JSON number, all of it: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?.
bool is_json_number(std::string_view s);

/// A failure when the text holds more than `max_numbers` number tokens.
Expected<JsonNumbers> scan_json_numbers(std::string_view text, std::size_t max_numbers);

/// A JSON parser's error message for a person: nlohmann's "[json.exception.parse_error.101] "
/// prefix dropped, so what remains names the line and column.
std::string json_error_text(std::string_view what);

/// The text of a file a person names (a scene, a contract, a report), read in blocks and never
/// more than `max_bytes` + 1 of it, so a device that never ends (/dev/zero) is refused, not read.
/// Fails with "is a directory", "cannot open: ...", "cannot read: ..." or "larger than N bytes".
Expected<std::string> read_text_file(const std::string& path, std::size_t max_bytes);

/// `s` as a JSON string literal (invalid UTF-8 replaced).
std::string json_string(std::string_view s);

}  // namespace oblique::protocol
