// The properties an oblique projection must have, by name (their exact evaluation:
// oracle/problem.h).
#pragma once

#include <string_view>

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

constexpr std::string_view property_name(Property p) noexcept {
  switch (p) {
    case Property::near_is_clip_plane: return "near_is_clip_plane";
    case Property::side_rows_unchanged: return "side_rows_unchanged";
    case Property::far_plane_through_corner: return "far_plane_through_corner";
    case Property::no_clipping: return "no_clipping";
    case Property::infinite_edge_parallel: return "infinite_edge_parallel";
    case Property::extracted_planes_match: return "extracted_planes_match";
  }
  return "unknown";
}

}  // namespace oblique::cases
