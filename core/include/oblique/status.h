// The outcome of every oblique computation: a status code and a human message.
#pragma once

#include <optional>
#include <string_view>

#include "oblique/util/enum_names.h"

namespace oblique {

/// What happened to one request. Inputs that have no answer get a code, never undefined behaviour.
enum class Status {
  ok,             ///< the modified projection is in the result
  invalid_input,  ///< a NaN or infinity in the input, or a method asked for where it does not apply
  singular_projection,       ///< the projection matrix is singular (or numerically singular for the
                             ///< general solve)
  camera_not_behind_plane,   ///< C_w >= 0: the eye is not strictly on the plane's negative side
  plane_misses_view_volume,  ///< no point of the original view volume lies strictly on C's positive
                             ///< side
  out_of_range,              ///< the answer (or the far corner Q) exceeds the scalar type's range
};

inline constexpr EnumName<Status> status_codes[] = {
    {Status::ok, "ok"},
    {Status::invalid_input, "invalid_input"},
    {Status::singular_projection, "singular_projection"},
    {Status::camera_not_behind_plane, "camera_not_behind_plane"},
    {Status::plane_misses_view_volume, "plane_misses_view_volume"},
    {Status::out_of_range, "out_of_range"},
};
inline constexpr auto all_statuses = values_in(status_codes);

/// The code used on the command line and in the JSON protocol, e.g. "camera_not_behind_plane".
constexpr std::string_view status_code(Status value) noexcept {
  return name_in(status_codes, value);
}
/// Inverse of status_code(); none for an unknown name.
constexpr std::optional<Status> parse_status(std::string_view name) noexcept {
  return value_in(status_codes, name);
}

/// One sentence a person can act on.
constexpr std::string_view status_message(Status status) noexcept {
  switch (status) {
    case Status::ok: return "the near plane of the projection is now the clip plane";
    case Status::invalid_input:
      return "the input is not a finite 4x4 projection and a finite plane";
    case Status::singular_projection:
      return "the projection matrix is singular, so it has no view volume to clip";
    case Status::camera_not_behind_plane:
      return "the camera is not strictly behind the clip plane (C_w >= 0); flip the plane or skip "
             "the pass";
    case Status::plane_misses_view_volume:
      return "no point of the view volume lies in front of the clip plane; the pass can be skipped";
    case Status::out_of_range:
      return "the oblique matrix exceeds the range of the scalar type (the plane passes too close "
             "to the far corner)";
  }
  return "unknown status";
}

}  // namespace oblique
