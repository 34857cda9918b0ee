// EquilibratedSolver (equilibrated_solver.h) on its own claims, against exact rational answers:
// its solves, their refinement and backward error, the transposed solve's signs and error bound,
// its refusals of zero rows and columns, and its reciprocal condition number.
#include "oblique/detail/equilibrated_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "oblique/oracle/exact.h"

namespace oblique {
namespace {

using detail::EquilibratedSolver;

template <class T>
class Solver : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(Solver, Scalars);

template <class T>
Matrix4<T> integer_matrix() {
  Matrix4<T> m;
  m << T(4), T(-2), T(1), T(3),  //
      T(1), T(5), T(-1), T(2),   //
      T(-3), T(1), T(6), T(-1),  //
      T(2), T(-1), T(2), T(7);
  return m;
}

template <class T>
oracle::exact::Vec exact_solution(const Matrix4<T>& m, const Vector4<T>& b, bool transposed) {
  oracle::exact::Mat inverse = *oracle::exact::inverse(oracle::exact::to_rational(m));
  if (transposed) inverse = oracle::exact::transpose(inverse);
  return oracle::exact::mul(inverse, oracle::exact::to_rational(b));
}

// A system with an integer answer is solved to within an ulp or two of it.
TYPED_TEST(Solver, solvesAKnownSystem) {
  using T = TypeParam;
  const Matrix4<T> m = integer_matrix<T>();
  const Vector4<T> x(T(1), T(-2), T(3), T(-4));
  const Vector4<T> b = m * x;  // small integers: exact
  const EquilibratedSolver<T> solver(m);
  ASSERT_EQ(solver.failure(), EquilibratedSolver<T>::Failure::none);
  T backward_error = T(-1);
  const Vector4<T> solved = solver.solve(b, &backward_error);
  for (int i = 0; i < 4; ++i)
    EXPECT_LE(oracle::exact::ulp_distance(solved(i), oracle::exact::Rational(int(x(i)))), 2.0);
  EXPECT_GE(backward_error, T(0));
  EXPECT_LE(backward_error, std::numeric_limits<T>::epsilon());
}

// Entries of 1e-6 beside ones of 1 to 13: the refined solve is close to componentwise backward
// stable, and its reported backward error is the Oettli-Prager one of what it returns.
TYPED_TEST(Solver, refinementGivesSmallComponentwiseBackwardError) {
  using T = TypeParam;
  Matrix4<T> m;
  m << T(1e-6), T(13), T(2), T(1),  //
      T(3), T(1e-6), T(1), T(7),    //
      T(1), T(2), T(1e-6), T(5),    //
      T(11), T(1), T(4), T(1e-6);
  const Vector4<T> b(T(1), T(-1e-6), T(0.5), T(3));
  const EquilibratedSolver<T> solver(m);
  T reported = T(-1);
  const Vector4<T> x = solver.solve(b, &reported);
  const Vector4<T> r = detail::accurate_residual(m, x, b, false);
  const T measured = detail::componentwise_backward_error(m, x, b, r, false);
  EXPECT_EQ(reported, measured);
  EXPECT_LE(reported, T(2) * std::numeric_limits<T>::epsilon());
  const oracle::exact::Vec expected = exact_solution(m, b, false);
  for (int i = 0; i < 4; ++i) EXPECT_LE(oracle::exact::ulp_distance(x(i), expected[i]), 64.0) << i;
}

// accurate_residual is b - A x as if summed in twice the precision and rounded once (Dot2): within
// u |r| + gamma_4^2 (|b| + |A| |x|) of the exact residual r (Ogita, Rump and Oishi, Prop. 4.5;
// taken as eps |r| + (5 eps)^2 (...)), though b = fl(A x) makes r cancel completely.
TYPED_TEST(Solver, accurateResidualAsInTwicePrecision) {
  using T = TypeParam;
  const Matrix4<T> m = integer_matrix<T>() / T(3);
  const Vector4<T> x(T(1) / T(7), T(-2) / T(9), T(3) / T(11), T(0.1));
  const Vector4<T> b = m * x;
  const oracle::exact::Rational eps = oracle::exact::to_rational(std::numeric_limits<T>::epsilon());
  for (bool transpose : {false, true}) {
    const Vector4<T> r = detail::accurate_residual(m, x, b, transpose);
    const oracle::exact::Mat mx = transpose
                                      ? oracle::exact::transpose(oracle::exact::to_rational(m))
                                      : oracle::exact::to_rational(m);
    const oracle::exact::Vec ax = oracle::exact::mul(mx, oracle::exact::to_rational(x));
    const oracle::exact::Vec size = oracle::exact::mul(
        oracle::exact::abs(mx), oracle::exact::abs(oracle::exact::to_rational(x)));
    for (int i = 0; i < 4; ++i) {
      const oracle::exact::Rational expected = oracle::exact::to_rational(b(i)) - ax[i];
      const oracle::exact::Rational bound =
          eps * oracle::exact::abs(expected) +
          25 * eps * eps * (oracle::exact::abs(oracle::exact::to_rational(b(i))) + size[i]);
      EXPECT_LE(oracle::exact::abs(oracle::exact::to_rational(r(i)) - expected), bound)
          << i << (transpose ? " transposed" : "");
      // Far below the plain residual's rounding: exact or nearly so at this size.
      EXPECT_LE(oracle::exact::ulp_distance(r(i), expected), 2.0) << i;
    }
  }
}

// With every row's largest entry in [1/2, 1) the row scaling R is the identity, so
// solve_transposed_unscaled(c) is M^-T c itself: within transposed_error_bound of the exact
// answer, and within an ulp or so once transposed_correction_unscaled is added.
TYPED_TEST(Solver, transposedSolveWithinItsBound) {
  using T = TypeParam;
  Matrix4<T> m;
  m << T(0.5), T(0.25), T(-0.125), T(0.375),  //
      T(0.75), T(-0.5), T(0.25), T(0.125),    //
      T(-0.25), T(0.625), T(0.5), T(-0.5),    //
      T(0.125), T(0.5), T(-0.75), T(0.25);
  const Vector4<T> c(T(0.1), T(-0.7), T(0.3), T(-0.9));
  const EquilibratedSolver<T> solver(m);
  const Vector4<T> y = solver.solve_transposed_unscaled(c);
  const Vector4<T> bound = solver.transposed_error_bound(y);
  const oracle::exact::Vec expected = exact_solution(m, c, true);
  const Vector4<T> correction = solver.transposed_correction_unscaled(c, y);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LE(oracle::exact::abs(oracle::exact::to_rational(y(i)) - expected[i]),
              oracle::exact::to_rational(bound(i)));
    // The bound is at least 16 eps |y_i|: (|Mt^-T| |Mt^T|) has a diagonal of at least 1.
    EXPECT_GE(bound(i), T(16) * std::numeric_limits<T>::epsilon() * std::abs(y(i)));
    EXPECT_LE(oracle::exact::ulp_distance(T(y(i) + correction(i)), expected[i]), 1.0) << i;
  }
}

// Rows scaled by powers of two far apart: equilibration gives back the unscaled matrix's
// conditioning, and R^-1 M^-T c has the signs of M^-T c.
TYPED_TEST(Solver, equilibrationRemovesBadScaling) {
  using T = TypeParam;
  const int e = std::numeric_limits<T>::max_exponent / 2;
  Matrix4<T> m = integer_matrix<T>();
  m.row(0) *= std::ldexp(T(1), -e);
  m.row(2) *= std::ldexp(T(1), e);
  const EquilibratedSolver<T> plain(integer_matrix<T>());
  const EquilibratedSolver<T> scaled(m);
  EXPECT_EQ(scaled.rcond(), plain.rcond());
  EXPECT_GT(scaled.rcond(), T(0.01));
  const Vector4<T> c(T(1), T(-1), T(0.5), T(2));
  const Vector4<T> y = scaled.solve_transposed_unscaled(c);
  const oracle::exact::Vec expected = exact_solution(m, c, true);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(y(i) > T(0), oracle::exact::sign(expected[i]) > 0) << i;
    EXPECT_EQ(y(i) < T(0), oracle::exact::sign(expected[i]) < 0) << i;
  }
}

TYPED_TEST(Solver, refusesZeroRowsAndColumns) {
  using T = TypeParam;
  Matrix4<T> zero_row = integer_matrix<T>();
  zero_row.row(2).setZero();
  EXPECT_EQ(EquilibratedSolver<T>(zero_row).failure(), EquilibratedSolver<T>::Failure::zero_row);
  Matrix4<T> zero_column = integer_matrix<T>();
  zero_column.col(3).setZero();
  EXPECT_EQ(EquilibratedSolver<T>(zero_column).failure(),
            EquilibratedSolver<T>::Failure::zero_column);
  // Exactly zero: a row of denormals is not zero.
  Matrix4<T> tiny_row = integer_matrix<T>();
  tiny_row.row(2).setConstant(std::numeric_limits<T>::denorm_min());
  EXPECT_NE(EquilibratedSolver<T>(tiny_row).failure(), EquilibratedSolver<T>::Failure::zero_row);
}

// Nearly singular: two rows that differ by an ulp. rcond falls to the order of eps, at or below
// the threshold the methods refuse at; the identity has rcond 1.
TYPED_TEST(Solver, rcondSmallForNearlySingular) {
  using T = TypeParam;
  constexpr T eps = std::numeric_limits<T>::epsilon();
  Matrix4<T> m = integer_matrix<T>();
  m.row(1) = m.row(0);
  m(1, 0) = m(0, 0) * (T(1) + eps);
  const EquilibratedSolver<T> solver(m);
  ASSERT_EQ(solver.failure(), EquilibratedSolver<T>::Failure::none);
  EXPECT_LE(solver.rcond(), T(16) * eps);
  EXPECT_EQ(EquilibratedSolver<T>(Matrix4<T>::Identity()).rcond(), T(1));
}

}  // namespace
}  // namespace oblique
