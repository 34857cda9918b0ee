#include "oblique/protocol/json.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace oblique::protocol {

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

namespace {

using json = nlohmann::json;

/// Builds a JsonValue tree from nlohmann's SAX events (run on JsonNumbers::masked); refuses nesting
/// deeper than a request needs and more than kMaxValuesPerLine values. Numbers take their text
/// from scan_json_numbers(): SAX gives the text of floats only, reports the integer -0 as 0, and
/// refuses a number beyond double's range even when the request asks for long double.
class TreeBuilder final : public nlohmann::json_sax<json> {
 public:
  TreeBuilder(const std::vector<std::string_view>& numbers, JsonLimits limits)
      : numbers_(numbers), limits_(limits) {}

  JsonValue root;
  std::string error;

  bool null() override { return add(JsonValue{}); }
  bool boolean(bool b) override {
    JsonValue v;
    v.kind = JsonValue::Kind::boolean;
    v.text = b ? "true" : "false";
    return add(std::move(v));
  }
  bool number_integer(number_integer_t) override { return add_number(); }
  bool number_unsigned(number_unsigned_t) override { return add_number(); }
  bool number_float(number_float_t, const string_t&) override { return add_number(); }
  bool string(string_t& s) override {
    JsonValue v;
    v.kind = JsonValue::Kind::string;
    v.text = s;
    return add(std::move(v));
  }
  bool binary(binary_t&) override { return add(JsonValue{}); }
  bool start_object(std::size_t) override { return open(JsonValue::Kind::object); }
  bool key(string_t& k) override {
    if (stack_.back()->find(k) != nullptr) {
      error = "field \"" + k + "\" given twice";
      return false;
    }
    pending_key_ = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(JsonValue::Kind::array); }
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
    JsonValue v;
    v.kind = JsonValue::Kind::number;
    v.text = std::string(numbers_[next_number_++]);
    return add(std::move(v));
  }
  JsonValue* place(JsonValue v) {
    if (stack_.empty()) {
      root = std::move(v);
      return &root;
    }
    JsonValue& parent = *stack_.back();
    if (parent.kind == JsonValue::Kind::array) {
      parent.items.push_back(std::move(v));
      return &parent.items.back();
    }
    parent.members.emplace_back(pending_key_, std::move(v));
    return &parent.members.back().second;
  }
  bool count_value() {
    if (++values_ <= limits_.max_values) return true;
    error = "more than " + std::to_string(limits_.max_values) + " JSON values";
    return false;
  }
  bool add(JsonValue v) {
    if (!count_value()) return false;
    place(std::move(v));
    return true;
  }
  bool open(JsonValue::Kind kind) {
    if (!count_value()) return false;
    if (stack_.size() >= limits_.max_depth) {
      error = "JSON nested deeper than " + std::to_string(limits_.max_depth) + " levels";
      return false;
    }
    JsonValue v;
    v.kind = kind;
    stack_.push_back(place(std::move(v)));
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  std::vector<JsonValue*> stack_;
  std::string pending_key_;
  const std::vector<std::string_view>& numbers_;
  JsonLimits limits_;
  std::size_t next_number_ = 0;
  std::size_t values_ = 0;
};

}  // namespace

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const auto& [k, v] : members) {
    if (k == key) return &v;
  }
  return nullptr;
}

const char* kind_name(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::null: return "null";
    case JsonValue::Kind::boolean: return "a boolean";
    case JsonValue::Kind::number: return "a number";
    case JsonValue::Kind::string: return "a string";
    case JsonValue::Kind::array: return "an array";
    case JsonValue::Kind::object: return "an object";
  }
  return "a value";
}

Expected<JsonNumbers> scan_json_numbers(std::string_view text, std::size_t max_numbers) {
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
        return Expected<JsonNumbers>::failure("more than " + std::to_string(max_numbers) +
                                              " numbers");
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

std::string json_error_text(std::string_view what) {
  const auto pos = what.find("] ");
  return std::string(pos == std::string_view::npos ? what : what.substr(pos + 2));
}

Expected<JsonValue> parse_json(std::string_view text, JsonLimits limits) {
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    return Expected<JsonValue>::failure("a NUL byte at column " + std::to_string(nul + 1) +
                                        " (JSON is text)");
  }
  const Expected<JsonNumbers> numbers =
      scan_json_numbers(text, std::min(limits.max_values, limits.max_numbers));
  if (!numbers) return Expected<JsonValue>::failure(numbers.error());
  TreeBuilder builder(numbers->texts, limits);
  if (!json::sax_parse(numbers->masked.begin(), numbers->masked.end(), &builder,
                       json::input_format_t::json, true, false)) {
    return Expected<JsonValue>::failure(builder.error.empty() ? "not valid JSON" : builder.error);
  }
  return std::move(builder.root);
}

Expected<std::string> read_text_file(const std::string& path, std::size_t max_bytes) {
  using Result = Expected<std::string>;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Result::failure("is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) return Result::failure(std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  char block[65536];
  while (file && text.size() <= max_bytes) {
    file.read(block, sizeof block);
    text.append(block, static_cast<std::size_t>(file.gcount()));
  }
  if (file.bad()) return Result::failure(std::string("cannot read: ") + std::strerror(errno));
  if (text.size() > max_bytes)
    return Result::failure("larger than " + std::to_string(max_bytes) + " bytes");
  return text;
}

std::string json_string(std::string_view s) {
  return json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace oblique::protocol
