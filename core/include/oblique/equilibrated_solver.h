// Solves with a 4 x 4 matrix M and with its transpose: M is equilibrated by powers of two
// (exactly, while no entry leaves the normal range) to Mt = R M S and factorised once with partial
// pivoting; both solves reuse the factorisation. Shared by the core's general method and the
// planted mutants, so the two cannot drift apart.
#pragma once

#include <Eigen/LU>
#include <cmath>

#include "oblique/plane.h"

namespace oblique::detail {

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
      row_scale_(i) = std::ldexp(T(1), -e);
      mt_.row(i) = scaled_by_power_of_two(mt_.row(i), -e);
    }
    for (int j = 0; j < 4; ++j) {
      if ((mt_.col(j).array() == T(0)).all()) {
        failure_ = Failure::zero_column;
        return;
      }
      const int e = magnitude_exponent(mt_.col(j));
      col_scale_(j) = std::ldexp(T(1), -e);
      mt_.col(j) = scaled_by_power_of_two(mt_.col(j), -e);
    }
    lu_.compute(mt_);
  }

  Failure failure() const noexcept { return failure_; }

  /// The reciprocal condition number of the equilibrated matrix (Eigen's estimate).
  T rcond() const { return lu_.rcond(); }

  /// x with M x = b: x = S Mt^-1 (R b).
  Vector4<T> solve(const Vector4<T>& b) const {
    return col_scale_.cwiseProduct(Vector4<T>(lu_.solve(row_scale_.cwiseProduct(b))));
  }

  /// Mt^-T (S c) = R^-1 M^-T c: the solution of M^T y = c divided by R's positive diagonal, so
  /// it has the signs of y (all that the far corner needs) without overflowing where y would.
  Vector4<T> solve_transposed_unscaled(const Vector4<T>& c) const {
    return lu_.transpose().solve(col_scale_.cwiseProduct(c));
  }

 private:
  Matrix4<T> mt_;
  Vector4<T> row_scale_ = Vector4<T>::Ones(), col_scale_ = Vector4<T>::Ones();
  Eigen::PartialPivLU<Matrix4<T>> lu_;
  Failure failure_ = Failure::none;
};

}  // namespace oblique::detail
