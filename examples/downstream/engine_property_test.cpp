// The property suite on the engine's make_oblique: one adapter, one contract, one test.
#include <oblique/testing.h>

#include "engine.h"

namespace {

// OpenGL depth (the function takes no convention, so it says which it serves), the perspective
// shape its closed form reads.
const auto make_oblique =
    oblique::adapt<float>("make_oblique", oblique::Layout::column_major, oblique::Convention::gl,
                          engine::make_oblique, oblique::perspective_shape_only<float>);

// What the engine promises beyond that: the perspective shapes it builds (symmetric, off-axis,
// infinite, y-flipped, jittered), every plane; it refuses (returns false) the inputs without an
// answer, in its own words (any_refusal, from the bool). The JSON form, as a verify report
// prints it (oblique/properties/contract.h).
const oblique::Contract engine_contract = oblique::read_contract(R"({
  "families": ["perspective", "off_axis", "infinite", "y_flipped", "jittered"]
})")
                                              .value();

}  // namespace

OBLIQUE_PROPERTY_TEST(Engine, makeObliqueHasEveryProperty, make_oblique, engine_contract)
