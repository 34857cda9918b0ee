// apply()'s input checks in one pass over the exponent bits, for the common request: a finite
// matrix of the standard perspective shape with zero or normal entries of moderate spread, and a
// finite plane whose nonzero components are normal.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "oblique/detail/config.h"
#include "oblique/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/projection.h"

namespace oblique::detail {

/// What ordinary_input() finds: whether the request is ordinary, and for an ordinary one the
/// biased exponent fields (biased_exponent()) of the plane's largest component and of its
/// smallest nonzero one (0 and ExponentBits<T>::all_ones for a zero plane).
struct OrdinaryInput {
  bool ordinary = false;
  unsigned plane_high = 0;
  unsigned plane_low = 0;
};

/// x's bits without the sign, shifted left by one: 0 exactly for +-0, and ordered as |x| is
/// (for finite x and the infinities). T: IEEE float or double.
template <class T>
OBLIQUE_ALWAYS_INLINE auto magnitude_bits(T x) noexcept {
  typename ExponentBits<T>::Bits bits;
  std::memcpy(&bits, &x, sizeof bits);
  return static_cast<typename ExponentBits<T>::Bits>(bits << 1);
}

/// ordinary is true when apply()'s first four checks all pass: all_finite(m), all_finite(plane),
/// !magnitude_spread_exceeds<max_magnitude_spread<T>()>(m) and has_perspective_shape(m), and
/// every nonzero entry of m and of the plane is normal; false otherwise, and apply() then runs
/// those checks one by one (so the statuses and messages are theirs).
///
/// From the biased exponent fields f: a value is finite when f < all_ones; a nonzero normal m_ij
/// has ilogb(m_ij) = f_ij - bias, so magnitude_spread(m) is max f_ij - min f_ij over the nonzero
/// entries when every nonzero entry is normal. The shape asks the nine entries outside M11, M13,
/// M22, M23, M33, M34, M43 to compare equal to zero (either sign) and M43 not to; those nine
/// then add nothing to the spread. For IEEE float and double, b = magnitude_bits(x) orders the
/// values by magnitude and is 0 for zeros alone: max b and min (b - 1) (wrapping, so a zero counts
/// as the largest) over a set give its largest magnitude and its smallest nonzero one, whose
/// fields are b >> (fraction bits + 1); no floating-point comparison and no branch.
template <class T>
OBLIQUE_ALWAYS_INLINE OrdinaryInput ordinary_input(const Matrix4<T>& m,
                                                   const Vector4<T>& plane) noexcept {
  OrdinaryInput out;
  if constexpr (ExponentBits<T>::known && !std::is_same_v<T, long double>) {
    using Bits = typename ExponentBits<T>::Bits;
    constexpr int shift = ExponentBits<T>::fraction_bits + 1;
    constexpr unsigned all_ones = ExponentBits<T>::all_ones;
    const Bits outside =
        magnitude_bits(m(0, 1)) | magnitude_bits(m(0, 3)) | magnitude_bits(m(1, 0)) |
        magnitude_bits(m(1, 3)) | magnitude_bits(m(2, 0)) | magnitude_bits(m(2, 1)) |
        magnitude_bits(m(3, 0)) | magnitude_bits(m(3, 1)) | magnitude_bits(m(3, 3));
    const T entries[7] = {m(0, 0), m(0, 2), m(1, 1), m(1, 2), m(2, 2), m(2, 3), m(3, 2)};
    Bits high = 0, low_minus_one = ~Bits(0);
    for (const T x : entries) {
      const Bits b = magnitude_bits(x);
      high = std::max(high, b);
      low_minus_one = std::min(low_minus_one, Bits(b - 1));
    }
    Bits plane_high = 0, plane_low_minus_one = ~Bits(0);
    for (int i = 0; i < 4; ++i) {
      const Bits b = magnitude_bits(plane(i));
      plane_high = std::max(plane_high, b);
      plane_low_minus_one = std::min(plane_low_minus_one, Bits(b - 1));
    }
    // M43 != 0, so some entry is nonzero and low_minus_one + 1 is the smallest nonzero b.
    const auto f_high = static_cast<unsigned>(high >> shift);
    const auto f_low = static_cast<unsigned>(Bits(low_minus_one + 1) >> shift);
    out.plane_high = static_cast<unsigned>(plane_high >> shift);
    // A zero plane wraps to 0 here, and is not ordinary (plane_low 0 reads as subnormal).
    out.plane_low = static_cast<unsigned>(Bits(plane_low_minus_one + 1) >> shift);
    out.ordinary = outside == 0 && magnitude_bits(m(3, 2)) != 0 && f_high != all_ones &&
                   f_low != 0 && f_high - f_low <= unsigned(max_magnitude_spread<T>()) &&
                   out.plane_high != all_ones && out.plane_low != 0;
  } else if constexpr (ExponentBits<T>::known) {
    constexpr unsigned all_ones = ExponentBits<T>::all_ones;
    const bool shape = m(0, 1) == T(0) && m(0, 3) == T(0) && m(1, 0) == T(0) && m(1, 3) == T(0) &&
                       m(2, 0) == T(0) && m(2, 1) == T(0) && m(3, 0) == T(0) && m(3, 1) == T(0) &&
                       m(3, 3) == T(0) && m(3, 2) != T(0);
    const T entries[7] = {m(0, 0), m(0, 2), m(1, 1), m(1, 2), m(2, 2), m(2, 3), m(3, 2)};
    unsigned high = 0, low = all_ones;
    bool ordinary = shape;
    for (const T x : entries) {
      const unsigned f = biased_exponent(x);
      const bool zero = x == T(0);
      ordinary &= zero | (f - 1u < all_ones - 1u);  // zero or normal
      high = std::max(high, f);
      low = std::min(low, zero ? all_ones : f);
    }
    unsigned plane_high = 0, plane_low = all_ones;
    for (int i = 0; i < 4; ++i) {
      const unsigned f = biased_exponent(plane(i));
      const bool zero = plane(i) == T(0);
      ordinary &= zero | (f - 1u < all_ones - 1u);
      plane_high = std::max(plane_high, f);
      plane_low = std::min(plane_low, zero ? all_ones : f);
    }
    out.plane_high = plane_high;
    out.plane_low = plane_low;
    // With the shape, M43 != 0, so low <= high.
    out.ordinary = ordinary && plane_high != 0 && high - low <= unsigned(max_magnitude_spread<T>());
  }
  return out;
}

}  // namespace oblique::detail
