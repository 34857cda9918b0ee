#include "protocol.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

namespace oblique::protocol {

std::string_view precision_name(Precision p) noexcept {
  switch (p) {
    case Precision::float32: return "float";
    case Precision::float64: return "double";
    case Precision::long_double: return "long_double";
  }
  return "unknown";
}

std::optional<Precision> parse_precision(std::string_view name) noexcept {
  for (Precision p : {Precision::float32, Precision::float64, Precision::long_double}) {
    if (precision_name(p) == name) return p;
  }
  return std::nullopt;
}

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

/// The texts of the JSON numbers in `line`, in order. Valid only for text the JSON parser accepts:
/// outside strings, a number is the only token that starts with '-' or a digit.
std::vector<std::string> number_texts(std::string_view line) {
  std::vector<std::string> out;
  bool in_string = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (in_string) {
      if (ch == '\\')
        ++i;
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '-' || (ch >= '0' && ch <= '9')) {
      std::size_t end = i + 1;
      while (end < line.size() && std::strchr("0123456789.eE+-", line[end]) != nullptr) ++end;
      out.emplace_back(line.substr(i, end - i));
      i = end - 1;
    }
  }
  return out;
}

/// Builds a Value tree from nlohmann's SAX events; refuses nesting deeper than a request needs.
/// Numbers take their text from number_texts(): SAX gives the text of floats only, and reports
/// the integer -0 as 0.
class TreeBuilder final : public nlohmann::json_sax<json> {
 public:
  static constexpr std::size_t kMaxDepth = 8;

  explicit TreeBuilder(std::string_view line) : numbers_(number_texts(line)) {}

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
    error = ex.what();
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix: the rest names line and column.
    if (const auto pos = error.find("] "); pos != std::string::npos) error.erase(0, pos + 2);
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
    v.text = numbers_[next_number_++];
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
  bool add(Value v) {
    place(std::move(v));
    return true;
  }
  bool open(Value::Kind kind) {
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
  std::vector<std::string> numbers_;
  std::size_t next_number_ = 0;
};

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

Answer refusal(Status status, std::string_view message) {
  Answer a;
  a.status = status;
  a.line =
      "{\"status\": " + quoted(status_code(status)) + ", \"message\": " + quoted(message) + "}";
  return a;
}

template <class T>
Answer run(const Request& request, const ApplyOptions& options) {
  Matrix4<T> m;
  Vector4<T> c;
  std::string error;
  for (int i = 0; i < 16; ++i) {
    auto value = parse_number<T>(request.projection[i], &error);
    if (!value)
      return refusal(Status::invalid_input, "projection[" + std::to_string(i) + "]: " + error);
    m(i / 4, i % 4) = *value;
  }
  for (int i = 0; i < 4; ++i) {
    auto value = parse_number<T>(request.plane[i], &error);
    if (!value) return refusal(Status::invalid_input, "plane[" + std::to_string(i) + "]: " + error);
    c(i) = *value;
  }
  const Convention convention = request.convention.value_or(options.convention);
  const ObliqueResult<T> result = apply<T>(m, c, convention, options.method);
  if (!result.ok()) return refusal(result.status, result.message());
  Answer a;
  a.status = Status::ok;
  a.line = "{\"status\": \"ok\", \"projection\": [";
  for (int i = 0; i < 16; ++i) {
    if (i) a.line += ", ";
    a.line += format_number<T>(result.projection(i / 4, i % 4));
  }
  a.line += "]}";
  return a;
}

}  // namespace

template <class T>
std::optional<T> parse_number(const std::string& token, std::string* error) {
  const bool quoted_string = !token.empty() && token[0] == '"';
  const std::string text = quoted_string ? token.substr(1) : token;
  if (quoted_string) {
    if (text == "nan") return std::numeric_limits<T>::quiet_NaN();
    if (text == "inf") return std::numeric_limits<T>::infinity();
    if (text == "-inf") return -std::numeric_limits<T>::infinity();
    if (!is_hex_float(text)) {
      *error =
          "the string \"" + text +
          "\" is not a number (use \"nan\", \"inf\", \"-inf\" or a hex float such as \"0x1.8p+1\")";
      return std::nullopt;
    }
  }
  char* end = nullptr;
  errno = 0;
  const T value = string_to<T>(text.c_str(), &end);
  if (end != text.c_str() + text.size()) {
    *error = "\"" + text + "\" is not a number";
    return std::nullopt;
  }
  if (std::isinf(value)) {
    *error = text + " overflows the scalar type";
    return std::nullopt;
  }
  return value;
}

template <class T>
std::string format_number(T value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

template std::optional<float> parse_number<float>(const std::string&, std::string*);
template std::optional<double> parse_number<double>(const std::string&, std::string*);
template std::optional<long double> parse_number<long double>(const std::string&, std::string*);
template std::string format_number<float>(float);
template std::string format_number<double>(double);
template std::string format_number<long double>(long double);

namespace {

/// Parses one line into a Value tree, or says why it is not JSON.
std::optional<Value> parse_tree(std::string_view line, std::string& error) {
  TreeBuilder builder(line);
  if (!json::sax_parse(line.begin(), line.end(), &builder, json::input_format_t::json, true,
                       false)) {
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
  bool has_projection = false, has_plane = false;
  for (const auto& [key, value] : root.members) {
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

Answer answer_request(std::string_view line, const ApplyOptions& options) {
  ParsedLine parsed = parse_request(line);
  if (!parsed.request)
    return refusal(Status::invalid_input, "not a valid request: " + parsed.error);
  switch (options.precision) {
    case Precision::float32: return run<float>(*parsed.request, options);
    case Precision::float64: return run<double>(*parsed.request, options);
    case Precision::long_double: return run<long double>(*parsed.request, options);
  }
  return refusal(Status::invalid_input, "unknown precision");
}

}  // namespace oblique::protocol
