// Magnitudes of vectors and matrices, by powers of two: finiteness, exponents, how many binades
// the nonzero entries span, and exact scaling by 2^k.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "oblique/accurate/error_free.h"

namespace oblique {

/// True when every entry is finite (no NaN, no infinity).
template <class Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}

/// The exponent e with max |v_i| = m * 2^e, m in [1/2, 1); 0 for a zero vector.
template <class Derived>
int magnitude_exponent(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  const T largest = v.cwiseAbs().maxCoeff();
  if (!(largest > T(0))) return 0;
  int exponent = 0;
  std::frexp(largest, &exponent);
  return exponent;
}

/// The largest and the smallest nonzero |v_ij| (high = 0 when every entry is 0).
template <class T>
struct MagnitudeRange {
  T high = T(0);
  T low = std::numeric_limits<T>::infinity();
};

template <class Derived>
MagnitudeRange<typename Derived::Scalar> magnitude_range(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  MagnitudeRange<T> range;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    for (Eigen::Index j = 0; j < v.cols(); ++j) {
      const T a = std::abs(v(i, j));
      if (a == T(0)) continue;
      range.high = std::max(range.high, a);
      range.low = std::min(range.low, a);
    }
  }
  return range;
}

/// How many binades the nonzero entries of v span: ilogb(max |v_ij|) - ilogb(min nonzero |v_ij|);
/// 0 when fewer than two entries are nonzero. Entries must be finite.
template <class Derived>
int magnitude_spread(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  const MagnitudeRange<T> range = magnitude_range(v);
  return range.high > T(0) ? std::ilogb(range.high) - std::ilogb(range.low) : 0;
}

/// Whether magnitude_spread(v) > limit, mostly without ilogb (a libm call per value on the
/// core's path): with high and low the largest and smallest nonzero |v_ij|, high < low 2^limit
/// gives a spread of at most limit and high >= low 2^(limit + 1) one above it (ilogb is the
/// floor of log2); only between them are the exponents compared. Entries must be finite.
template <int Limit, class Derived>
bool magnitude_spread_exceeds(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  const auto [high, low] = magnitude_range(v);
  if (!(high > T(0))) return false;
  // Multiplying by a power of two is exact (an overflow to infinity keeps the comparisons right).
  constexpr T factor = eft::power_of_two<T>(Limit);
  if (high < low * factor) return false;
  if (high >= low * factor * T(2)) return true;
  return std::ilogb(high) - std::ilogb(low) > Limit;
}

/// The widest magnitude_spread() of a projection matrix that the core computes with in T: 2p
/// binades (p = T's precision). Beyond it the far corner's small coordinates cannot be resolved
/// against its large ones by a 4 x 4 solve in T (fuzz_oblique found matrices with entries near
/// DBL_MAX beside ordinary ones whose answers were silently wrong), and the core answers
/// out_of_range instead. A plane's spread is not limited: a C_w far below |N| (the plane almost
/// through the eye) is a stiff but ordinary case.
template <class T>
constexpr int max_magnitude_spread() noexcept {
  return 2 * std::numeric_limits<T>::digits;
}

/// v * 2^k entry by entry: exact unless an entry leaves the normal range, so it removes overflow
/// and underflow from what follows without changing its rounding. While 2^k is itself a normal
/// number, multiplying by it gives what ldexp gives (the exact v_i 2^k rounded once), so one
/// ldexp makes the factor and multiplications do the rest.
template <class Derived>
typename Derived::PlainObject scaled_by_power_of_two(const Eigen::MatrixBase<Derived>& v, int k) {
  using T = typename Derived::Scalar;
  typename Derived::PlainObject out = v;
  if (k >= std::numeric_limits<T>::min_exponent - 1 && k < std::numeric_limits<T>::max_exponent) {
    const T factor = std::ldexp(T(1), k);
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] *= factor;
  } else {
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = std::ldexp(out.data()[i], k);
  }
  return out;
}

}  // namespace oblique
