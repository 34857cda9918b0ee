// Depth conventions: how clip-space z is bounded, and which rows of M make the near and far planes.
#pragma once

#include <optional>
#include <string_view>

#include "oblique/util/enum_names.h"

namespace oblique {

/// The clip-space depth range a projection matrix targets.
enum class Convention {
  gl,          ///< OpenGL: -w <= z <= w, near plane at z = -w
  zero_one,    ///< Direct3D, Vulkan, Metal, WebGPU: 0 <= z <= w, near plane at z = 0
  reversed_z,  ///< [0, 1] depth with near and far swapped: z = w at the near plane, z = 0 at the
               ///< far plane
};

inline constexpr EnumName<Convention> convention_names[] = {
    {Convention::gl, "gl"},
    {Convention::zero_one, "zero_one"},
    {Convention::reversed_z, "reversed_z"},
};
inline constexpr auto all_conventions = values_in(convention_names);

constexpr std::string_view convention_name(Convention value) noexcept {
  return name_in(convention_names, value);
}
/// Inverse of convention_name(); none for an unknown name.
constexpr std::optional<Convention> parse_convention(std::string_view name) noexcept {
  return value_in(convention_names, name);
}

/// A clip plane as a combination of rows: plane = m3 * M_3 + m4 * M_4 (rows counted from 1).
struct RowCombination {
  int m3;
  int m4;
};

/// The camera-space near plane of M is near_rows(c).m3 * M_3 + near_rows(c).m4 * M_4
/// (paper Table 1 for gl; Gribb-Hartmann for [0, 1]; swapped for reversed Z).
constexpr RowCombination near_rows(Convention c) noexcept {
  switch (c) {
    case Convention::gl: return {1, 1};           // z >= -w
    case Convention::zero_one: return {1, 0};     // z >= 0
    case Convention::reversed_z: return {-1, 1};  // z <= w
  }
  return {0, 0};
}

/// The camera-space far plane, as for near_rows().
constexpr RowCombination far_rows(Convention c) noexcept {
  switch (c) {
    case Convention::gl: return {-1, 1};         // z <= w
    case Convention::zero_one: return {-1, 1};   // z <= w
    case Convention::reversed_z: return {1, 0};  // z >= 0
  }
  return {0, 0};
}

/// Clip-space z of the view volume's corners at w = 1: z_low <= z <= z_high.
struct DepthRange {
  int z_low;
  int z_high;
};

constexpr DepthRange clip_depth_range(Convention c) noexcept {
  return c == Convention::gl ? DepthRange{-1, 1} : DepthRange{0, 1};
}

}  // namespace oblique
