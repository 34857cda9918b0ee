// The request kinds of the code around the oblique matrix ("consumers"), in the JSON Lines
// protocol that `oblique verify` and `oblique check --impl` speak to a user's program. A request
// names its kind and carries its inputs; the answer carries one field of numbers:
//
//   kind            request fields                                     answer
//   view_position   projection, original [16], convention, buffer,     {"position": [x, y, z]}
//                   ndc [x, y], depth, stored
//   linear_depth    (as view_position)                                 {"depth": d}
//   world_position  (as view_position), view [16]                      {"position": [x, y, z]}
//   culling_planes  projection [16], convention                        {"planes": [[4] x 6]}
//   camera_plane    view [16], plane [4]                               {"plane": [4]}
//   mirror_view     view [16], plane [4]                               {"view": [16]}
//   portal_view     view, frame, linked [16]                           {"view": [16]}
//   corners         projection, original [16], convention              {"corners": [[x, y, z],
//   ...]}
//
// Matrices are row-major; planes keep P . x >= 0; the culling planes are left, right, bottom,
// top, near, far. docs/verify.md has the meaning of each field.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/expected.h"
#include "oblique/projection.h"
#include "oblique/protocol/numbers.h"
#include "oblique/util/enum_names.h"

namespace oblique::protocol {

enum class ConsumerKind {
  view_position,
  linear_depth,
  world_position,
  culling_planes,
  camera_plane,
  mirror_view,
  portal_view,
  corners
};

inline constexpr EnumName<ConsumerKind> consumer_kind_names[] = {
    {ConsumerKind::view_position, "view_position"},
    {ConsumerKind::linear_depth, "linear_depth"},
    {ConsumerKind::world_position, "world_position"},
    {ConsumerKind::culling_planes, "culling_planes"},
    {ConsumerKind::camera_plane, "camera_plane"},
    {ConsumerKind::mirror_view, "mirror_view"},
    {ConsumerKind::portal_view, "portal_view"},
    {ConsumerKind::corners, "corners"},
};
inline constexpr auto all_consumer_kinds = values_in(consumer_kind_names);

constexpr std::string_view consumer_kind_name(ConsumerKind kind) noexcept {
  return name_in(consumer_kind_names, kind);
}
/// Inverse of consumer_kind_name(); none for an unknown name.
constexpr std::optional<ConsumerKind> parse_consumer_kind(std::string_view name) noexcept {
  return value_in(consumer_kind_names, name);
}

/// The answer's field of a kind ("position", "depth", "planes", ...).
std::string_view consumer_answer_field(ConsumerKind kind);

/// The writer of consumer request lines: {"kind": "...", field: value, ...} in the order given,
/// numbers as json_number() prints them (they read back exactly), matrices row-major.
class ConsumerRequest {
 public:
  explicit ConsumerRequest(ConsumerKind kind);

  template <class T, int R, int C>
  ConsumerRequest& numbers(std::string_view field, const Eigen::Matrix<T, R, C>& m) {
    std::vector<std::string> tokens;
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j) tokens.push_back(json_number(m(i, j)));
    return add(field, tokens);
  }
  template <class T>
  ConsumerRequest& number(std::string_view field, T value) {
    return add(field, {json_number(value)}, false);
  }
  ConsumerRequest& text(std::string_view field, std::string_view value);

  /// The line, without its newline.
  std::string line() const { return line_ + "}"; }

 private:
  ConsumerRequest& add(std::string_view field, const std::vector<std::string>& tokens,
                       bool array = true);
  std::string line_;
};

/// The numbers of `kind`'s answer line, read as T: its field (consumer_answer_field()) holds a
/// number, an array of numbers, or an array of arrays of `group` numbers each (read in order);
/// `count` numbers in all, or any multiple of `group` (none included) when `count` is 0. Non-finite
/// spellings read as in read_answer() and a number beyond T's range as an infinity, to be judged.
/// Fails, saying why, for a line that is not such an answer (a refusal, {"status": ...} without
/// the field, included).
template <class T>
Expected<std::vector<T>> read_consumer_answer(std::string_view line, ConsumerKind kind,
                                              std::size_t count, std::size_t group);

}  // namespace oblique::protocol
