// The property suite on the engine's make_oblique: one adapter, one contract, one test.
#include <oblique/testing.h>

#include "engine.h"

namespace {

const auto make_oblique =
    oblique::adapt<float>("make_oblique", oblique::Layout::column_major, engine::make_oblique,
                          oblique::perspective_shape_only<float>);

// What the engine promises: OpenGL depth, the perspective shapes it builds (symmetric,
// off-axis, infinite, y-flipped, jittered), every plane; it refuses (returns false) the inputs
// without an answer, in its own words (StatusContract::any_refusal, from the bool).
oblique::testing::Contract engine_contract() {
  using oblique::generators::Family;
  oblique::testing::Contract contract;
  contract.conventions = {oblique::Convention::gl};
  contract.families = {Family::perspective, Family::off_axis, Family::infinite, Family::y_flipped,
                       Family::jittered};
  return contract;
}

}  // namespace

OBLIQUE_PROPERTY_TEST(Engine, makeObliqueHasEveryProperty, make_oblique, engine_contract())
