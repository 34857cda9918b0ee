// Wrong answers built from a correct one, one class per property: the checker's own mutation test
// (tests/oracle/checker_mutation_test.cpp) holds each property, alone, to rejecting every member of
// its class, and the filtered checker's differential test (tests/oracle/filtered_checker_test.cpp)
// judges them with both checkers.
//
// Each class is defined by what the wrong answer does, and its members are the mutants for which
// the wrongness is certain, decided in exact arithmetic from quantities independent of the
// property's own test:
//  1. near_is_clip_plane: one entry of near' = s M'_3 + t M_4 with its sign flipped, where
//     C_i != 0 and the flipped entry lies on the wrong side of zero (sgn(C_i) near'_i < 0) by more
//     than the rounding an entry may carry there (gamma(3) |M4_i| in every convention, as the
//     property allows a row formed through another convention's, plus the underflow term):
//     no lambda > 0 can bring it within its bound of lambda C_i.
//  2. side_rows_unchanged: one entry of row 1, 2 or 4 moved up by one ulp (a zero becomes the
//     smallest subnormal, never -0).
//  3. far_plane_through_corner: the far plane moved beyond Q, a' = a / 2 (near' stays a multiple
//     of C, nothing is clipped), on well-conditioned cases (below).
//  4. no_clipping: the far plane moved inside Q, a' = 2 a: the far corner (or both ends of the far
//     edge) clipped, on well-conditioned cases.
//  5. infinite_edge_parallel: an infinite matrix whose far corner is at infinity, with a' = 3a / 4:
//     far' . Q = k / 4 != 0, the far plane no longer parallel to the frustum edge Q.
// Well-conditioned: a is known to 1/16 (scale_error() <= 1/16) and the entries' rounding moves
// far' . Q by at most k / 16 (gamma(3) sum_i (|a C_i| + |M4_i|) |Q_i| <= k / 16), so a far plane
// moved by k / 4 or more at Q is certainly wrong. The mutated third rows are the exact
// s (a' C - t M_4) rounded once (oracle::exact::round_to), as careful arithmetic would give them.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "oblique/oracle/problem.h"

namespace oblique::mistakes::wrong_answers {

using cases::Property;
using oracle::Problem;

struct WrongAnswer {
  Property catches = Property::near_is_clip_plane;  ///< the property whose class it belongs to
  int detail = 0;                                   ///< the entry flipped or moved
};

template <class T>
struct Mutant {
  WrongAnswer what;
  Matrix4<T> projection;
};

/// The third row s (a' C - t M_4) for a' = factor a, rounded once to T.
template <class T>
Matrix4<T> with_scale(const Problem<T>& problem, const Matrix4<T>& answer, const Vector4<T>& c,
                      const oracle::exact::Rational& factor) {
  const Convention convention = problem.convention();
  const DepthRange range = clip_depth_range(convention);
  const RowCombination nr = near_rows(convention);
  const oracle::exact::Rational a =
      factor * oracle::exact::Rational(range.z_high - range.z_low) / problem.corner_dot();
  Matrix4<T> out = answer;
  for (int i = 0; i < 4; ++i) {
    const oracle::exact::Rational entry =
        nr.m3 * (a * oracle::exact::to_rational(c(i)) -
                 nr.m4 * oracle::exact::to_rational(problem.matrix()(3, i)));
    out(2, i) = oracle::exact::round_to<T>(entry);
  }
  return out;
}

/// Whether a far plane moved by k / 4 at Q is certainly beyond every bound (see the top).
template <class T>
bool well_conditioned(const Problem<T>& problem, const Vector4<T>& c) {
  const std::optional<oracle::exact::Rational> scale = problem.scale_error();
  if (!scale || *scale > oracle::exact::Rational(1, 16)) return false;
  const Convention convention = problem.convention();
  const DepthRange range = clip_depth_range(convention);
  const oracle::exact::Rational k = range.z_high - range.z_low;
  const oracle::exact::Rational a = k / problem.corner_dot();
  oracle::exact::Rational rounding = 0;
  for (int i = 0; i < 4; ++i) {
    rounding += (oracle::exact::abs(a * oracle::exact::to_rational(c(i))) +
                 oracle::exact::abs(oracle::exact::to_rational(problem.matrix()(3, i)))) *
                oracle::exact::abs(problem.far_corner()[i]);
  }
  rounding *= oracle::tolerance::gamma(oracle::tolerance::kEntryRoundings,
                                       oracle::tolerance::precision_bits<T>());
  return rounding <= k / 16;
}

/// The members of every class built from `answer`, a correct ok answer for `problem` (whose
/// exact_status() is ok). Non-finite mutants are left out (they are rejected for being
/// non-finite, not for the property's reason).
template <class T>
std::vector<Mutant<T>> mutants(const Problem<T>& problem, const Matrix4<T>& answer,
                               const Vector4<T>& c) {
  std::vector<Mutant<T>> out;
  auto keep = [&out](Property p, int detail, const Matrix4<T>& m) {
    if (all_finite(m)) out.push_back(Mutant<T>{WrongAnswer{p, detail}, m});
  };
  const Convention convention = problem.convention();
  const RowCombination nr = near_rows(convention);
  const Matrix4<T>& m = problem.matrix();
  // 1. One entry of near' with its sign flipped: M'_3i = -M'_3i - 2 s t M4_i (s = +-1).
  const oracle::exact::Rational g = oracle::tolerance::gamma(
      oracle::tolerance::kEntryRoundings, oracle::tolerance::precision_bits<T>());
  const oracle::exact::Rational underflow =
      oracle::tolerance::kEntryRoundings * oracle::tolerance::underflow_unit<T>();
  // An entry far below the plane's norm may change by what no rasterizer sees
  // (oracle::tolerance::kInvisiblePlaneUlps): its flip is a mutant only when it is visible.
  oracle::exact::Rational largest = 0;
  for (int i = 0; i < 4; ++i)
    largest = std::max(largest, oracle::exact::abs(oracle::exact::to_rational(c(i))));
  const oracle::exact::Rational invisible =
      oracle::tolerance::kInvisiblePlaneUlps *
      oracle::tolerance::unit_roundoff(oracle::tolerance::precision_bits<T>()) * largest;
  for (int i = 0; i < 4; ++i) {
    if (c(i) == T(0)) continue;
    if (oracle::exact::abs(oracle::exact::to_rational(c(i))) * (1 - g) <= invisible) continue;
    const oracle::exact::Rational r3 = oracle::exact::to_rational(answer(2, i));
    const oracle::exact::Rational m4 = oracle::exact::to_rational(m(3, i));
    Matrix4<T> mutant = answer;
    mutant(2, i) = oracle::exact::round_to<T>(-r3 - 2 * nr.m3 * nr.m4 * m4);
    if (!std::isfinite(mutant(2, i))) continue;
    const oracle::exact::Rational flipped =
        nr.m3 * oracle::exact::to_rational(mutant(2, i)) + nr.m4 * m4;
    const oracle::exact::Rational signed_flipped =
        c(i) > T(0) ? flipped : oracle::exact::Rational(-flipped);
    // The rounding the property allows an entry in every convention (problem.h: a row formed
    // through another convention's carries g |M4_i|, a [0, 1] row too).
    const oracle::exact::Rational allowance = g * oracle::exact::abs(m4) + underflow;
    if (signed_flipped < -allowance) keep(Property::near_is_clip_plane, i, mutant);
  }
  // 2. One entry of a side row one ulp up.
  for (int row : {0, 1, 3}) {
    const int j = (row + 1) % 4;
    Matrix4<T> mutant = answer;
    const T before = mutant(row, j);
    mutant(row, j) = before == T(0) ? std::numeric_limits<T>::denorm_min()
                                    : std::nextafter(before, std::numeric_limits<T>::infinity());
    keep(Property::side_rows_unchanged, row, mutant);
  }
  if (!well_conditioned(problem, c)) return out;
  // 3. The far plane beyond Q.
  keep(Property::far_plane_through_corner, 0,
       with_scale(problem, answer, c, oracle::exact::Rational(1, 2)));
  // 4. The far plane inside Q: Q clipped.
  keep(Property::no_clipping, 0, with_scale(problem, answer, c, oracle::exact::Rational(2)));
  // 5. An infinite far plane no longer parallel to Q.
  if (problem.far_corner_at_infinity()) {
    keep(Property::infinite_edge_parallel, 0,
         with_scale(problem, answer, c, oracle::exact::Rational(3, 4)));
  }
  return out;
}

}  // namespace oblique::mistakes::wrong_answers
