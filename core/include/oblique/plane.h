// Planes and matrices on Eigen types. Column-vector convention: clip = M * p.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "oblique/error_free.h"

namespace oblique {

template <class T>
using Matrix4 = Eigen::Matrix<T, 4, 4>;

/// A homogeneous point (w = 1), direction (w = 0), or plane <N, -N.P>; a plane keeps the points
/// p with plane.dot(p) >= 0 (paper Eq. 1).
template <class T>
using Vector4 = Eigen::Matrix<T, 4, 1>;

/// The plane through `point` whose positive (kept) side is the one `normal` points to.
template <class T>
Vector4<T> plane_from_normal_and_point(const Eigen::Matrix<T, 3, 1>& normal,
                                       const Eigen::Matrix<T, 3, 1>& point) {
  Vector4<T> plane;
  plane << normal, -normal.dot(point);
  return plane;
}

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

/// How the core scales a plane before C . Q, and the plane's magnitude_spread(), from one pass.
struct PlaneScale {
  int shift = 0;   ///< see plane_scale_shift()
  int spread = 0;  ///< binades from the smallest nonzero component to the largest
  /// Whether the smallest nonzero component, scaled by 2^shift, is below the normal range (and
  /// may have lost bits).
  bool below_normal = false;
};

/// The power of two k by which the core scales a plane before C . Q: k = -e brings the largest
/// component to [1/2, 1), unless that would push the smallest nonzero component below the normal
/// range (losing its bits, which C . Q may need when Q is large in that coordinate); then k keeps
/// that component normal, as long as the largest stays below 2^(max_exponent / 2).
template <class Derived>
PlaneScale plane_scale(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  const int e = magnitude_exponent(v);
  T low = std::numeric_limits<T>::infinity();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (v(i) != T(0)) low = std::min(low, T(std::abs(v(i))));
  }
  if (!(low < std::numeric_limits<T>::infinity())) return {-e, 0};
  int low_exponent = 0;
  std::frexp(low, &low_exponent);
  const int keep_normal = std::numeric_limits<T>::min_exponent - low_exponent;
  if (-e < keep_normal && e + keep_normal <= std::numeric_limits<T>::max_exponent / 2)
    return {keep_normal, e - low_exponent, false};
  return {-e, e - low_exponent, -e < keep_normal};
}

template <class Derived>
int plane_scale_shift(const Eigen::MatrixBase<Derived>& v) {
  return plane_scale(v).shift;
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

/// Keeps a rarely taken path out of its caller's code.
#if defined(__GNUC__)
#define OBLIQUE_NOINLINE __attribute__((noinline))
#else
#define OBLIQUE_NOINLINE
#endif

/// C scaled by 2^shift (c_hat), and whether that lost bits: a nonzero component pushed below
/// the normal range and off some of its bits, so that sums with c_hat miss what they carry.
template <class T>
struct ScaledPlane {
  Vector4<T> c_hat;
  int shift = 0;
  bool lossy = false;
};

/// The slow part of scale_plane(): some scaled component is below the normal range.
template <class T>
OBLIQUE_NOINLINE bool scaled_components_inexact(const Vector4<T>& c, const Vector4<T>& c_hat,
                                                int shift) {
  bool lost = false;
  for (int i = 0; i < 4; ++i) {
    if (c(i) != T(0) && !(std::abs(c_hat(i)) >= std::numeric_limits<T>::min()))
      lost |= std::ldexp(c_hat(i), -shift) != c(i);
  }
  return lost;
}

/// c scaled by plane_scale(c)'s shift, computed in T (the plane's own type, or a wider one: a
/// component normal at the narrower type's scale is normal in the wider one, so `below_normal`
/// still tells when to look). No work beyond the scaling unless the smallest nonzero component
/// went below the normal range.
template <class T>
ScaledPlane<T> scale_plane(const Vector4<T>& c, const PlaneScale& scale) {
  ScaledPlane<T> out{scaled_by_power_of_two(c, scale.shift), scale.shift, false};
  out.lossy = scale.below_normal && scaled_components_inexact(c, out.c_hat, scale.shift);
  return out;
}

/// Whether a plane is stiff for a computation in W: its nonzero components span more than
/// max_magnitude_spread<W>() = 2p binades, beyond what even the refinement's twice-precision
/// residuals resolve (C' or C . Q may rest on the small components: fuzz_oblique found a float
/// plane spanning 2^-126 to 1 whose C' came out with a trusted wrong sign), or scaling it lost
/// bits.
template <class W>
bool stiff_plane(const PlaneScale& scale, const ScaledPlane<W>& scaled) {
  return scaled.lossy || scale.spread > max_magnitude_spread<W>();
}

}  // namespace oblique
