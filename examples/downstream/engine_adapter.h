// The engine's make_oblique as the property suite sees it, and what the engine promises: one
// adapter and one contract for engine_property_test.cpp and engine_raster_test.cpp.
#pragma once

#include <oblique/testing.h>

#include "engine.h"

namespace engine_checks {

// OpenGL depth (the function takes no convention, so it says which it serves), the perspective
// shape its closed form reads.
inline const auto make_oblique =
    oblique::adapt<float>("make_oblique", oblique::Layout::column_major, oblique::Convention::gl,
                          engine::make_oblique, oblique::perspective_shape_only<float>);

// What the engine promises beyond that: the perspective shapes it builds (symmetric, off-axis,
// infinite, y-flipped, jittered), every plane; it refuses (returns false) the inputs without an
// answer, in its own words (any_refusal, from the bool). The JSON form, as a verify report
// prints it (oblique/cases/contract.h).
inline const oblique::Contract contract = oblique::read_contract(R"({
  "families": ["perspective", "off_axis", "infinite", "y_flipped", "jittered"]
})")
                                              .value();

}  // namespace engine_checks
