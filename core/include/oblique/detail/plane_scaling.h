// How the core scales a clip plane C by a power of two before C . Q (so that the dot product
// neither overflows nor underflows), whether that lost bits, and when a plane is stiff.
#pragma once

#include <cmath>
#include <limits>

#include "oblique/detail/config.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"

namespace oblique {

/// How the core scales a plane before C . Q, and the plane's magnitude_spread(), from one pass.
struct PlaneScale {
  int shift = 0;   ///< see plane_scale_shift()
  int spread = 0;  ///< binades from the smallest nonzero component to the largest
  /// Whether the smallest nonzero component, scaled by 2^shift, is below the normal range (and
  /// may have lost bits).
  bool below_normal = false;
  /// The frexp exponent e of the largest component (2^(e-1) <= max |C_i| < 2^e; 0 for a zero
  /// plane).
  int top = 0;
};

/// plane_scale() from the frexp exponents of the largest component (e) and of the smallest
/// nonzero one (low_exponent).
template <class T>
OBLIQUE_ALWAYS_INLINE PlaneScale plane_scale_of_exponents(int e, int low_exponent) noexcept {
  const int keep_normal = std::numeric_limits<T>::min_exponent - low_exponent;
  if (-e < keep_normal && e + keep_normal <= std::numeric_limits<T>::max_exponent / 2)
    return {keep_normal, e - low_exponent, false, e};
  return {-e, e - low_exponent, -e < keep_normal, e};
}

/// plane_scale() of a plane whose components are zero or normal, not all zero, from the biased
/// exponent fields (biased_exponent()) of its largest component and of its smallest nonzero
/// one, as ordinary_input() reads them: no libm call.
template <class T>
OBLIQUE_ALWAYS_INLINE PlaneScale plane_scale_of_fields(unsigned high, unsigned low) noexcept {
  constexpr int offset = ExponentBits<T>::bias - 1;  // frexp exponent = field - offset, normal
  return plane_scale_of_exponents<T>(static_cast<int>(high) - offset,
                                     static_cast<int>(low) - offset);
}

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
  if (!(low < std::numeric_limits<T>::infinity())) return {-e, 0, false, e};
  return plane_scale_of_exponents<T>(e, frexp_exponent(low));
}

template <class Derived>
int plane_scale_shift(const Eigen::MatrixBase<Derived>& v) {
  return plane_scale(v).shift;
}

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
OBLIQUE_ALWAYS_INLINE ScaledPlane<T> scale_plane(const Vector4<T>& c, const PlaneScale& scale) {
  // Entry by entry (Eigen's assignment is a call for long double), as scaled_by_power_of_two().
  ScaledPlane<T> out;
  out.shift = scale.shift;
  if (normal_power_of_two<T>(scale.shift)) {
    const T factor = power_of_two<T>(scale.shift);
    for (int i = 0; i < 4; ++i) out.c_hat(i) = c(i) * factor;
  } else {
    for (int i = 0; i < 4; ++i) out.c_hat(i) = std::ldexp(c(i), scale.shift);
  }
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
