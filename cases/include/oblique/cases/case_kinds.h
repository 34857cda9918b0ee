// What the generators make, by name: the families of projections, the places of planes, the
// defects of invalid inputs (the generators themselves: generators.h).
#pragma once

#include <iterator>
#include <optional>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/util/enum_names.h"

namespace oblique::cases {

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
  /// A left-handed camera's mirror pass as Direct3D-style engines build it: the left-handed
  /// frustum (M43 = +1) with clip x negated (M11 < 0), finite or infinite, leaning either way.
  /// Code that assumes M43 = -1, or takes the far corner's x sign from C, is wrong here.
  left_handed_x_flipped,
};
inline constexpr EnumName<Family> family_names[] = {
    {Family::perspective, "perspective"},
    {Family::off_axis, "off_axis"},
    {Family::infinite, "infinite"},
    {Family::orthographic, "orthographic"},
    {Family::y_flipped, "y_flipped"},
    {Family::jittered, "jittered"},
    {Family::rotated, "rotated"},
    {Family::general, "general"},
    {Family::stereo_shift, "stereo_shift"},
    {Family::x_flipped, "x_flipped"},
    {Family::xy_flipped, "xy_flipped"},
    {Family::left_handed, "left_handed"},
    {Family::left_handed_x_flipped, "left_handed_x_flipped"},
};
inline constexpr auto all_families = values_in(family_names);

/// The families whose matrices have the perspective shape (has_perspective_shape()): the inputs
/// of the closed form.
inline constexpr Family perspective_shape_families[] = {
    Family::perspective, Family::off_axis,    Family::infinite,
    Family::y_flipped,   Family::jittered,    Family::x_flipped,
    Family::xy_flipped,  Family::left_handed, Family::left_handed_x_flipped};

/// The perspective shape as engines build it, right-handed (M43 = -1): the families of the
/// engine contract (contract.h's engine_contract()) and of engine_perspective_only (adapter.h).
inline constexpr Family engine_families[] = {
    Family::perspective, Family::off_axis,  Family::infinite,  Family::y_flipped,
    Family::jittered,    Family::x_flipped, Family::xy_flipped};

constexpr std::string_view family_name(Family value) noexcept {
  return name_in(family_names, value);
}
/// Inverse of family_name(); none for an unknown name.
constexpr std::optional<Family> parse_family(std::string_view name) noexcept {
  return value_in(family_names, name);
}

/// What sets a family's matrices apart, in the words of an engine's code (for a diagnosis that
/// finds answers right on some families and wrong on others).
constexpr std::string_view family_shape(Family value) noexcept {
  switch (value) {
    case Family::perspective: return "a symmetric frustum (M11, M22 > 0, M13 = M23 = 0, M43 = -1)";
    case Family::off_axis: return "a frustum leaning off axis (M13 or M23 not 0)";
    case Family::infinite: return "the far plane at infinity (M33 = M43)";
    case Family::orthographic: return "an orthographic matrix (row 4 = (0, 0, 0, 1))";
    case Family::y_flipped: return "clip y flipped (M22 < 0, Vulkan)";
    case Family::jittered: return "a sub-pixel jitter (small M13, M23)";
    case Family::rotated: return "a rotated camera (row 4 not (0, 0, a, b))";
    case Family::general: return "any invertible matrix";
    case Family::stereo_shift: return "a stereo or lens shift (M14 or M24 not 0)";
    case Family::x_flipped: return "clip x flipped (M11 < 0, a mirror camera)";
    case Family::xy_flipped: return "both clip axes flipped (M11 < 0, M22 < 0)";
    case Family::left_handed: return "a left-handed camera (M43 = +1)";
    case Family::left_handed_x_flipped: return "a left-handed mirror camera (M43 = +1, M11 < 0)";
  }
  return "";
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
inline constexpr EnumName<Place> place_names[] = {
    {Place::typical, "typical"},       {Place::zero_in_clip_plane, "zero_in_clip_plane"},
    {Place::near_eye, "near_eye"},     {Place::near_far_corner, "near_far_corner"},
    {Place::along_axis, "along_axis"}, {Place::near_standard, "near_standard"},
    {Place::scaled, "scaled"},
};
inline constexpr auto all_places = values_in(place_names);

constexpr std::string_view place_name(Place value) noexcept {
  return name_in(place_names, value);
}
/// Inverse of place_name(); none for an unknown name.
constexpr std::optional<Place> parse_place(std::string_view name) noexcept {
  return value_in(place_names, name);
}

/// What is wrong with an invalid input.
enum class Defect { camera_in_front, misses_view_volume, singular, near_singular, non_finite };
inline constexpr EnumName<Defect> defect_names[] = {
    {Defect::camera_in_front, "camera_in_front"},
    {Defect::misses_view_volume, "misses_view_volume"},
    {Defect::singular, "singular"},
    {Defect::near_singular, "near_singular"},
    {Defect::non_finite, "non_finite"},
};
inline constexpr auto all_defects = values_in(defect_names);

constexpr std::string_view defect_name(Defect value) noexcept {
  return name_in(defect_names, value);
}
/// Inverse of defect_name(); none for an unknown name.
constexpr std::optional<Defect> parse_defect(std::string_view name) noexcept {
  return value_in(defect_names, name);
}

inline std::vector<Place> every_place() {
  return {std::begin(all_places), std::end(all_places)};
}

inline std::vector<Family> every_family() {
  return {std::begin(all_families), std::end(all_families)};
}
inline std::vector<Convention> every_convention() {
  return {std::begin(all_conventions), std::end(all_conventions)};
}

}  // namespace oblique::cases
