#include "oblique/protocol/protocol.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

namespace oblique::protocol {

namespace {

using json = nlohmann::json;

/// A parsed JSON value that keeps the text of its numbers.
struct Value {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  std::string text;  // a number's text, a string's contents
  std::vector<Value> items;
  std::vector<std::pair<std::string, Value>> members;
};

const char* kind_name(Value::Kind kind) {
  switch (kind) {
    case Value::Kind::null: return "null";
    case Value::Kind::boolean: return "a boolean";
    case Value::Kind::number: return "a number";
    case Value::Kind::string: return "a string";
    case Value::Kind::array: return "an array";
    case Value::Kind::object: return "an object";
  }
  return "a value";
}

bool is_json_number(std::string_view s) {
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t from = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i - from;
  };
  if (i < s.size() && s[i] == '-') ++i;
  if (i < s.size() && s[i] == '0') {
    ++i;
  } else if (digits() == 0) {
    return false;
  }
  if (i < s.size() && s[i] == '.') {
    ++i;
    if (digits() == 0) return false;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == s.size();
}

/// Builds a Value tree from nlohmann's SAX events (run on JsonNumbers::masked); refuses nesting
/// deeper than a request needs and more than kMaxValuesPerLine values. Numbers take their text
/// from scan_json_numbers(): SAX gives the text of floats only, reports the integer -0 as 0, and
/// refuses a number beyond double's range even when the request asks for long double.
class TreeBuilder final : public nlohmann::json_sax<json> {
 public:
  static constexpr std::size_t kMaxDepth = 8;

  explicit TreeBuilder(const std::vector<std::string_view>& numbers) : numbers_(numbers) {}

  Value root;
  std::string error;

  bool null() override { return add(Value{}); }
  bool boolean(bool b) override {
    Value v;
    v.kind = Value::Kind::boolean;
    v.text = b ? "true" : "false";
    return add(std::move(v));
  }
  bool number_integer(number_integer_t) override { return add_number(); }
  bool number_unsigned(number_unsigned_t) override { return add_number(); }
  bool number_float(number_float_t, const string_t&) override { return add_number(); }
  bool string(string_t& s) override {
    Value v;
    v.kind = Value::Kind::string;
    v.text = s;
    return add(std::move(v));
  }
  bool binary(binary_t&) override { return add(Value{}); }
  bool start_object(std::size_t) override { return open(Value::Kind::object); }
  bool key(string_t& k) override {
    pending_key_ = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(Value::Kind::array); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&,
                   const nlohmann::detail::exception& ex) override {
    error = json_error_text(ex.what());
    return false;
  }

 private:
  bool add_number() {
    if (next_number_ >= numbers_.size()) {  // cannot happen for text the parser accepted
      error = "internal error: number tokens out of step";
      return false;
    }
    Value v;
    v.kind = Value::Kind::number;
    v.text = std::string(numbers_[next_number_++]);
    return add(std::move(v));
  }
  Value* place(Value v) {
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    Value& parent = *stack_.back();
    if (parent.kind == Value::Kind::array) {
      parent.items.push_back(std::move(v));
      return &parent.items.back();
    }
    parent.members.emplace_back(pending_key_, std::move(v));
    return &parent.members.back().second;
  }
  bool count_value() {
    if (++values_ <= kMaxValuesPerLine) return true;
    error = "more than " + std::to_string(kMaxValuesPerLine) + " JSON values in a line";
    return false;
  }
  bool add(Value v) {
    if (!count_value()) return false;
    place(std::move(v));
    return true;
  }
  bool open(Value::Kind kind) {
    if (!count_value()) return false;
    if (stack_.size() >= kMaxDepth) {
      error = "JSON nested deeper than " + std::to_string(kMaxDepth) + " levels";
      return false;
    }
    Value v;
    v.kind = kind;
    stack_.push_back(place(std::move(v)));
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  std::vector<Value*> stack_;
  std::string pending_key_;
  const std::vector<std::string_view>& numbers_;
  std::size_t next_number_ = 0;
  std::size_t values_ = 0;
};

/// A number token: a JSON number's text, or a string (marked by a leading '"' here).
std::optional<std::string> number_token(const Value& v) {
  if (v.kind == Value::Kind::number) return v.text;
  if (v.kind == Value::Kind::string) return "\"" + v.text;
  return std::nullopt;
}

template <std::size_t N>
bool read_numbers(const Value& v, const char* field, std::array<std::string, N>& out,
                  std::string& error) {
  if (v.kind != Value::Kind::array) {
    error = std::string("\"") + field + "\" must be an array of " + std::to_string(N) +
            " numbers, not " + kind_name(v.kind);
    return false;
  }
  if (v.items.size() != N) {
    error = std::string("\"") + field + "\" must hold " + std::to_string(N) + " numbers, not " +
            std::to_string(v.items.size());
    return false;
  }
  for (std::size_t i = 0; i < N; ++i) {
    auto token = number_token(v.items[i]);
    if (!token) {
      error = std::string("\"") + field + "\"[" + std::to_string(i) + "] must be a number, not " +
              kind_name(v.items[i].kind);
      return false;
    }
    out[i] = std::move(*token);
  }
  return true;
}

std::string quoted(std::string_view s) {
  return json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

std::optional<JsonNumbers> scan_json_numbers(std::string_view text, std::size_t max_numbers,
                                             std::string* error) {
  JsonNumbers out;
  out.masked.assign(text);
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\')
        ++i;
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '-' || (ch >= '0' && ch <= '9')) {
      std::size_t end = i + 1;
      while (end < text.size() && std::strchr("0123456789.eE+-", text[end]) != nullptr) ++end;
      if (out.texts.size() == max_numbers) {
        *error = "more than " + std::to_string(max_numbers) + " numbers";
        return std::nullopt;
      }
      const std::string_view token = text.substr(i, end - i);
      out.texts.push_back(token);
      if (is_json_number(token)) {  // an invalid token is left for the parser to report
        out.masked[i] = '0';
        std::fill(out.masked.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                  out.masked.begin() + static_cast<std::ptrdiff_t>(end), ' ');
      }
      i = end - 1;
    }
  }
  return out;
}

namespace {

/// Parses one line into a Value tree, or says why it is not JSON.
std::optional<Value> parse_tree(std::string_view line, std::string& error) {
  if (const auto nul = line.find('\0'); nul != std::string_view::npos) {
    error = "a NUL byte at column " + std::to_string(nul + 1) + " (a line is JSON text)";
    return std::nullopt;
  }
  const std::optional<JsonNumbers> numbers = scan_json_numbers(line, kMaxValuesPerLine, &error);
  if (!numbers) return std::nullopt;
  TreeBuilder builder(numbers->texts);
  if (!json::sax_parse(numbers->masked.begin(), numbers->masked.end(), &builder,
                       json::input_format_t::json, true, false)) {
    error = builder.error.empty() ? "not valid JSON" : builder.error;
    return std::nullopt;
  }
  return std::move(builder.root);
}

}  // namespace

ParsedLine parse_request(std::string_view line) {
  ParsedLine out;
  const std::optional<Value> tree = parse_tree(line, out.error);
  if (!tree) return out;
  const Value& root = *tree;
  if (root.kind != Value::Kind::object) {
    out.error = std::string("a request must be a JSON object, not ") + kind_name(root.kind);
    return out;
  }
  Request request;
  bool has_projection = false, has_plane = false, has_convention = false;
  for (const auto& [key, value] : root.members) {
    const bool repeated = (key == "projection" && has_projection) ||
                          (key == "plane" && has_plane) || (key == "convention" && has_convention);
    if (repeated) {
      out.error = "field \"" + key + "\" given twice";
      return out;
    }
    if (key == "projection") {
      if (!read_numbers(value, "projection", request.projection, out.error)) return out;
      has_projection = true;
    } else if (key == "plane") {
      if (!read_numbers(value, "plane", request.plane, out.error)) return out;
      has_plane = true;
    } else if (key == "convention") {
      if (value.kind != Value::Kind::string) {
        out.error = std::string("\"convention\" must be a string, not ") + kind_name(value.kind);
        return out;
      }
      has_convention = true;
      request.convention = parse_convention(value.text);
      if (!request.convention) {
        out.error = "unknown convention \"" + value.text + "\" (gl, zero_one or reversed_z)";
        return out;
      }
    } else {
      out.error = "unknown field \"" + key + "\" (a request has projection, plane, convention)";
      return out;
    }
  }
  if (!has_projection)
    out.error = "missing field \"projection\"";
  else if (!has_plane)
    out.error = "missing field \"plane\"";
  else
    out.request = std::move(request);
  return out;
}

ParsedAnswer parse_answer(std::string_view line) {
  ParsedAnswer out;
  const std::optional<Value> tree = parse_tree(line, out.error);
  if (!tree) return out;
  if (tree->kind != Value::Kind::object) {
    out.error = std::string("an answer must be a JSON object, not ") + kind_name(tree->kind);
    return out;
  }
  bool has_status = false;
  for (const auto& [key, value] : tree->members) {
    if (key == "status") {
      if (value.kind != Value::Kind::string) {
        out.error = std::string("\"status\" must be a string, not ") + kind_name(value.kind);
        return out;
      }
      out.status = value.text;
      has_status = true;
    } else if (key == "projection") {
      std::array<std::string, 16> numbers;
      if (!read_numbers(value, "projection", numbers, out.error)) return out;
      out.projection = std::move(numbers);
    } else if (key == "message") {
      if (value.kind == Value::Kind::string) out.message = value.text;
    }
  }
  if (!has_status) {
    out.error = "missing field \"status\"";
  } else if (out.status == "ok" && !out.projection) {
    out.error = "an ok answer needs \"projection\"";
  } else {
    out.valid = true;
  }
  return out;
}

std::string request_line(const std::array<std::string, 16>& projection,
                         const std::array<std::string, 4>& plane,
                         std::optional<Convention> convention) {
  std::string line = "{\"projection\": [";
  for (std::size_t i = 0; i < projection.size(); ++i) line += (i ? ", " : "") + projection[i];
  line += "], \"plane\": [";
  for (std::size_t i = 0; i < plane.size(); ++i) line += (i ? ", " : "") + plane[i];
  line += "]";
  if (convention) line += ", \"convention\": \"" + std::string(convention_name(*convention)) + "\"";
  return line + "}";
}

template <class T>
std::string request_line(const Matrix4<T>& projection, const Vector4<T>& plane,
                         std::optional<Convention> convention, Notation notation) {
  std::array<std::string, 16> m;
  std::array<std::string, 4> c;
  for (int i = 0; i < 16; ++i) m[i] = json_number(projection(i / 4, i % 4), notation);
  for (int i = 0; i < 4; ++i) c[i] = json_number(plane(i), notation);
  return request_line(m, c, convention);
}

template <class T>
std::string ok_answer_line(const Matrix4<T>& projection) {
  std::string line = "{\"status\": \"ok\", \"projection\": [";
  for (int i = 0; i < 16; ++i) {
    if (i) line += ", ";
    line += format_number<T>(projection(i / 4, i % 4));
  }
  return line + "]}";
}

std::string refusal_line(Status status, std::string_view message) {
  return "{\"status\": " + quoted(status_code(status)) + ", \"message\": " + quoted(message) + "}";
}

#define OBLIQUE_PROTOCOL_MESSAGES(T)                                         \
  template std::string request_line<T>(const Matrix4<T>&, const Vector4<T>&, \
                                       std::optional<Convention>, Notation); \
  template std::string ok_answer_line<T>(const Matrix4<T>&);
OBLIQUE_PROTOCOL_MESSAGES(float)
OBLIQUE_PROTOCOL_MESSAGES(double)
OBLIQUE_PROTOCOL_MESSAGES(long double)
#undef OBLIQUE_PROTOCOL_MESSAGES

std::string normalise_non_finite(std::string_view line) {
  std::string out;
  out.reserve(line.size() + 16);
  bool in_string = false;
  auto starts = [&](std::size_t i, std::string_view word) {
    return line.substr(i, word.size()) == word;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (in_string) {
      out += ch;
      if (ch == '\\' && i + 1 < line.size()) {
        out += line[++i];
      } else if (ch == '"') {
        in_string = false;
      }
      continue;
    }
    if (ch == '"') {
      in_string = true;
      out += ch;
      continue;
    }
    // The bare non-finite tokens writers print: Python's NaN/Infinity, JavaScript's null, C's
    // printf("%.17g") nan/-nan/inf/-inf; longest first, so "-Infinity" is not read as "-inf".
    static constexpr std::pair<std::string_view, std::string_view> kTokens[] = {
        {"-Infinity", "\"-inf\""}, {"+Infinity", "\"inf\""}, {"Infinity", "\"inf\""},
        {"-infinity", "\"-inf\""}, {"+infinity", "\"inf\""}, {"infinity", "\"inf\""},
        {"-NaN", "\"nan\""},       {"NaN", "\"nan\""},       {"-nan", "\"nan\""},
        {"nan", "\"nan\""},        {"-inf", "\"-inf\""},     {"+inf", "\"inf\""},
        {"inf", "\"inf\""},        {"null", "\"nan\""}};
    bool replaced = false;
    for (const auto& [token, replacement] : kTokens) {
      if (starts(i, token)) {
        out += replacement;
        i += token.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) {
      out += ch;
    }
  }
  return out;
}

std::string json_error_text(std::string_view what) {
  const auto pos = what.find("] ");
  return std::string(pos == std::string_view::npos ? what : what.substr(pos + 2));
}

}  // namespace oblique::protocol
