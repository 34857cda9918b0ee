// What the consumer judges (judge_depth.cpp, judge_culling.cpp, judge_corners.cpp,
// judge_pass_cameras.cpp) share: the error bound of a solve in T (solve_error()), exact matrix
// products, rationals as certified numbers and ranges, the kept region in exact arithmetic, and
// the words and pictures of a finding's numbers. Internal to the oracle library.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oracle/certified.h"
#include "oblique/oracle/consumers.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"

namespace oblique::oracle::consumer_judging {

using oracle::exact::Mat;
using oracle::exact::Rational;
using oracle::exact::Vec;

/// gamma(roundings) and u of T's arithmetic, or of an arithmetic whose unit roundoff is 2^-bits
/// (a GPU's, tolerance.h: kGpuLostBits).
template <class T>
Rational gamma_of(int roundings, int bits = oracle::tolerance::precision_bits<T>()) {
  return oracle::tolerance::gamma(roundings, bits);
}

template <class T>
Rational unit(int bits = oracle::tolerance::precision_bits<T>()) {
  return oracle::tolerance::unit_roundoff(bits);
}

/// The 4 x 4 matrix whose every entry is oracle::tolerance::lu_entry_bound(m): what |L||U| of m's
/// LU factors is at most, entry by entry.
Mat lu_bound(const Mat& m);

/// The product of two exact matrices.
Mat mul(const Mat& a, const Mat& b);

/// a lu_bound(m) b, given a's row sums (a 1), as the outer product it is (lu_bound(m) holds one
/// number, 32 max|m|, in every entry): 32 max|m| (a 1)(1^T b), the same rationals as the two
/// products.
Mat through_lu_bound(const Vec& a_rows, const Mat& m, const Mat& b);

/// A bound S, entry by entry, on the error of v = M^-1 b computed in T by a correct
/// implementation: |v^ - v| <= S |b| (tolerance.h, "a solve with a projection"). The larger of
/// the two ways engines compute it, each bounded from this matrix rather than the worst case:
///  - an inverse by cofactors (adjugate over determinant), then applied: each cofactor within
///    gamma(kCofactorRoundings) of the permanent of its minor of |M|, the determinant within
///    that of the permanent of |M|; then 4 roundings applying it;
///  - an elimination with partial pivoting (an inverse, or an LU solve): backward error
///    gamma(kConsumerSolveRoundings) |L^||U^|, so gamma |M^-1| G |M^-1| with G = lu_magnitudes().
/// Empty where the determinant computed by cofactors is not determined in T. `bits`: the
/// arithmetic's unit roundoff is 2^-bits (T's own by default).
template <class T>
std::optional<Mat> solve_error(const Mat& m, const Mat& inv,
                               int bits = oracle::tolerance::precision_bits<T>());

/// The largest |v_i|, and the sum of the |v_i|.
Rational max_abs(const Vec& v);
Rational sum_abs(const Vec& v);

/// A rational as a certified number: its double (mpq_get_d truncates toward zero) and, unless
/// that is the rational exactly, the step to the next double away from zero as its error.
certified::Num certified_of(const Rational& r);
/// A rational >= 0 as a certified range: its double (truncated) and the next one up.

certified::Range range_of(const Rational& r);
/// 1 - x for a range x below 1 (Undecided where x may reach 1).

certified::Range one_minus(const certified::Range& x);
/// x / y for ranges, y > 0 (Undecided where y may be 0, or the quotient overflows).

certified::Range quotient(const certified::Range& x, const certified::Range& y);

/// The point p (w = 1) in exact numbers.
template <class T>
Vec point_of(const Vector3<T>& p) {
  return {oracle::exact::to_rational(p(0)), oracle::exact::to_rational(p(1)),
          oracle::exact::to_rational(p(2)), Rational(1)};
}

/// A rational as the nearest double, shortest digits.

std::string text(const Rational& x);
/// The first n entries of v, as text().
std::string text(const Vec& v, int n = 4);
/// The point v (w = 1) in doubles, for a picture.
Eigen::Vector3d approx_point(const Vec& v);

/// |a| / b as a double ratio; 0 for 0 / 0, infinity for x / 0.

double ratio_of(const Rational& a, const Rational& b);

/// view_axis_sign() in exact arithmetic, from the inverse of the original projection: the sign
/// of the z of its view volume's centre. Given `error` (solve_error()'s S for the original), 0
/// where a solve in T can give the other sign: the centre's z or w within its error of 0, or no
/// S (the inverse not determined in T).
int axis_sign(const Mat& original_inverse, Convention convention,
              const std::optional<std::optional<Mat>>& error = std::nullopt);

/// A matrix in T, exactly, and its exact inverse (empty: singular).
struct Inverse {
  Mat m;
  std::optional<Mat> inv;
};

// What the judges ask of one matrix, or of one case, exactly: each computed once on a thread for
// the last few asked (recent.h), since a round asks them of M, M' and the view from several
// judges.

/// The matrix exactly, and its inverse.
template <class T>
std::shared_ptr<const Inverse> inverse_of(const Matrix4<T>& matrix);

/// solve_error() of the matrix, in an arithmetic of `bits` (empty: singular, or its determinant
/// not determined in T).
template <class T>
std::shared_ptr<const std::optional<Mat>> solve_error_of(
    const Matrix4<T>& matrix, int bits = oracle::tolerance::precision_bits<T>());

/// The matrix oracle's exact analysis of M and C (problem.h).
template <class T>
std::shared_ptr<const Problem<T>> problem_of(const Matrix4<T>& m, const Vector4<T>& c,
                                             Convention convention);

/// solve_error()'s bound as ranges that hold it, entry by entry: what the judges' certified paths
/// compare with, and the exact bound's existence (the determinant determined in T).
struct SolveBound {
  bool exists = false;  ///< solve_error() is not empty
  bool ranged = false;  ///< `range` holds it (false: beyond double's range; only the exact one)
  std::array<std::array<certified::Range, 4>, 4> range{};
};

/// solve_error() of the matrix as ranges: computed in certified intervals (solve_error() is
/// written once over its number type) from the exact inverse rounded outward, and exactly where
/// they cannot decide (a pivot order, the determinant). `exists` is exactly whether solve_error()
/// gives a bound. Kept for the last few matrices (recent.h).
template <class T>
std::shared_ptr<const SolveBound> solve_bound_of(const Matrix4<T>& matrix,
                                                 int bits = oracle::tolerance::precision_bits<T>());

/// axis_sign() of the original projection with its solve's bound in an arithmetic of `bits`
/// (solve_bound_of(): its ranges where they decide, the exact bound where they cannot).
/// Precondition: `original` is invertible.
template <class T>
int axis_sign_of(const Matrix4<T>& original, Convention convention, int bits);

/// The kept region's vertices, exactly (polytope::clip_volume on M's exact corners); empty when
/// M is singular or a corner of its volume is behind the eye (w < 0: the volume wraps through
/// infinity, and has no kept region to judge by).
template <class T>
std::shared_ptr<const std::optional<std::vector<Vec>>> exact_kept_region(const Matrix4<T>& m,
                                                                         const Vector4<T>& c,
                                                                         Convention convention);

/// Why a judge that needs the kept region has none (exact_kept_region() is empty).
inline constexpr const char* kNotProper =
    "a corner of the original view volume is behind the eye in exact arithmetic";

}  // namespace oblique::oracle::consumer_judging
