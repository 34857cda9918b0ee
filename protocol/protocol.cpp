#include "oblique/protocol/protocol.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace oblique::protocol {

namespace {

template <std::size_t N>
bool read_numbers(const JsonValue& v, const char* field, std::array<std::string, N>& out,
                  std::string& error) {
  if (v.kind != JsonValue::Kind::array) {
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

}  // namespace

std::optional<std::string> number_token(const JsonValue& v) {
  if (v.kind == JsonValue::Kind::number) return v.text;
  if (v.kind == JsonValue::Kind::string) return "\"" + v.text;
  return std::nullopt;
}

template <class T>
Expected<T> read_answer_number(const std::string& token) {
  const Expected<T> value = parse_number<T>(token);
  if (value) return value;
  const Expected<long double> wide = parse_number<long double>(token);
  if (!wide) return value;
  return *wide < 0 ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::infinity();
}

Expected<Request> parse_request(std::string_view line) {
  using Result = Expected<Request>;
  std::string error;
  const Expected<JsonValue> tree = parse_json(line, JsonLimits{kMaxValuesPerLine, 8});
  if (!tree) return Result::failure(tree.error());
  const JsonValue& root = *tree;
  if (root.kind != JsonValue::Kind::object)
    return Result::failure(std::string("a request must be a JSON object, not ") +
                           kind_name(root.kind));
  Request request;
  bool has_projection = false, has_plane = false;
  for (const auto& [key, value] : root.members) {
    if (key == "projection") {
      if (!read_numbers(value, "projection", request.projection, error))
        return Result::failure(error);
      has_projection = true;
    } else if (key == "plane") {
      if (!read_numbers(value, "plane", request.plane, error)) return Result::failure(error);
      has_plane = true;
    } else if (key == "convention") {
      if (value.kind != JsonValue::Kind::string)
        return Result::failure(std::string("\"convention\" must be a string, not ") +
                               kind_name(value.kind));
      request.convention = parse_convention(value.text);
      if (!request.convention)
        return Result::failure("unknown convention \"" + value.text +
                               "\" (gl, zero_one or reversed_z)");
    } else {
      return Result::failure("unknown field \"" + key +
                             "\" (a request has projection, plane, convention)");
    }
  }
  if (!has_projection) return Result::failure("missing field \"projection\"");
  if (!has_plane) return Result::failure("missing field \"plane\"");
  return request;
}

Expected<AnswerText> parse_answer(std::string_view line) {
  using Result = Expected<AnswerText>;
  std::string error;
  const Expected<JsonValue> tree = parse_json(line, JsonLimits{kMaxValuesPerLine, 8});
  if (!tree) return Result::failure(tree.error());
  if (tree->kind != JsonValue::Kind::object)
    return Result::failure(std::string("an answer must be a JSON object, not ") +
                           kind_name(tree->kind));
  AnswerText out;
  bool has_status = false;
  for (const auto& [key, value] : tree->members) {
    if (key == "status") {
      if (value.kind != JsonValue::Kind::string)
        return Result::failure(std::string("\"status\" must be a string, not ") +
                               kind_name(value.kind));
      out.status = value.text;
      has_status = true;
    } else if (key == "projection") {
      std::array<std::string, 16> numbers;
      if (!read_numbers(value, "projection", numbers, error)) return Result::failure(error);
      out.projection = std::move(numbers);
    } else if (key == "message") {
      if (value.kind == JsonValue::Kind::string) out.message = value.text;
    }
  }
  if (!has_status) return Result::failure("missing field \"status\"");
  if (out.status == "ok" && !out.projection)
    return Result::failure("an ok answer needs \"projection\"");
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
  return "{\"status\": " + json_string(status_code(status)) +
         ", \"message\": " + json_string(message) + "}";
}

namespace {

bool is_json_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// The ok answer in its common form, {"status": "ok", "projection": [16 JSON numbers]}, read by a
/// cursor; none for any other line (read_answer_in_full() reads it, and says what is wrong).
template <class T>
std::optional<Answer<T>> plain_ok_answer(std::string_view line) {
  std::size_t i = 0;
  auto space = [&] {
    while (i < line.size() && is_json_space(line[i])) ++i;
  };
  auto literal = [&](std::string_view word) {
    space();
    if (line.substr(i, word.size()) != word) return false;
    i += word.size();
    return true;
  };
  if (!literal("{") || !literal("\"status\"") || !literal(":") || !literal("\"ok\"") ||
      !literal(",") || !literal("\"projection\"") || !literal(":") || !literal("["))
    return std::nullopt;
  Answer<T> a;
  a.status = Status::ok;
  for (int k = 0; k < 16; ++k) {
    if (k > 0 && !literal(",")) return std::nullopt;
    space();
    const std::size_t from = i;
    while (i < line.size() &&
           ((line[i] >= '0' && line[i] <= '9') || line[i] == '-' || line[i] == '+' ||
            line[i] == '.' || line[i] == 'e' || line[i] == 'E'))
      ++i;
    const std::string_view token = line.substr(from, i - from);
    if (!is_json_number(token)) return std::nullopt;
    const Expected<T> value = read_answer_number<T>(std::string(token));
    if (!value) return std::nullopt;
    a.projection(k / 4, k % 4) = *value;
  }
  if (!literal("]") || !literal("}")) return std::nullopt;
  space();
  if (i != line.size()) return std::nullopt;
  return a;
}

}  // namespace

template <class T>
Expected<Answer<T>> read_answer(std::string_view line) {
  if (std::optional<Answer<T>> plain = plain_ok_answer<T>(line)) return *std::move(plain);
  return read_answer_in_full<T>(line);
}

template <class T>
Expected<Answer<T>> read_answer_in_full(std::string_view line) {
  using Result = Expected<Answer<T>>;
  const Expected<AnswerText> parsed = parse_answer(normalise_non_finite(line));
  if (!parsed) return Result::failure(parsed.error());
  Answer<T> a;
  a.message = parsed->message;
  const std::optional<Status> status = parse_status(parsed->status);
  if (!status) return Result::failure("unknown status \"" + parsed->status + "\"");
  a.status = *status;
  if (a.status != Status::ok) return a;
  for (int i = 0; i < 16; ++i) {
    const std::string& token = (*parsed->projection)[static_cast<std::size_t>(i)];
    const Expected<T> value = read_answer_number<T>(token);
    if (!value) return Result::failure("projection[" + std::to_string(i) + "]: " + value.error());
    a.projection(i / 4, i % 4) = *value;
  }
  return a;
}

#define OBLIQUE_PROTOCOL_MESSAGES(T)                                         \
  template std::string request_line<T>(const Matrix4<T>&, const Vector4<T>&, \
                                       std::optional<Convention>, Notation); \
  template std::string ok_answer_line<T>(const Matrix4<T>&);                 \
  template Expected<Answer<T>> read_answer<T>(std::string_view);             \
  template Expected<Answer<T>> read_answer_in_full<T>(std::string_view);     \
  template Expected<T> read_answer_number<T>(const std::string&);
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

}  // namespace oblique::protocol
