// The properties an oblique projection must have, by name (their exact evaluation:
// oracle/problem.h).
#pragma once

#include <optional>
#include <string_view>

#include "oblique/util/enum_names.h"

namespace oblique::cases {

enum class Property {
  near_is_clip_plane,        ///< 1. near(M') = lambda C with lambda > 0
  side_rows_unchanged,       ///< 2. rows 1, 2, 4 of M' are those of M (values: -0 == +0)
  far_plane_through_corner,  ///< 3. far(M') . Q = 0, Q the corner farthest on C's positive side
  no_clipping,               ///< 4. far(M') . p >= 0 for every p of the view volume with C . p >= 0
  infinite_edge_parallel,    ///< 5. infinite M: Q is a direction and far(M') is parallel to it
  extracted_planes_match,    ///< the suite's cross-check: frustum_planes(M') sides equal M's
};

inline constexpr Property all_properties[] = {
    Property::near_is_clip_plane, Property::side_rows_unchanged, Property::far_plane_through_corner,
    Property::no_clipping, Property::infinite_edge_parallel};

inline constexpr EnumName<Property> property_names[] = {
    {Property::near_is_clip_plane, "near_is_clip_plane"},
    {Property::side_rows_unchanged, "side_rows_unchanged"},
    {Property::far_plane_through_corner, "far_plane_through_corner"},
    {Property::no_clipping, "no_clipping"},
    {Property::infinite_edge_parallel, "infinite_edge_parallel"},
    {Property::extracted_planes_match, "extracted_planes_match"}};

constexpr std::string_view property_name(Property p) noexcept {
  return name_in(property_names, p);
}
/// Inverse of property_name(); none for an unknown name.
constexpr std::optional<Property> parse_property(std::string_view name) noexcept {
  return value_in(property_names, name);
}

}  // namespace oblique::cases
