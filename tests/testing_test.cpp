// oblique::testing on a user's function: the default contract is the function's own.
#include "oblique/testing.h"

#include <gtest/gtest-spi.h>

#include "oblique/oblique.h"

namespace oblique {
namespace {

/// A GL-only engine function, pointer-style (column-major, in place): it takes no convention.
Status make_oblique_gl(double m[16], const double plane[4]) {
  const ObliqueResult<double> r =
      apply<double>(adapting::load(m, Layout::column_major),
                    Vector4<double>(plane[0], plane[1], plane[2], plane[3]), Convention::gl);
  if (r.ok()) adapting::store(r.projection, Layout::column_major, m);
  return r.status;
}

const auto gl_only =
    adapt<double>("make_oblique_gl", Layout::column_major, Convention::gl, make_oblique_gl);

// The done-when of issue 25: the default contract checks it in the convention it serves.
OBLIQUE_PROPERTY_TEST(Testing, aGlOnlyFunctionPassesTheDefaultContract, gl_only, Contract{})

TEST(Testing, aContractNamingAConventionTheFunctionDoesNotServeFails) {
  Contract zero_one;
  zero_one.conventions = {Convention::zero_one};
  EXPECT_NONFATAL_FAILURE(testing::check_properties(gl_only, zero_one),
                          "the contract names convention zero_one, which make_oblique_gl");
}

TEST(Testing, theGlFunctionJudgedInAnotherConventionFails) {
  // What the default contract spares it: the same function, claimed for every convention (a
  // matrix-shaped wrapper that ignores the convention), is caught.
  const auto claims_all =
      adapt<double>("ignores_the_convention", Layout::row_major,
                    [](const Matrix4<double>& m, const Vector4<double>& c, Convention) {
                      return apply<double>(m, c, Convention::gl);
                    });
  Contract zero_one;
  zero_one.conventions = {Convention::zero_one};
  zero_one.properties = {properties::Property::far_plane_through_corner};
  zero_one.statuses = properties::StatusContract::answers_only;  // one run, so one failure
  EXPECT_NONFATAL_FAILURE(testing::check_properties(claims_all, zero_one),
                          "violates far_plane_through_corner");
}

}  // namespace
}  // namespace oblique
