#include "oblique/protocol/consumer_messages.h"

#include "oblique/protocol/json.h"
#include "oblique/protocol/protocol.h"

namespace oblique::protocol {

std::string_view consumer_answer_field(ConsumerKind kind) {
  switch (kind) {
    case ConsumerKind::view_position:
    case ConsumerKind::world_position: return "position";
    case ConsumerKind::linear_depth: return "depth";
    case ConsumerKind::culling_planes: return "planes";
    case ConsumerKind::camera_plane: return "plane";
    case ConsumerKind::mirror_view:
    case ConsumerKind::portal_view: return "view";
    case ConsumerKind::corners: return "corners";
  }
  return "position";
}

ConsumerRequest::ConsumerRequest(ConsumerKind kind)
    : line_("{\"kind\": " + json_string(consumer_kind_name(kind))) {}

ConsumerRequest& ConsumerRequest::text(std::string_view field, std::string_view value) {
  line_ += ", " + json_string(field) + ": " + json_string(value);
  return *this;
}

ConsumerRequest& ConsumerRequest::add(std::string_view field,
                                      const std::vector<std::string>& tokens, bool array) {
  line_ += ", " + json_string(field) + ": ";
  if (!array) {
    line_ += tokens.front();
    return *this;
  }
  line_ += "[";
  for (std::size_t i = 0; i < tokens.size(); ++i) line_ += (i ? ", " : "") + tokens[i];
  line_ += "]";
  return *this;
}

template <class T>
Expected<std::vector<T>> read_consumer_answer(std::string_view line, ConsumerKind kind,
                                              std::size_t count, std::size_t group) {
  using Result = Expected<std::vector<T>>;
  const std::string field(consumer_answer_field(kind));
  const Expected<JsonValue> tree =
      parse_json(normalise_non_finite(line), JsonLimits{kMaxValuesPerLine, 8});
  if (!tree) return Result::failure(tree.error());
  if (!tree->is_object())
    return Result::failure(std::string("an answer must be a JSON object, not ") +
                           kind_name(tree->kind));
  const JsonValue* value = tree->find(field);
  if (!value) {
    std::string why =
        "a " + std::string(consumer_kind_name(kind)) + " answer needs \"" + field + "\"";
    if (const JsonValue* status = tree->find("status"); status && status->is_string())
      why += " (it has status \"" + status->text + "\": these requests have no refusal)";
    return Result::failure(why);
  }
  // The number tokens in order: a number, an array of numbers, or an array of `group`-arrays.
  std::vector<std::string> tokens;
  std::string error;
  auto take = [&](const JsonValue& v, const std::string& where) {
    const std::optional<std::string> token = number_token(v);
    if (!token) {
      error = where + " must be a number, not " + kind_name(v.kind);
      return false;
    }
    tokens.push_back(*token);
    return true;
  };
  if (!value->is_array()) {
    if (!take(*value, "\"" + field + "\"")) return Result::failure(error);
  } else {
    for (std::size_t i = 0; i < value->size(); ++i) {
      const JsonValue& item = (*value)[i];
      const std::string where = "\"" + field + "\"[" + std::to_string(i) + "]";
      if (!item.is_array()) {
        if (!take(item, where)) return Result::failure(error);
        continue;
      }
      if (item.size() != group)
        return Result::failure(where + " must hold " + std::to_string(group) + " numbers, not " +
                               std::to_string(item.size()));
      for (std::size_t j = 0; j < item.size(); ++j)
        if (!take(item[j], where + "[" + std::to_string(j) + "]")) return Result::failure(error);
    }
  }
  const bool fits = count ? tokens.size() == count : tokens.size() % group == 0;
  if (!fits)
    return Result::failure("\"" + field + "\" must hold " +
                           (count ? std::to_string(count) + " numbers"
                                  : "a multiple of " + std::to_string(group) + " numbers") +
                           ", not " + std::to_string(tokens.size()));
  std::vector<T> out;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const Expected<T> v = read_answer_number<T>(tokens[i]);
    if (!v)
      return Result::failure("\"" + field + "\" number " + std::to_string(i) + ": " + v.error());
    out.push_back(*v);
  }
  return out;
}

template Expected<std::vector<float>> read_consumer_answer<float>(std::string_view, ConsumerKind,
                                                                  std::size_t, std::size_t);
template Expected<std::vector<double>> read_consumer_answer<double>(std::string_view, ConsumerKind,
                                                                    std::size_t, std::size_t);
template Expected<std::vector<long double>> read_consumer_answer<long double>(std::string_view,
                                                                              ConsumerKind,
                                                                              std::size_t,
                                                                              std::size_t);

}  // namespace oblique::protocol
