// What the generators make, by name: the families of projections, the places of planes, the
// defects of invalid inputs (the generators themselves: generators.h).
#pragma once

#include <iterator>
#include <optional>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"

namespace oblique::generators {

enum class Family {
  perspective,
  off_axis,
  infinite,
  orthographic,
  y_flipped,
  jittered,
  rotated,
  general,
  /// A stereo eye or a lens shift: the perspective shape (finite or infinite) times a camera
  /// translation T(tx, ty, 0), so M14 = M11 tx and/or M24 = M22 ty are not zero (row-major:
  /// M14 is m(0, 3)). Engines whose portal math ignores the shift clip a sliver of the far
  /// corner; the core takes these to the general method (not the perspective shape).
  stereo_shift,
  /// A mirror camera: the symmetric frustum with clip x negated (row 1 of M, so M11 < 0), as
  /// engines make a mirror pass's camera by negating M11. The perspective shape, so
  /// C'_x = C_x / M11 has the sign opposite to C_x's: code that takes the far corner's x sign
  /// from C (or from |M11|) is wrong only here.
  x_flipped,
  /// Both axes flipped (M11 < 0 and M22 < 0): a mirror camera's x flip on a y-flipped (Vulkan)
  /// projection.
  xy_flipped,
  /// A left-handed camera looking down +z (Direct3D's LH projections): a frustum leaning either
  /// way, finite or infinite, with camera z negated, so M43 = +1 and M13, M23, M33 change sign.
  /// The perspective shape; code that assumes M43 = -1 (Listing 5.1's Q) is wrong only here.
  left_handed,
};
inline constexpr Family all_families[] = {
    Family::perspective,  Family::off_axis,  Family::infinite,   Family::orthographic,
    Family::y_flipped,    Family::jittered,  Family::rotated,    Family::general,
    Family::stereo_shift, Family::x_flipped, Family::xy_flipped, Family::left_handed};

/// The families whose matrices have the perspective shape (has_perspective_shape()): the inputs
/// of the closed form.
inline constexpr Family perspective_shape_families[] = {
    Family::perspective, Family::off_axis,  Family::infinite,   Family::y_flipped,
    Family::jittered,    Family::x_flipped, Family::xy_flipped, Family::left_handed};

/// The perspective shape as engines build it, right-handed (M43 = -1): the families of the
/// engine contract (contract.h's engine_contract()) and of engine_perspective_only (adapter.h).
inline constexpr Family engine_families[] = {
    Family::perspective, Family::off_axis,  Family::infinite,  Family::y_flipped,
    Family::jittered,    Family::x_flipped, Family::xy_flipped};

constexpr std::string_view family_name(Family f) noexcept {
  switch (f) {
    case Family::perspective: return "perspective";
    case Family::off_axis: return "off_axis";
    case Family::infinite: return "infinite";
    case Family::orthographic: return "orthographic";
    case Family::y_flipped: return "y_flipped";
    case Family::jittered: return "jittered";
    case Family::rotated: return "rotated";
    case Family::general: return "general";
    case Family::stereo_shift: return "stereo_shift";
    case Family::x_flipped: return "x_flipped";
    case Family::xy_flipped: return "xy_flipped";
    case Family::left_handed: return "left_handed";
  }
  return "unknown";
}

inline std::optional<Family> parse_family(std::string_view name) noexcept {
  for (Family f : all_families) {
    if (family_name(f) == name) return f;
  }
  return std::nullopt;
}

/// Where a valid plane sits: the hard places the suite must cover on every run.
enum class Place {
  typical,             ///< through a point inside the view volume
  zero_in_clip_plane,  ///< C'_x or C'_y exactly zero (sgn = 0), or rounding-close for general M
  near_eye,            ///< |C_w| tiny against |N|: the plane almost through the eye
  near_far_corner,     ///< C . Q tiny against |C| |Q|: the plane almost through the far corner
  along_axis,          ///< the normal almost perpendicular to the view axis
  near_standard,       ///< almost the standard near plane of M
  scaled,              ///< a typical plane scaled by 1e-8 .. 1e8
};
inline constexpr Place all_places[] = {
    Place::typical,    Place::zero_in_clip_plane, Place::near_eye, Place::near_far_corner,
    Place::along_axis, Place::near_standard,      Place::scaled};

constexpr std::string_view place_name(Place p) noexcept {
  switch (p) {
    case Place::typical: return "typical";
    case Place::zero_in_clip_plane: return "zero_in_clip_plane";
    case Place::near_eye: return "near_eye";
    case Place::near_far_corner: return "near_far_corner";
    case Place::along_axis: return "along_axis";
    case Place::near_standard: return "near_standard";
    case Place::scaled: return "scaled";
  }
  return "unknown";
}

/// What is wrong with an invalid input.
enum class Defect { camera_in_front, misses_view_volume, singular, near_singular, non_finite };
inline constexpr Defect all_defects[] = {Defect::camera_in_front, Defect::misses_view_volume,
                                         Defect::singular, Defect::near_singular,
                                         Defect::non_finite};

constexpr std::string_view defect_name(Defect d) noexcept {
  switch (d) {
    case Defect::camera_in_front: return "camera_in_front";
    case Defect::misses_view_volume: return "misses_view_volume";
    case Defect::singular: return "singular";
    case Defect::near_singular: return "near_singular";
    case Defect::non_finite: return "non_finite";
  }
  return "unknown";
}

inline std::vector<Place> every_place() {
  return {std::begin(all_places), std::end(all_places)};
}

inline std::optional<Place> parse_place(std::string_view name) noexcept {
  for (Place p : all_places) {
    if (place_name(p) == name) return p;
  }
  return std::nullopt;
}

inline std::optional<Defect> parse_defect(std::string_view name) noexcept {
  for (Defect d : all_defects) {
    if (defect_name(d) == name) return d;
  }
  return std::nullopt;
}

inline std::vector<Family> every_family() {
  return {std::begin(all_families), std::end(all_families)};
}
inline std::vector<Convention> every_convention() {
  return {std::begin(all_conventions), std::end(all_conventions)};
}

}  // namespace oblique::generators
