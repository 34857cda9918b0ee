// The property suite on the campaign's float engine, one test per convention: a function without
// statuses (void), so inputs without an answer and inputs undecidable in float are left out
// (oracle::not_judged()) and every other case is judged. The campaign raises the case count
// with RC_PARAMS="max_success=N seed=S"; the summary's "left out:" line counts what was left out.
#include <oblique/testing.h>

#include "float_engine.h"

namespace oblique::false_alarms {
namespace {

// Given the perspective-shape inputs only (the closed form's domain), as in the README; each
// serves one convention.
const auto gl = adapt<float>("make_oblique_gl", Layout::column_major, Convention::gl,
                             make_oblique_gl, perspective_shape_only<float>);
const auto zero_one =
    adapt<float>("make_oblique_zero_one", Layout::column_major, Convention::zero_one,
                 make_oblique_zero_one, perspective_shape_only<float>);
const auto reversed_z =
    adapt<float>("make_oblique_reversed_z", Layout::column_major, Convention::reversed_z,
                 make_oblique_reversed_z, perspective_shape_only<float>);
// A [0, 1] engine that keeps one GL code path: its row formed in GL's range and converted.
const auto zero_one_from_gl =
    adapt<float>("make_oblique_zero_one_from_gl", Layout::column_major, Convention::zero_one,
                 make_oblique_zero_one_from_gl, perspective_shape_only<float>);

// Every family of the perspective shape and every place, in the function's own convention;
// answers only (from the void adapter).
Contract perspective_shapes() {
  Contract contract;
  contract.families = {std::begin(cases::perspective_shape_families),
                       std::end(cases::perspective_shape_families)};
  return contract;
}

OBLIQUE_PROPERTY_TEST(FloatEngine, glHasEveryProperty, gl, perspective_shapes())
OBLIQUE_PROPERTY_TEST(FloatEngine, zeroOneHasEveryProperty, zero_one, perspective_shapes())
OBLIQUE_PROPERTY_TEST(FloatEngine, reversedZHasEveryProperty, reversed_z, perspective_shapes())
OBLIQUE_PROPERTY_TEST(FloatEngine, zeroOneThroughGlHasEveryProperty, zero_one_from_gl,
                      perspective_shapes())

}  // namespace
}  // namespace oblique::false_alarms
