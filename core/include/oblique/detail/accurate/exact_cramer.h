// Exact arithmetic for the accurate method's stiff planes: the oblique answer by Cramer's rule on
// big integers, with no rounding until the last step.
//
// Every finite floating-point number is an integer times a power of two. Scaling M by 2^-e_m and
// C by 2^-e_c (e_m, e_c: the exponents of their lowest set bits) and Q' by 2 makes every input
// an integer, and then, with D = det M, X_j = det(M with column j replaced by 2 Q') and
// Y_i = det(M with row i replaced by C) (all in those integer units):
//   C'_i = M^-T C has the sign of Y_i D               (Cramer's rule on M^T y = C),
//   Q_j  = X_j / D 2^(-1 - e_m),
//   C . Q = N / D 2^(e_c - 1 - e_m),   N = sum_j c_j X_j,
//   M'_3i = s (a C_i - t M4_i) = s 2^e_m P_i / N,   P_i = 2 k D c_i - t m4_i N,
// where a = k / (C . Q), k = z_high - z_low and near = s M_3 + t M_4. The signs of C', of D and
// of C . Q are exact; Q and each entry of M'_3 are quotients of exact integers, formed to about
// 2p bits and rounded once (within an ulp of the exact value, correctly rounded but for ties and
// the subnormal range).
//
// The cost (nine 4 x 4 determinants of integers up to a few thousand bits) is paid only for the
// inputs the floating-point path cannot settle (see detail::accurate()).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/numeric/error_free.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"

namespace oblique::detail {

/// A signed integer of any size, sign and magnitude (32-bit limbs, least significant first, no
/// leading zero limbs; zero has no limbs and is never negative). Only what Cramer's rule needs.
class BigInt {
 public:
  BigInt() = default;

  /// magnitude 2^shift, with the sign given.
  static BigInt from_magnitude(std::uint64_t magnitude, bool negative, int shift) {
    BigInt out;
    const int limb_shift = shift / 32, bit_shift = shift % 32;
    out.limbs_.assign(static_cast<std::size_t>(limb_shift), 0u);
    // magnitude << bit_shift spans up to 96 bits.
    const std::uint64_t low = magnitude << bit_shift;
    const std::uint64_t high = bit_shift == 0 ? 0 : magnitude >> (64 - bit_shift);
    out.limbs_.push_back(static_cast<std::uint32_t>(low));
    out.limbs_.push_back(static_cast<std::uint32_t>(low >> 32));
    out.limbs_.push_back(static_cast<std::uint32_t>(high));
    out.trim();
    out.negative_ = negative && !out.limbs_.empty();
    return out;
  }

  int sign() const { return limbs_.empty() ? 0 : (negative_ ? -1 : 1); }

  /// The number of bits of the magnitude (0 for zero).
  int bit_length() const {
    if (limbs_.empty()) return 0;
    int bits = 32 * static_cast<int>(limbs_.size() - 1);
    for (std::uint32_t top = limbs_.back(); top != 0; top >>= 1) ++bits;
    return bits;
  }

  friend BigInt operator-(BigInt x) {
    x.negative_ = !x.negative_ && !x.limbs_.empty();
    return x;
  }

  friend BigInt operator+(const BigInt& x, const BigInt& y) {
    if (x.negative_ == y.negative_) {
      BigInt out = add_magnitudes(x, y);
      out.negative_ = x.negative_ && !out.limbs_.empty();
      return out;
    }
    // Opposite signs: the larger magnitude's sign.
    const int order = compare_magnitudes(x, y);
    if (order == 0) return BigInt();
    BigInt out = order > 0 ? subtract_magnitudes(x, y) : subtract_magnitudes(y, x);
    out.negative_ = (order > 0 ? x.negative_ : y.negative_) && !out.limbs_.empty();
    return out;
  }

  friend BigInt operator-(const BigInt& x, const BigInt& y) { return x + (-y); }

  friend BigInt operator*(const BigInt& x, const BigInt& y) {
    BigInt out;
    if (x.limbs_.empty() || y.limbs_.empty()) return out;
    out.limbs_.assign(x.limbs_.size() + y.limbs_.size(), 0u);
    for (std::size_t i = 0; i < x.limbs_.size(); ++i) {
      std::uint64_t carry = 0;
      const std::uint64_t xi = x.limbs_[i];
      for (std::size_t j = 0; j < y.limbs_.size(); ++j) {
        const std::uint64_t t = xi * y.limbs_[j] + out.limbs_[i + j] + carry;
        out.limbs_[i + j] = static_cast<std::uint32_t>(t);
        carry = t >> 32;
      }
      for (std::size_t k = i + y.limbs_.size(); carry != 0; ++k) {
        const std::uint64_t t = std::uint64_t(out.limbs_[k]) + carry;
        out.limbs_[k] = static_cast<std::uint32_t>(t);
        carry = t >> 32;
      }
    }
    out.trim();
    out.negative_ = x.negative_ != y.negative_;
    return out;
  }

  /// |x| = (hi + lo) 2^exponent with hi + lo in [1/2, 1): the top 128 bits of the magnitude,
  /// truncated (relative error below 2^-127), as an unevaluated sum in W (within eps of W times
  /// |lo| of those bits). Precondition: x != 0.
  template <class W>
  eft::Pair<W> top_bits(int& exponent) const {
    const int length = bit_length();
    exponent = length;
    // The 128 bits below the top one, as four 32-bit words, each exact in W.
    eft::Terms<W, 4> terms;
    for (int word = 0; word < 4; ++word) {
      const int low_bit = length - 32 * (word + 1);  // bit of x that lands on the word's bit 0
      std::uint64_t bits = 0;
      for (int b = 31; b >= 0; --b) bits = (bits << 1) | bit(low_bit + b);
      terms.add(std::ldexp(W(static_cast<std::uint32_t>(bits)), -32 * (word + 1)));
    }
    bool exact = false;
    return terms.distil(exact);
  }

 private:
  std::uint64_t bit(int index) const {
    if (index < 0) return 0;
    const std::size_t limb = static_cast<std::size_t>(index / 32);
    return limb < limbs_.size() ? (limbs_[limb] >> (index % 32)) & 1u : 0;
  }

  void trim() {
    while (!limbs_.empty() && limbs_.back() == 0) limbs_.pop_back();
  }

  static int compare_magnitudes(const BigInt& x, const BigInt& y) {
    if (x.limbs_.size() != y.limbs_.size()) return x.limbs_.size() < y.limbs_.size() ? -1 : 1;
    for (std::size_t i = x.limbs_.size(); i-- > 0;) {
      if (x.limbs_[i] != y.limbs_[i]) return x.limbs_[i] < y.limbs_[i] ? -1 : 1;
    }
    return 0;
  }

  static BigInt add_magnitudes(const BigInt& x, const BigInt& y) {
    const BigInt& longer = x.limbs_.size() >= y.limbs_.size() ? x : y;
    const BigInt& shorter = x.limbs_.size() >= y.limbs_.size() ? y : x;
    BigInt out;
    out.limbs_.resize(longer.limbs_.size() + 1);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < longer.limbs_.size(); ++i) {
      const std::uint64_t t = std::uint64_t(longer.limbs_[i]) +
                              (i < shorter.limbs_.size() ? shorter.limbs_[i] : 0u) + carry;
      out.limbs_[i] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    out.limbs_.back() = static_cast<std::uint32_t>(carry);
    out.trim();
    return out;
  }

  /// |x| - |y|, precondition |x| >= |y|.
  static BigInt subtract_magnitudes(const BigInt& x, const BigInt& y) {
    BigInt out;
    out.limbs_.resize(x.limbs_.size());
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < x.limbs_.size(); ++i) {
      std::int64_t t = std::int64_t(x.limbs_[i]) -
                       (i < y.limbs_.size() ? std::int64_t(y.limbs_[i]) : 0) - borrow;
      borrow = t < 0;
      if (t < 0) t += std::int64_t(1) << 32;
      out.limbs_[i] = static_cast<std::uint32_t>(t);
    }
    out.trim();
    return out;
  }

  std::vector<std::uint32_t> limbs_;
  bool negative_ = false;
};

/// x = integer 2^exponent, the integer below 2^digits (0 for x = 0, with exponent 0).
template <class W>
struct IntegerAndExponent {
  std::uint64_t magnitude = 0;
  bool negative = false;
  int exponent = 0;
};

template <class W>
IntegerAndExponent<W> integer_and_exponent(W x) {
  static_assert(std::numeric_limits<W>::digits <= 64, "the significand must fit in 64 bits");
  IntegerAndExponent<W> out;
  if (x == W(0)) return out;
  int e = 0;
  const W fraction = std::frexp(std::fabs(x), &e);  // [1/2, 1)
  out.magnitude = static_cast<std::uint64_t>(std::ldexp(fraction, std::numeric_limits<W>::digits));
  out.negative = x < W(0);
  out.exponent = e - std::numeric_limits<W>::digits;
  // Drop trailing zeros so that the common exponent below is as high as it can be.
  while ((out.magnitude & 1u) == 0) {
    out.magnitude >>= 1;
    ++out.exponent;
  }
  return out;
}

/// The entries of v as integers in units of 2^exponent (the lowest exponent of a nonzero entry).
template <class W, std::size_t N>
std::array<BigInt, N> to_integers(const std::array<W, N>& v, int& exponent) {
  std::array<IntegerAndExponent<W>, N> parts;
  exponent = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < N; ++i) {
    parts[i] = integer_and_exponent(v[i]);
    if (parts[i].magnitude != 0) exponent = std::min(exponent, parts[i].exponent);
  }
  if (exponent == std::numeric_limits<int>::max()) exponent = 0;
  std::array<BigInt, N> out;
  for (std::size_t i = 0; i < N; ++i) {
    if (parts[i].magnitude != 0)
      out[i] = BigInt::from_magnitude(parts[i].magnitude, parts[i].negative,
                                      parts[i].exponent - exponent);
  }
  return out;
}

using BigMatrix4 = std::array<std::array<BigInt, 4>, 4>;

/// det a by the Laplace expansion along the first two rows (six 2 x 2 minors each side).
inline BigInt determinant(const BigMatrix4& a) {
  const auto minor = [](const BigInt& p, const BigInt& q, const BigInt& r, const BigInt& s) {
    return p * s - q * r;  // det [[p, q], [r, s]]
  };
  const BigInt s0 = minor(a[0][0], a[0][1], a[1][0], a[1][1]);
  const BigInt s1 = minor(a[0][0], a[0][2], a[1][0], a[1][2]);
  const BigInt s2 = minor(a[0][0], a[0][3], a[1][0], a[1][3]);
  const BigInt s3 = minor(a[0][1], a[0][2], a[1][1], a[1][2]);
  const BigInt s4 = minor(a[0][1], a[0][3], a[1][1], a[1][3]);
  const BigInt s5 = minor(a[0][2], a[0][3], a[1][2], a[1][3]);
  const BigInt c5 = minor(a[2][2], a[2][3], a[3][2], a[3][3]);
  const BigInt c4 = minor(a[2][1], a[2][3], a[3][1], a[3][3]);
  const BigInt c3 = minor(a[2][1], a[2][2], a[3][1], a[3][2]);
  const BigInt c2 = minor(a[2][0], a[2][3], a[3][0], a[3][3]);
  const BigInt c1 = minor(a[2][0], a[2][2], a[3][0], a[3][2]);
  const BigInt c0 = minor(a[2][0], a[2][1], a[3][0], a[3][1]);
  return s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;
}

/// num / den 2^shift rounded to T, within an ulp of the exact value (an eps^2-accurate quotient
/// of each one's top 128 bits, rounded once; where the result is subnormal, once more by the
/// scaling). 0 when num is 0; +-infinity beyond the range. Precondition: den != 0.
template <class T, class W>
T exact_quotient(const BigInt& num, const BigInt& den, int shift) {
  if (num.sign() == 0) return T(0);
  int num_exponent = 0, den_exponent = 0;
  const eft::Pair<W> n = num.template top_bits<W>(num_exponent);
  const eft::Pair<W> d = den.template top_bits<W>(den_exponent);
  const eft::Pair<W> q = eft::divide(n, d);  // in (1/2, 2)
  const long total = long(num_exponent) - long(den_exponent) + long(shift);
  // Beyond W's exponent range the result is 0 or infinite in T anyway.
  const int e = static_cast<int>(std::clamp<long>(total, -100000, 100000));
  const W sign = W(num.sign() * den.sign());
  const eft::Pair<W> scaled{sign * std::ldexp(q.hi, e), sign * std::ldexp(q.lo, e)};
  return eft::round_pair<T>(scaled);
}

/// The exact oblique answer for M and C (computed in W, the answer rounded to T).
template <class T, class W>
struct ExactOblique {
  enum class Outcome { singular, plane_misses_view_volume, answered };
  Outcome outcome = Outcome::singular;
  Vector4<W> far_corner = Vector4<W>::Zero();  ///< Q, each entry within an ulp (may be infinite)
  Vector4<T> row3 = Vector4<T>::Zero();        ///< M'_3, each entry within an ulp (may be infinite)
};

/// The oblique answer by Cramer's rule in exact integer arithmetic (see the top of this file).
/// Preconditions: M and C finite.
template <class T, class W>
ExactOblique<T, W> exact_oblique(const Matrix4<W>& m, const Vector4<W>& c, Convention convention) {
  ExactOblique<T, W> out;
  std::array<W, 16> m_entries;
  for (int i = 0; i < 16; ++i) m_entries[static_cast<std::size_t>(i)] = m(i / 4, i % 4);
  int e_m = 0, e_c = 0;
  const std::array<BigInt, 16> m_int = to_integers(m_entries, e_m);
  const std::array<BigInt, 4> c_int = to_integers(std::array<W, 4>{c(0), c(1), c(2), c(3)}, e_c);
  BigMatrix4 mi;
  for (int i = 0; i < 16; ++i) mi[i / 4][i % 4] = m_int[static_cast<std::size_t>(i)];
  const BigInt det = determinant(mi);
  if (det.sign() == 0) return out;
  // The signs of C' = M^-T C: row i of M replaced by C.
  int c_clip_sign[3];
  for (int i = 0; i < 3; ++i) {
    BigMatrix4 replaced = mi;
    for (int j = 0; j < 4; ++j) replaced[i][j] = c_int[j];
    c_clip_sign[i] = determinant(replaced).sign() * det.sign();
  }
  // 2 Q', integers: the corner's x, y (sign of C'_x, C'_y; 0 for the middle of the edge) and z
  // (the face C'_z leans toward, the middle for C'_z = 0).
  const DepthRange range = clip_depth_range(convention);
  const int z2 = c_clip_sign[2] > 0   ? 2 * range.z_high
                 : c_clip_sign[2] < 0 ? 2 * range.z_low
                                      : range.z_low + range.z_high;
  const int corner2[4] = {2 * c_clip_sign[0], 2 * c_clip_sign[1], z2, 2};
  std::array<BigInt, 4> x;  // X_j: column j of M replaced by 2 Q'
  BigInt n;                 // N = sum_j c_j X_j
  for (int j = 0; j < 4; ++j) {
    BigMatrix4 replaced = mi;
    for (int i = 0; i < 4; ++i) {
      replaced[i][j] = BigInt::from_magnitude(static_cast<std::uint64_t>(std::abs(corner2[i])),
                                              corner2[i] < 0, 0);
    }
    x[j] = determinant(replaced);
    n = n + c_int[j] * x[j];
  }
  for (int j = 0; j < 4; ++j) out.far_corner(j) = exact_quotient<W, W>(x[j], det, -1 - e_m);
  if (n.sign() * det.sign() <= 0) {
    out.outcome = ExactOblique<T, W>::Outcome::plane_misses_view_volume;
    return out;
  }
  out.outcome = ExactOblique<T, W>::Outcome::answered;
  const RowCombination near_combination = near_rows(convention);
  const int k = range.z_high - range.z_low;
  const BigInt two_k_det =
      BigInt::from_magnitude(static_cast<std::uint64_t>(2 * k), false, 0) * det;
  for (int i = 0; i < 4; ++i) {
    // P_i = 2 k D c_i - t m4_i N, in units of 2^e_m / N: m4_i is in M's units, c_i in C's, and
    // the factor 2^(e_c) of C cancels against that of N.
    BigInt p = two_k_det * c_int[i];
    const int t = near_combination.m4;
    if (t != 0 && m_int[12 + i].sign() != 0) {
      const BigInt tm4n = m_int[12 + i] * n;
      p = t > 0 ? p - tm4n : p + tm4n;
    }
    if (near_combination.m3 < 0) p = -p;
    const T entry = exact_quotient<T, W>(p, n, e_m);
    out.row3(i) = entry == T(0) ? T(0) : entry;  // +0, as the plain methods give
  }
  return out;
}

}  // namespace oblique::detail
