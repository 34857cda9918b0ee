// The property suite on the campaign's float engine, one test per convention: a function without
// statuses (void), so inputs without an answer and inputs undecidable in float are left out
// (properties::not_judged()) and every other case is judged. The campaign raises the case count
// with RC_PARAMS="max_success=N seed=S"; the summary's "left out:" line counts what was left out.
#include <oblique/testing.h>

#include "float_engine.h"

namespace oblique::false_alarms {
namespace {

// Given the perspective-shape inputs only (the closed form's domain), as in the README.
const auto gl = adapt<float>("make_oblique_gl", Layout::column_major, make_oblique_gl,
                             perspective_shape_only<float>);
const auto zero_one = adapt<float>("make_oblique_zero_one", Layout::column_major,
                                   make_oblique_zero_one, perspective_shape_only<float>);
const auto reversed_z = adapt<float>("make_oblique_reversed_z", Layout::column_major,
                                     make_oblique_reversed_z, perspective_shape_only<float>);

// Every family of the perspective shape and every place; answers only (from the void adapter).
testing::Contract only(Convention convention) {
  testing::Contract contract;
  contract.conventions = {convention};
  contract.families = {std::begin(generators::perspective_shape_families),
                       std::end(generators::perspective_shape_families)};
  return contract;
}

OBLIQUE_PROPERTY_TEST(FloatEngine, glHasEveryProperty, gl, only(Convention::gl))
OBLIQUE_PROPERTY_TEST(FloatEngine, zeroOneHasEveryProperty, zero_one, only(Convention::zero_one))
OBLIQUE_PROPERTY_TEST(FloatEngine, reversedZHasEveryProperty, reversed_z,
                      only(Convention::reversed_z))

}  // namespace
}  // namespace oblique::false_alarms
