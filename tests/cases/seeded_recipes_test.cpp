// The printed formulas against the properties: where each holds, and a concrete input where it
// breaks. The README's findings section quotes these cases.
#include "oblique/cases/seeded_recipes.h"

#include <gtest/gtest.h>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/references/frustum_planes.h"
#include "printers.h"

namespace oblique {
namespace {

using cases::Property;
using oracle::Problem;

template <class T>
std::string describe(const oracle::Verdicts& verdicts) {
  std::string out;
  for (const auto& v : verdicts.items) {
    if (v.applies && !v.holds) {
      out += std::string(cases::property_name(v.property())) + ": " + oracle::residual_text(v) +
             " vs " + oracle::bound_text(v) + "\n";
    }
  }
  return out;
}

const Vector4<double> kTilted(0.25, -0.375, -1, -3);

TEST(SeededRecipes, listing51HoldsOnStandardGlPerspective) {
  const Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::gl);
  const Problem<double> problem(m, kTilted, Convention::gl);
  const auto verdicts = problem.check(cases::listing_5_1(m, kTilted));
  EXPECT_TRUE(verdicts.all_hold()) << describe<double>(verdicts);
}

// Listing 5.1 takes the corner's signs from C in camera space. A y-flipped (Vulkan-style) matrix
// has M22 < 0, so sgn(C'_y) = -sgn(C_y): the listing picks the wrong corner and its far plane
// cuts away part of the view volume in front of C.
TEST(SeededRecipes, listing51ClipsTheViewVolumeOfAYFlippedMatrix) {
  Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::gl);
  m.row(1) *= -1;
  const Problem<double> problem(m, kTilted, Convention::gl);
  const auto listing = problem.check(cases::listing_5_1(m, kTilted));
  EXPECT_FALSE(listing[Property::no_clipping].holds);
  EXPECT_FALSE(listing[Property::far_plane_through_corner].holds);
  const auto core = problem.check(apply(m, kTilted, Convention::gl).projection);
  EXPECT_TRUE(core.all_hold()) << describe<double>(core);
}

// With no guard, a plane whose positive side misses the view volume gives C . Q < 0, a negative
// scale, and a near plane that keeps the wrong side.
TEST(SeededRecipes, listing51KeepsTheWrongSideWhenThePlaneMissesTheVolume) {
  const Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::gl);
  const Vector4<double> beyond_far(0, 0, -1, -60);  // keeps z <= -60, past the far plane at 50
  const Matrix4<double> listing = cases::listing_5_1(m, beyond_far);
  const Vector4<double> near = near_plane(listing, Convention::gl);
  EXPECT_LT(near.dot(beyond_far), 0) << "the listing's near plane points away from C";
  EXPECT_EQ(apply(m, beyond_far, Convention::gl).status, Status::plane_misses_view_volume);
}

TEST(SeededRecipes, paperEq20HoldsOnPerspectiveAndRotatedMatrices) {
  const Matrix4<double> p = frustum<double>(-0.1, 0.7, -0.2, 0.3, 1, 100, Convention::gl);
  const Problem<double> problem(p, kTilted, Convention::gl);
  EXPECT_TRUE(problem.check(cases::paper_eq_20(p, kTilted)).all_hold());
}

// Eq. 7 fixes Q'_z = 1. When C'_z < 0 (an orthographic volume reaching behind the eye, near < 0)
// the farthest corner lies on the z = -1 face, and Eq. 20's far plane clips the volume.
TEST(SeededRecipes, paperEq7PicksTheWrongFaceWhenClipSpaceCzIsNegative) {
  const Matrix4<double> m = orthographic<double>(-2, 2, -2, 2, -5, 10, Convention::gl);
  // Keeps x + y + z/8 >= 1; the origin is behind it, and C'_z = (1/8) / M33 < 0.
  const Vector4<double> c(1, 1, 0.125, -1);
  const Problem<double> problem(m, c, Convention::gl);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  const auto paper = problem.check(cases::paper_eq_20(m, c));
  EXPECT_FALSE(paper[Property::no_clipping].holds);
  const auto core = problem.check(apply(m, c, Convention::gl).projection);
  EXPECT_TRUE(core.all_hold()) << describe<double>(core);
}

TEST(SeededRecipes, zeroOneNoteHoldsOnZeroOneMatrices) {
  const Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::zero_one);
  const Problem<double> problem(m, kTilted, Convention::zero_one);
  const auto verdicts = problem.check(cases::note_zero_one(m, kTilted));
  EXPECT_TRUE(verdicts.all_hold()) << describe<double>(verdicts);
}

// The note's flip matrix has fourth row (0, 0, 1, 1): it changes w, so the flipped matrix is not
// a reversed-Z form of the same projection (row 4 changes, depth is no longer z/w in [0, 1]).
// With the fourth row (0, 0, 0, 1) the route is sound.
TEST(SeededRecipes, zeroOneNoteFlipMatrixChangesW) {
  const Matrix4<double> forward = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::zero_one);
  const Matrix4<double> reversed = cases::depth_flip<double>() * forward;
  const Problem<double> problem(reversed, kTilted, Convention::reversed_z);
  const auto printed =
      problem.check(cases::note_reversed(forward, kTilted, cases::note_flip_as_printed<double>()));
  EXPECT_FALSE(printed[Property::side_rows_unchanged].holds);
  const auto fixed =
      problem.check(cases::note_reversed(forward, kTilted, cases::depth_flip<double>()));
  EXPECT_TRUE(fixed.all_hold()) << describe<double>(fixed);
}

// The mistakes engines ship, as negative controls: the checker must catch each.
TEST(SeededRecipes, zeroOneFactorOnAGlMatrixBreaksTheNearPlane) {
  const Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::gl);
  const Problem<double> problem(m, kTilted, Convention::gl);
  const auto verdicts = problem.check(cases::note_zero_one(m, kTilted));
  EXPECT_FALSE(verdicts[Property::near_is_clip_plane].holds);
}

TEST(SeededRecipes, glFormulaOnAZeroOneMatrixBreaksTheNearPlane) {
  const Matrix4<double> m = frustum<double>(-1, 1, -0.75, 0.75, 1, 50, Convention::zero_one);
  const Problem<double> problem(m, kTilted, Convention::zero_one);
  const auto verdicts = problem.check(cases::listing_5_1(m, kTilted));
  EXPECT_FALSE(verdicts[Property::near_is_clip_plane].holds);
}

// The paper's Eq. 12 is the exact inverse of Eq. 11, and Eq. 15 is M^-1 Q'.
TEST(SeededRecipes, paperEq12IsTheInverseOfEq11) {
  const double l = -0.1, r = 0.7, b = -0.2, t = 0.3, n = 1, f = 100;
  using oracle::exact::Rational;
  const Rational L(l), R(r), B(b), T(t), N(n), F(f);
  oracle::exact::Mat m{}, inv{};
  m[0] = {2 * N / (R - L), 0, (R + L) / (R - L), 0};
  m[1] = {0, 2 * N / (T - B), (T + B) / (T - B), 0};
  m[2] = {0, 0, -(F + N) / (F - N), -2 * F * N / (F - N)};
  m[3] = {0, 0, -1, 0};
  inv[0] = {(R - L) / (2 * N), 0, 0, (R + L) / (2 * N)};
  inv[1] = {0, (T - B) / (2 * N), 0, (T + B) / (2 * N)};
  inv[2] = {0, 0, 0, -1};
  inv[3] = {0, 0, -(F - N) / (2 * F * N), (F + N) / (2 * F * N)};
  const auto exact_inverse = oracle::exact::inverse(m);
  ASSERT_TRUE(exact_inverse.has_value());
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_EQ((*exact_inverse)[i][j], inv[i][j]) << i << "," << j;
  }
  const oracle::exact::Vec q = oracle::exact::mul(inv, oracle::exact::Vec{1, -1, 1, 1});
  EXPECT_EQ(q[0], (R - L) / (2 * N) + (R + L) / (2 * N));  // Eq. 15, sgn = +1
  EXPECT_EQ(q[1], -(T - B) / (2 * N) + (T + B) / (2 * N));
  EXPECT_EQ(q[2], -1);
  EXPECT_EQ(q[3], 1 / F);
}

}  // namespace
}  // namespace oblique
