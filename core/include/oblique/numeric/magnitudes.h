// Magnitudes of vectors and matrices, by powers of two: finiteness, exponents, how many binades
// the nonzero entries span, and exact scaling by 2^k.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace oblique {

/// Where T's exponent can be read from its bits: IEEE binary32 and binary64, and x87's 80-bit
/// extended long double (64-bit significand with an explicit integer bit, 15-bit exponent).
/// For these, the core reads exponents and builds powers of two from the bits instead of calling
/// libm's frexp, ldexp and ilogb (a call each, on every request); other types call them.
template <class T>
struct ExponentBits {
  static constexpr bool known = false;
};
template <>
struct ExponentBits<float> {
  static constexpr bool known = std::numeric_limits<float>::is_iec559;
  using Bits = std::uint32_t;
  static constexpr int fraction_bits = 23;
  static constexpr unsigned all_ones = 0xff;  ///< the field of infinities and NaN
  static constexpr int bias = 127;
};
template <>
struct ExponentBits<double> {
  static constexpr bool known = std::numeric_limits<double>::is_iec559;
  using Bits = std::uint64_t;
  static constexpr int fraction_bits = 52;
  static constexpr unsigned all_ones = 0x7ff;
  static constexpr int bias = 1023;
};
template <>
struct ExponentBits<long double> {
  static constexpr bool known = std::numeric_limits<long double>::digits == 64 &&
                                std::numeric_limits<long double>::max_exponent == 16384 &&
                                std::numeric_limits<long double>::min_exponent == -16381;
  static constexpr unsigned all_ones = 0x7fff;
  static constexpr int bias = 16383;
};

/// The biased exponent field of x, for a type whose ExponentBits are known: all_ones for
/// infinities and NaN; in [1, all_ones) exactly when x is normal, and then
/// x = +-f 2^(field - bias), f in [1, 2); 0 for zeros and subnormals (and for x87's invalid
/// unnormals, which take the libm paths like subnormals).
template <class T>
inline unsigned biased_exponent(T x) noexcept {
  using Layout = ExponentBits<T>;
  static_assert(Layout::known);
  if constexpr (std::is_same_v<T, long double>) {
    // Bytes 0-7 hold the significand (bit 63 the integer bit), bytes 8-9 the sign and exponent.
    unsigned char bytes[sizeof(long double)];
    std::memcpy(bytes, &x, sizeof bytes);
    std::uint16_t sign_exponent;
    std::memcpy(&sign_exponent, bytes + 8, 2);
    const unsigned field = sign_exponent & 0x7fffu;
    const bool integer_bit = (bytes[7] & 0x80u) != 0;
    return field == Layout::all_ones || integer_bit ? field : 0u;
  } else {
    typename Layout::Bits bits;
    std::memcpy(&bits, &x, sizeof bits);
    return static_cast<unsigned>(bits >> Layout::fraction_bits) & Layout::all_ones;
  }
}

/// The exponent std::frexp gives for a finite nonzero x (x = m 2^e, |m| in [1/2, 1)): from the
/// bits where x is normal and T's layout is known, from std::frexp otherwise.
template <class T>
inline int frexp_exponent(T x) noexcept {
  if constexpr (ExponentBits<T>::known) {
    const unsigned field = biased_exponent(x);
    if (field != 0 && field != ExponentBits<T>::all_ones)
      return static_cast<int>(field) - (ExponentBits<T>::bias - 1);
  }
  int e = 0;
  std::frexp(x, &e);
  return e;
}

/// 2^k as a constant expression (exact for any k whose 2^k is representable in T).
template <class T>
constexpr T constant_power_of_two(int k) noexcept {
  T x = T(1);
  for (; k > 0; --k) x *= T(2);
  for (; k < 0; ++k) x /= T(2);
  return x;
}

/// Whether 2^k is a normal number of T.
template <class T>
constexpr bool normal_power_of_two(int k) noexcept {
  return k >= std::numeric_limits<T>::min_exponent - 1 && k < std::numeric_limits<T>::max_exponent;
}

/// 2^k for a k with normal_power_of_two<T>(k): from the bits where T's layout is known (exactly
/// the value std::ldexp(T(1), k) gives), from std::ldexp otherwise.
template <class T>
inline T power_of_two(int k) noexcept {
  using Layout = ExponentBits<T>;
  if constexpr (Layout::known && std::is_same_v<T, long double>) {
    unsigned char bytes[sizeof(long double)] = {};
    const std::uint64_t significand = std::uint64_t(1) << 63;
    const auto field = static_cast<std::uint16_t>(k + Layout::bias);
    std::memcpy(bytes, &significand, 8);
    std::memcpy(bytes + 8, &field, 2);
    T x;
    std::memcpy(&x, bytes, sizeof x);
    return x;
  } else if constexpr (Layout::known) {
    const typename Layout::Bits bits = static_cast<typename Layout::Bits>(k + Layout::bias)
                                       << Layout::fraction_bits;
    T x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  } else {
    return std::ldexp(T(1), k);
  }
}

/// std::ldexp(x, k), the exact x 2^k rounded once: one multiplication by 2^k where that is a
/// normal number (the product is that same rounding of x 2^k, overflow and gradual underflow
/// included), std::ldexp otherwise.
template <class T>
inline T times_power_of_two(T x, int k) noexcept {
  return normal_power_of_two<T>(k) ? x * power_of_two<T>(k) : std::ldexp(x, k);
}

/// True when every entry is finite (no NaN, no infinity): |x| <= max for each (false for NaN),
/// what Eigen's allFinite() decides, in a loop the compiler keeps inline.
template <class Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  using T = typename Derived::Scalar;
  bool finite = true;
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      finite &= std::abs(m(i, j)) <= std::numeric_limits<T>::max();
  }
  return finite;
}

/// The exponent e with max |v_i| = m * 2^e, m in [1/2, 1); 0 for a zero vector.
template <class Derived>
inline int magnitude_exponent(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  T largest = T(0);
  for (Eigen::Index j = 0; j < v.cols(); ++j) {
    for (Eigen::Index i = 0; i < v.rows(); ++i) largest = std::max(largest, T(std::abs(v(i, j))));
  }
  if (!(largest > T(0))) return 0;
  return frexp_exponent(largest);
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
  constexpr T factor = constant_power_of_two<T>(Limit);
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
/// number, multiplying by it gives what ldexp gives (the exact v_i 2^k rounded once), so
/// power_of_two() makes the factor and multiplications do the rest.
template <class Derived>
typename Derived::PlainObject scaled_by_power_of_two(const Eigen::MatrixBase<Derived>& v, int k) {
  using T = typename Derived::Scalar;
  typename Derived::PlainObject out = v;
  if (normal_power_of_two<T>(k)) {
    const T factor = power_of_two<T>(k);
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] *= factor;
  } else {
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = std::ldexp(out.data()[i], k);
  }
  return out;
}

}  // namespace oblique
