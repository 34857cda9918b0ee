// The accurate method's exact path (exact_cramer.h): big-integer arithmetic, and the oblique
// answer by Cramer's rule against the rational oracle (oracle::Problem) on stiff inputs.
#include "oblique/detail/accurate/exact_cramer.h"
#include "oblique/detail/accurate/accurate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "printers.h"

namespace oblique {
namespace {

using detail::BigInt;

BigInt big(std::uint64_t magnitude, bool negative = false, int shift = 0) {
  return BigInt::from_magnitude(magnitude, negative, shift);
}

/// The value of x as a double (x exact in double), from its top bits.
double value(const BigInt& x) {
  if (x.sign() == 0) return 0;
  int exponent = 0;
  const eft::Pair<double> top = x.top_bits<double>(exponent);
  return x.sign() * std::ldexp(top.hi + top.lo, exponent);
}

TEST(BigInt, addsSubtractsAndMultipliesAcrossLimbs) {
  const std::uint64_t all_ones = ~std::uint64_t(0);
  EXPECT_EQ((big(all_ones) + big(1)).bit_length(), 65);
  EXPECT_EQ((big(1, false, 64) - big(1)).bit_length(), 64);
  EXPECT_EQ((big(5) - big(5)).sign(), 0);
  EXPECT_EQ((big(3) - big(5)).sign(), -1);
  EXPECT_EQ(value(big(3) - big(5)), -2.0);
  EXPECT_EQ(value(big(7, true) * big(6, true)), 42.0);
  EXPECT_EQ(value(big(7, true) * big(6)), -42.0);
  // (2^64 - 1)^2 = 2^128 - 2^65 + 1: 128 bits, and its top 128 bits are all of it.
  const BigInt square = big(all_ones) * big(all_ones);
  EXPECT_EQ(square.bit_length(), 128);
  EXPECT_EQ((square - big(1, false, 128) + big(1, false, 65)).sign(), 1);
  EXPECT_EQ(value(square - big(1, false, 128) + big(1, false, 65)), 1.0);
  // Shifts far beyond a limb, and a sum whose terms are 2^3000 apart.
  const BigInt far = big(3, false, 3000) + big(1);
  EXPECT_EQ(far.bit_length(), 3002);
  EXPECT_EQ((far - big(3, false, 3000)).sign(), 1);
  EXPECT_EQ(value(far - big(3, false, 3000)), 1.0);
}

TEST(BigInt, determinantOfIntegerMatrices) {
  detail::BigMatrix4 identity;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) identity[i][j] = big(i == j ? 1 : 0);
  EXPECT_EQ(value(detail::determinant(identity)), 1.0);
  // A permutation (one swap) and a scaled row.
  detail::BigMatrix4 m = identity;
  std::swap(m[0], m[1]);
  m[2][2] = big(5, true);
  EXPECT_EQ(value(detail::determinant(m)), 5.0);
  // Rows 1 and 4 equal: singular.
  detail::BigMatrix4 singular = identity;
  singular[3] = singular[0];
  EXPECT_EQ(detail::determinant(singular).sign(), 0);
}

template <class T>
class ExactCramer : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(ExactCramer, Scalars);

/// A general (not perspective-shape) matrix: a frustum times a rotation about y.
template <class T>
Matrix4<T> rotated_frustum(Convention convention) {
  Matrix4<T> rotation = Matrix4<T>::Identity();
  rotation(0, 0) = T(0.8), rotation(0, 2) = T(0.6), rotation(2, 0) = T(-0.6);
  rotation(2, 2) = T(0.8);
  return Matrix4<T>(frustum<T>(T(-1), T(1.25), T(-0.75), T(0.5), T(0.5), T(40), convention) *
                    rotation);
}

/// The planes that take the exact path: components spanning more binades than the working type
/// holds, components the scaling of C loses, C' components exactly zero.
template <class T>
std::vector<Vector4<T>> stiff_planes() {
  const T tiny = std::numeric_limits<T>::min();
  const T huge = std::numeric_limits<T>::max() / T(4);
  const T far = std::ldexp(T(1), std::numeric_limits<T>::max_exponent / 2);
  return {Vector4<T>(T(0.25), far, T(-1), T(-3)), Vector4<T>(tiny, T(0), T(-1), -huge),
          Vector4<T>(T(-1.5), T(0.125) / far, T(-1), T(-0.75)),
          Vector4<T>(T(0), T(0), T(-1), T(-1)), Vector4<T>(T(0.5), T(-0.25), T(-1), -far)};
}

TYPED_TEST(ExactCramer, agreesWithTheRationalOracleOnStiffPlanes) {
  using T = TypeParam;
  using W = typename detail::AccurateWorkingType<T>::type;
  int compared = 0;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = rotated_frustum<T>(convention);
    for (const Vector4<T>& c : stiff_planes<T>()) {
      const std::string what = std::string(convention_name(convention)) + " C = (" +
                               std::to_string(double(c(0))) + ", " + std::to_string(double(c(1))) +
                               ", " + std::to_string(double(c(2))) + ", " +
                               std::to_string(double(c(3))) + ")";
      const oracle::Problem<T> problem(m, c, convention);
      const auto exact = detail::exact_oblique<T, W>(m.template cast<W>(),
                                                     Vector4<W>(c.template cast<W>()), convention);
      using Outcome = typename detail::ExactOblique<T, W>::Outcome;
      if (problem.exact_status() == Status::plane_misses_view_volume) {
        EXPECT_EQ(exact.outcome, Outcome::plane_misses_view_volume) << what;
        continue;
      }
      ASSERT_EQ(problem.exact_status(), Status::ok) << what;
      ASSERT_EQ(exact.outcome, Outcome::answered) << what;
      if (!all_finite(exact.row3)) continue;  // beyond the range: apply() answers out_of_range
      Matrix4<T> answer = m;
      answer.row(2) = exact.row3.transpose();
      EXPECT_LE(problem.ulps_from_exact(answer), 1.0) << what;
      ++compared;
      const auto result = apply<T>(m, c, convention, Method::accurate);
      const auto acceptable = problem.acceptable_statuses();
      EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), result.status), acceptable.end())
          << what << ": " << status_code(result.status);
      if (result.ok()) {
        EXPECT_LE(problem.ulps_from_exact(result.projection), oracle::tolerance::kAccurateUlps)
            << what;
      }
    }
  }
  EXPECT_GE(compared, 6);  // most of the planes have a finite answer in every convention
}

TYPED_TEST(ExactCramer, reportsSingularMatricesAndPlanesMissingTheVolume) {
  using T = TypeParam;
  using W = typename detail::AccurateWorkingType<T>::type;
  Matrix4<W> singular = rotated_frustum<T>(Convention::gl).template cast<W>();
  singular.row(3) = singular.row(0);
  using Outcome = typename detail::ExactOblique<T, W>::Outcome;
  EXPECT_EQ(
      (detail::exact_oblique<T, W>(singular, Vector4<W>(0, 0, -1, -1), Convention::gl).outcome),
      Outcome::singular);
  // Beyond the far plane (f = 40): no point of the volume in front of C.
  const Matrix4<W> m = frustum<W>(W(-1), W(1), W(-1), W(1), W(1), W(40), Convention::gl);
  EXPECT_EQ((detail::exact_oblique<T, W>(m, Vector4<W>(0, 0, -1, -60), Convention::gl).outcome),
            Outcome::plane_misses_view_volume);
}

// The closed form and the general method hand stiff planes to the accurate method.
TYPED_TEST(ExactCramer, stiffPlanesAreHandedToTheAccurateMethod) {
  using T = TypeParam;
  const T far = std::ldexp(T(1), std::numeric_limits<T>::max_exponent / 2);
  const Matrix4<T> m = rotated_frustum<T>(Convention::zero_one);
  const auto general =
      apply<T>(m, Vector4<T>(T(0.25), far, T(-1), T(-3)), Convention::zero_one, Method::general);
  EXPECT_EQ(general.method, Method::accurate);
  // C = (DBL_MIN, 0, 0, -DBL_MAX) on an infinite frustum: C . Q = C_x Q_x, lost to the scaling.
  const Matrix4<T> inf = infinite_frustum<T>(T(-1), T(1), T(-1), T(1), T(1), Convention::gl);
  const Vector4<T> c(std::numeric_limits<T>::min(), T(0), T(0), -std::numeric_limits<T>::max());
  const oracle::Problem<T> problem(inf, c, Convention::gl);
  const auto closed = apply<T>(inf, c, Convention::gl, Method::closed_form);
  EXPECT_EQ(closed.method, Method::accurate);
  const auto acceptable = problem.acceptable_statuses();
  EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), closed.status), acceptable.end())
      << status_code(closed.status);
}

}  // namespace
}  // namespace oblique
