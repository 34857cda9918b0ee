// Solves with a 4 x 4 matrix M and with its transpose, for the core's general method and the
// planted mutants (so the two cannot drift apart):
//  - M is equilibrated by powers of two (exactly, while no entry leaves the normal range) to
//    Mt = R M S, and factorised once with partial pivoting;
//  - each solve is refined with residuals computed in about twice the working precision
//    (error-free transformations, error_free.h), keeping the iterate with the smallest
//    componentwise backward error |b - A x|_i / (|A| |x| + |b|)_i.
// Partial pivoting alone is backward stable against |L| |U|, which can be far larger than |M|
// entry by entry; fuzz_oblique found matrices with entries of 1e-6 beside ones of 1 to 13 whose
// unrefined far corner missed the checker's bound by a factor of 400. The refinement brings the
// solution close to componentwise backward stable, which is what the bounds assume.
#pragma once

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "oblique/numeric/error_free.h"
#include "oblique/plane.h"

namespace oblique::detail {

/// b - A x (or b - A^T x), each entry with the accuracy of a computation in twice the working
/// precision rounded once (Ogita, Rump and Oishi's Dot2).
template <class T>
Vector4<T> accurate_residual(const Matrix4<T>& a, const Vector4<T>& x, const Vector4<T>& b,
                             bool transpose) noexcept {
  Vector4<T> r;
  for (int i = 0; i < 4; ++i) {
    T s = b(i), c = T(0);
    for (int j = 0; j < 4; ++j) {
      const T aij = transpose ? a(j, i) : a(i, j);
      const eft::Pair<T> p = eft::two_prod(aij, x(j));  // aij x_j exactly
      const eft::Pair<T> t = eft::two_sum(s, -p.hi);
      s = t.hi;
      c += t.lo - p.lo;
    }
    r(i) = s + c;
  }
  return r;
}

/// max_i |r_i| / (|A| |x| + |b|)_i, Oettli and Prager's componentwise backward error.
template <class T>
T componentwise_backward_error(const Matrix4<T>& a, const Vector4<T>& x, const Vector4<T>& b,
                               const Vector4<T>& r, bool transpose) noexcept {
  T worst = T(0);
  for (int i = 0; i < 4; ++i) {
    T scale = std::abs(b(i));
    for (int j = 0; j < 4; ++j) scale += std::abs(transpose ? a(j, i) : a(i, j)) * std::abs(x(j));
    if (r(i) == T(0)) continue;
    const T ratio = scale > T(0) ? std::abs(r(i)) / scale : std::numeric_limits<T>::infinity();
    worst = std::max(worst, ratio);
  }
  return worst;
}

/// The largest componentwise backward error of a refined solve that the error bounds built on it
/// accept (transposed_error_bound(), the checker's): the refinement stops at eps, and beyond this
/// it has stalled. The general method hands such inputs to the accurate method, which settles
/// them exactly.
template <class T>
constexpr T backward_error_limit() noexcept {
  return T(8) * std::numeric_limits<T>::epsilon();
}

template <class T>
class EquilibratedSolver {
 public:
  enum class Failure { none, zero_row, zero_column };

  explicit EquilibratedSolver(const Matrix4<T>& m) : mt_(m) {
    for (int i = 0; i < 4; ++i) {
      if ((mt_.row(i).array() == T(0)).all()) {  // exact: isZero() is fuzzy
        failure_ = Failure::zero_row;
        return;
      }
      const int e = magnitude_exponent(mt_.row(i));
      row_shift_(i) = -e;
      mt_.row(i) = scaled_by_power_of_two(mt_.row(i), -e);
    }
    for (int j = 0; j < 4; ++j) {
      if ((mt_.col(j).array() == T(0)).all()) {
        failure_ = Failure::zero_column;
        return;
      }
      const int e = magnitude_exponent(mt_.col(j));
      col_shift_(j) = -e;
      mt_.col(j) = scaled_by_power_of_two(mt_.col(j), -e);
    }
    lu_.compute(mt_);
  }

  Failure failure() const noexcept { return failure_; }

  /// The reciprocal condition number of the equilibrated matrix (Eigen's estimate).
  T rcond() const { return lu_.rcond(); }

  /// A componentwise bound on the error of y = solve_transposed_unscaled(c), if the solve is
  /// componentwise backward stable: 16 epsilon (|Mt^-T| |Mt^T| |y|)_i. A component below its
  /// bound may be a rounded zero, and its sign is not to be trusted.
  Vector4<T> transposed_error_bound(const Vector4<T>& y) const {
    const Matrix4<T> inverse = lu_.inverse();
    const Vector4<T> bound =
        inverse.cwiseAbs().transpose() * (mt_.cwiseAbs().transpose() * y.cwiseAbs());
    return T(16) * std::numeric_limits<T>::epsilon() * bound;
  }

  /// The correction z1 to z = solve_transposed_unscaled(c) from one more refinement step whose
  /// residual S c - Mt^T z is summed as in twice the working precision (z + z1 is then accurate to
  /// about eps^2 times the conditioning). Its error is bounded by transposed_error_bound(z1) plus
  /// eps transposed_error_bound(z).
  Vector4<T> transposed_correction_unscaled(const Vector4<T>& c, const Vector4<T>& z) const {
    const Vector4<T> scaled_c = shifted(c, col_shift_);
    return lu_solve(accurate_residual(mt_, z, scaled_c, true), true);
  }

  /// x with M x = b: x = S Mt^-1 (R b). With `backward_error`, also the componentwise backward
  /// error of x (max_i |b - M x|_i / (|M| |x| + |b|)_i, the same for the equilibrated system).
  Vector4<T> solve(const Vector4<T>& b, T* backward_error = nullptr) const {
    return shifted(refined(shifted(b, row_shift_), false, backward_error), col_shift_);
  }

  /// Mt^-T (S c) = R^-1 M^-T c: the solution of M^T y = c divided by R's positive diagonal, so
  /// it has the signs of y (all that the far corner needs) without overflowing where y would.
  Vector4<T> solve_transposed_unscaled(const Vector4<T>& c, T* backward_error = nullptr) const {
    return refined(shifted(c, col_shift_), true, backward_error);
  }

 private:
  /// v_i 2^k_i, each rounded once. The scales are kept as exponents, not as powers of two in T:
  /// a row whose largest entry is subnormal has a scale beyond T's range (2^1026 in double), and
  /// the product inf * 0 made a zero right-hand side NaN (fuzz_oblique: a far corner with
  /// Q'_z = 0 and M_34 = 4.2e-309 came out NaN, and the core answered out_of_range).
  static Vector4<T> shifted(const Vector4<T>& v, const Eigen::Vector4i& k) {
    Vector4<T> out;
    for (int i = 0; i < 4; ++i) out(i) = times_power_of_two(v(i), k(i));
    return out;
  }

  Vector4<T> lu_solve(const Vector4<T>& b, bool transpose) const {
    return transpose ? Vector4<T>(lu_.transpose().solve(b)) : Vector4<T>(lu_.solve(b));
  }

  Vector4<T> refined(const Vector4<T>& b, bool transpose, T* backward_error) const {
    constexpr int kMaxSteps = 4;
    Vector4<T> x = lu_solve(b, transpose);
    if (backward_error) *backward_error = std::numeric_limits<T>::infinity();
    if (!all_finite(x)) return x;
    Vector4<T> r = accurate_residual(mt_, x, b, transpose);
    T error = componentwise_backward_error(mt_, x, b, r, transpose);
    for (int step = 0; step < kMaxSteps && error > std::numeric_limits<T>::epsilon(); ++step) {
      const Vector4<T> d = lu_solve(r, transpose);
      const Vector4<T> next = x + d;
      if (!all_finite(next)) break;
      const Vector4<T> next_r = accurate_residual(mt_, next, b, transpose);
      const T next_error = componentwise_backward_error(mt_, next, b, next_r, transpose);
      if (!(next_error < error)) break;  // no progress: keep the best iterate
      x = next;
      r = next_r;
      error = next_error;
    }
    if (backward_error) *backward_error = error;
    return x;
  }

  Matrix4<T> mt_;
  Eigen::Vector4i row_shift_ = Eigen::Vector4i::Zero(), col_shift_ = Eigen::Vector4i::Zero();
  Eigen::PartialPivLU<Matrix4<T>> lu_;
  Failure failure_ = Failure::none;
};

}  // namespace oblique::detail
