// apply()'s input checks in one pass over the exponent bits, for the common request: a finite
// matrix of the standard perspective shape with zero or normal entries of moderate spread, and a
// finite plane whose nonzero components are normal.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "oblique/detail/closed_form_steps.h"  // Entries
#include "oblique/detail/config.h"
#include "oblique/numeric/magnitudes.h"
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

  Entries entries() const noexcept { return Entries(ordinary); }
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
    // x87 long double, from the bytes in memory (no x87 loads): zero when the exponent field and
    // the significand are both 0 (what x == 0 finds for every encoding: x87's unnormals, the
    // only other ones with a zero significand, compare unordered), and the field as
    // biased_exponent() gives it (0 where the integer bit is clear).
    constexpr unsigned all_ones = ExponentBits<T>::all_ones;
    struct Fields {
      unsigned field;      ///< biased_exponent(x)
      bool zero;           ///< x == 0
      std::uint64_t bits;  ///< 0 exactly when x == 0
    };
    const auto fields = [](const T& x) {
      unsigned char bytes[10];
      std::memcpy(bytes, &x, sizeof bytes);
      std::uint64_t significand;
      std::uint16_t sign_exponent;
      std::memcpy(&significand, bytes, 8);
      std::memcpy(&sign_exponent, bytes + 8, 2);
      const unsigned raw = sign_exponent & 0x7fffu;
      const bool integer_bit = (significand >> 63) != 0;
      return Fields{raw == all_ones || integer_bit ? raw : 0u, (raw | significand) == 0,
                    raw | significand};
    };
    const bool shape = (fields(m(0, 1)).bits | fields(m(0, 3)).bits | fields(m(1, 0)).bits |
                        fields(m(1, 3)).bits | fields(m(2, 0)).bits | fields(m(2, 1)).bits |
                        fields(m(3, 0)).bits | fields(m(3, 1)).bits | fields(m(3, 3)).bits) == 0 &&
                       !fields(m(3, 2)).zero;
    const T* const entries[7] = {&m(0, 0), &m(0, 2), &m(1, 1), &m(1, 2),
                                 &m(2, 2), &m(2, 3), &m(3, 2)};
    unsigned high = 0, low = all_ones;
    bool ordinary = shape;
    for (const T* x : entries) {
      const Fields f = fields(*x);
      ordinary &= f.zero | (f.field - 1u < all_ones - 1u);  // zero or normal
      high = std::max(high, f.field);
      low = std::min(low, f.zero ? all_ones : f.field);
    }
    unsigned plane_high = 0, plane_low = all_ones;
    for (int i = 0; i < 4; ++i) {
      const Fields f = fields(plane(i));
      ordinary &= f.zero | (f.field - 1u < all_ones - 1u);
      plane_high = std::max(plane_high, f.field);
      plane_low = std::min(plane_low, f.zero ? all_ones : f.field);
    }
    out.plane_high = plane_high;
    out.plane_low = plane_low;
    // With the shape, M43 != 0, so low <= high.
    out.ordinary = ordinary && plane_high != 0 && high - low <= unsigned(max_magnitude_spread<T>());
  }
  return out;
}

}  // namespace oblique::detail
