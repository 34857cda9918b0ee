// The filtered checker's arithmetic for ViewVolume (view_volume.h): certified double-double
// intervals (certified.h) on M and C scaled by powers of two, with exact signs from integer
// determinants (Cramer's rule, GMP) where a value may be exactly zero. A predicate the intervals
// do not decide throws certified::Undecided, and the caller asks the exact oracle instead.
//
// Signs that may be exactly zero are settled on the integers behind M and C (exact.h's
// to_integers and determinant):
//   sgn C'_k = sgn(Y_k) sgn(D),  sgn C . p = sgn(C' . p') = sgn(sum_k p'_k Y_k) sgn(D),
//   (M^-1 p')_w = sum_j p'_j X_j / D,
// with D = det M, Y_k = det(M with row k replaced by C), X_j = det(M with column 4 replaced by
// e_j).
//
// Scaling: the arithmetic holds M 2^-row_scale() and C 2^-plane_scale() (certified::scaled:
// exactly, or within 2^-1074 for an entry that lands below double's normal range), so every
// quantity is that of the scaled problem, which is the exact one's times a power of two: the
// inverse, the corners and Q times 2^sm, C', C . Q, its corner values and kappa's numerator times
// 2^(sm - sc), the exact row 3 and every row of an answer (scaled alike) times 2^-sm; lambda
// (property 1) times 2^(sc - sm); ratios, Skeel's condition number and eps alike. Only the absolute
// terms (the underflow unit) and the overflow thresholds are not homogeneous: the underflow unit
// enters the bounds on entries of rows as underflow_row() = u_min 2^-sm and those on C . Q as
// underflow_dot() = u_min 2^(sm - sc); at_least_largest() takes the exponent that brings its value
// back.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "oblique/depth_convention.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/oracle/algebra.h"
#include "oblique/oracle/certified.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/plane.h"

namespace oblique::oracle {

namespace filtering {

using certified::Num;
using certified::Undecided;

/// The underflow unit (denorm_min / 2 of T: 2^-150, 2^-1075, 2^-16446) times 2^e, for a quantity
/// held scaled by 2^-e (an interval above 0 below double's range).
template <class T>
Num underflow_unit(int e) {
  return certified::power_of_two(std::numeric_limits<T>::min_exponent -
                                 std::numeric_limits<T>::digits - 1 + e);
}

/// Whether x 2^k >= the largest finite T (or the overflow threshold, the largest plus half an
/// ulp), decided: L 2^-k = 2^top - 2^low, with L = 2^emax (1 - 2^-digits) or 2^emax (1 -
/// 2^-(digits + 1)); beyond double's range a finite interval is below it.
template <class T>
bool at_least_largest(const Num& x, bool overflow_threshold, int k) {
  constexpr int digits = std::numeric_limits<T>::digits;
  const int top = std::numeric_limits<T>::max_exponent - k;
  const int low = top - digits - (overflow_threshold ? 1 : 0);
  constexpr double dmax = std::numeric_limits<double>::max();  // 2^1024 - 2^971
  if (top == 1024 && low >= 971)  // L 2^-k = DBL_MAX - (2^low - 2^971), a double
    return certified::less_equal(
        certified::constant(dmax) - (certified::power_of_two(low) - certified::power_of_two(971)),
        x);
  if (top >= 1024) {  // L 2^-k > DBL_MAX
    if (certified::upper(x) <= dmax) return false;
    throw Undecided{__LINE__};
  }
  return certified::less_equal(certified::power_of_two(top) - certified::power_of_two(low), x);
}

/// The integers behind M and C (GMP: exact.h), and the determinants Cramer's rule needs, each
/// computed once.
template <class T>
class IntegerSigns {
 public:
  IntegerSigns(const Matrix4<T>& m, const Vector4<T>& c) {
    std::array<T, 16> entries;
    for (int i = 0; i < 16; ++i) entries[static_cast<std::size_t>(i)] = m(i / 4, i % 4);
    const std::array<oracle::exact::Integer, 16> mi = oracle::exact::to_integers(entries, e_m_);
    for (int i = 0; i < 16; ++i) m_[i / 4][i % 4] = mi[static_cast<std::size_t>(i)];
    c_ = oracle::exact::to_integers(std::array<T, 4>{c(0), c(1), c(2), c(3)}, e_c_);
  }

  const oracle::exact::Integer& det() {
    if (!det_) det_ = oracle::exact::determinant(m_);
    return *det_;
  }
  int det_sign() { return sgn(det()); }
  /// Y_k = det(M with row k replaced by C) (C' = (Y_0, .., Y_3) / D up to a positive factor).
  const oracle::exact::Integer& y(int k) {
    if (!y_[k]) {
      oracle::exact::IntegerMat replaced = m_;
      replaced[k] = c_;
      y_[k] = oracle::exact::determinant(replaced);
    }
    return *y_[k];
  }
  /// sgn(C'_k).
  int c_clip_sign(int k) { return sgn(y(k)) * det_sign(); }
  /// sgn(C' . p') for integer p'.
  int dot_sign(const std::array<int, 4>& p) {
    oracle::exact::Integer sum;
    for (int k = 0; k < 4; ++k) sum += y(k) * p[k];
    return sgn(sum) * det_sign();
  }
  /// C . Q times 2^scale, as a certified number: N / D 2^(e_c - 1 - e_m) (see row3()).
  Num c_dot_q(const std::array<int, 4>& q_clip2, int scale) {
    const oracle::exact::Integer& n = cramer_n(q_clip2);
    if (sgn(n) == 0) return Num{};
    int e_n = 0, e_d = 0;
    const Num q = certified_top_bits(n, e_n) / certified_top_bits(det(), e_d);
    return q * certified::power_of_two(e_n - e_d + e_c_ - 1 - e_m_ + scale);
  }
  /// Entry i of the exact row 3 times 2^-scale, as a certified number, by Cramer's rule:
  /// M'_3i = sgn(m3) 2^e_m P_i / N with P_i = 2 k D c_i - t m4_i N and N = sum_k (2 Q')_k Y_k
  /// (C . Q = N / D 2^(e_c - 1 - e_m)), k = z_high - z_low, t = near_rows().m4, in the integer
  /// units of M (2^e_m) and C (2^e_c). Precondition: C . Q > 0.
  Num row3(int i, const std::array<int, 4>& q_clip2, int k, const RowCombination& nr, int scale) {
    cramer_n(q_clip2);
    if (!two_k_det_) two_k_det_ = det() * (2 * k);
    oracle::exact::Integer p = *two_k_det_ * c_[i];
    if (nr.m4 != 0 && sgn(m_[3][i]) != 0) p -= m_[3][i] * nr.m4 * *n_;
    if (nr.m3 < 0) p = -p;
    if (sgn(p) == 0) return Num{};
    int e_p = 0, e_n = 0;
    const Num q = certified_top_bits(p, e_p) / certified_top_bits(*n_, e_n);
    return q * certified::power_of_two(e_p - e_n + e_m_ - scale);
  }
  /// N = sum_k (2 Q')_k Y_k.
  const oracle::exact::Integer& cramer_n(const std::array<int, 4>& q_clip2) {
    if (!n_) {
      oracle::exact::Integer n;
      for (int j = 0; j < 4; ++j) n += y(j) * q_clip2[j];
      n_ = n;
    }
    return *n_;
  }
  /// sgn((M^-1 p')_w) for integer p'.
  int w_sign(const std::array<int, 4>& p) {
    oracle::exact::Integer sum;
    for (int j = 0; j < 4; ++j) {
      if (!x_[j]) {
        oracle::exact::IntegerMat replaced = m_;
        for (int i = 0; i < 4; ++i) replaced[i][3] = i == j ? 1 : 0;
        x_[j] = oracle::exact::determinant(replaced);
      }
      sum += *x_[j] * p[j];
    }
    return sgn(sum) * det_sign();
  }

 private:
  /// |x| = (hi + lo) 2^exponent with hi + lo in [1/2, 1), as a certified number with x's sign:
  /// the top 106 bits t of |x| (truncated: the rest is below 2^-106 on this scale) are hi + lo
  /// exactly, hi the top 53 bits of t and lo the rest (both doubles, GMP's conversions truncate).
  /// Precondition: x != 0.
  static Num certified_top_bits(const oracle::exact::Integer& x, int& exponent) {
    constexpr int kBits = 106;
    const int length = static_cast<int>(mpz_sizeinbase(x.get_mpz_t(), 2));
    exponent = length;
    oracle::exact::Integer t;
    mpz_abs(t.get_mpz_t(), x.get_mpz_t());
    const int drop = std::max(0, length - kBits);
    mpz_fdiv_q_2exp(t.get_mpz_t(), t.get_mpz_t(), static_cast<mp_bitcnt_t>(drop));
    const double hi = t.get_d();  // truncated toward zero: t - hi is exact and below 2^53
    const oracle::exact::Integer rest = t - oracle::exact::Integer(hi);
    const double lo = rest.get_d();
    const int shift = drop - length;  // the scale of t's unit
    const double sign = sgn(x);
    const Num sum = certified::constant(sign * std::ldexp(hi, shift)) +
                    certified::constant(sign * std::ldexp(lo, shift));
    return Num{sum.hi, sum.lo, sum.err + (drop > 0 ? std::ldexp(1.0, -kBits) : 0.0)};
  }

  oracle::exact::IntegerMat m_;
  std::array<oracle::exact::Integer, 4> c_;
  int e_m_ = 0, e_c_ = 0;
  std::optional<oracle::exact::Integer> det_, n_, two_k_det_;
  std::array<std::optional<oracle::exact::Integer>, 4> y_, x_;
};

}  // namespace filtering

template <class T>
class CertifiedArithmetic {
 public:
  using Num = certified::Num;
  using Magnitude = certified::Range;
  using Mat = algebra::Mat<Num>;

  CertifiedArithmetic(const Matrix4<T>& m, const Vector4<T>& c)
      : m_(m), c_(c), sm_(largest_exponent(m)), sc_(largest_exponent(c)) {}

  /// The exponent of the largest |entry| (0 when all are 0): the power of two M and C are scaled
  /// by.
  template <class V>
  static int largest_exponent(const V& v) {
    if (!all_finite(v)) return 0;
    const T largest = v.cwiseAbs().maxCoeff();
    return largest == T(0) ? 0 : std::ilogb(largest);
  }

  int row_scale() const { return sm_; }
  int plane_scale() const { return sc_; }
  Num matrix_entry(T x) const { return certified::scaled(x, -sm_); }
  Num plane_entry(T x) const { return certified::scaled(x, -sc_); }
  Num underflow_row() const { return filtering::underflow_unit<T>(-sm_); }
  Num underflow_dot() const { return filtering::underflow_unit<T>(sm_ - sc_); }

  static Num constant(double x) { return certified::constant(x); }
  static Num gamma(int n) {
    const Num nu = certified::constant(n * std::ldexp(1.0, -tolerance::precision_bits<T>()));
    return nu / (certified::constant(1) - nu);
  }
  static Num unit_roundoff() {
    return certified::constant(std::ldexp(1.0, -tolerance::precision_bits<T>()));
  }
  static Num abs(const Num& x) { return certified::abs(x); }
  static bool less_equal(const Num& x, const Num& y) { return certified::less_equal(x, y); }
  static bool less(const Num& x, const Num& y) { return certified::less(x, y); }

  static Magnitude magnitude(const Num& x) { return certified::magnitude_of(x); }
  static Magnitude magnitude_constant(double x) { return Magnitude{x, x}; }
  static Num as_num(const Magnitude& x) { return certified::as_num(x); }
  static bool some_at_least(const algebra::Vec<Magnitude>& v, double t) {
    bool decided = true;
    for (const Magnitude& r : v) {
      if (r.lo >= t) return true;
      if (!(r.hi < t)) decided = false;
    }
    if (!decided) throw filtering::Undecided{__LINE__};
    return false;
  }
  static bool at_least_largest(const Num& x, bool overflow_threshold, int k) {
    return filtering::at_least_largest<T>(x, overflow_threshold, k);
  }

  /// Gauss-Jordan with partial pivoting on the intervals; empty when M is exactly singular.
  std::optional<Mat> inverse(Mat a) const {
    Mat inv;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) inv[i][j] = certified::constant(i == j ? 1 : 0);
    }
    for (int col = 0; col < 4; ++col) {
      int pivot = col;
      for (int row = col + 1; row < 4; ++row) {
        if (std::fabs(a[row][col].hi) > std::fabs(a[pivot][col].hi)) pivot = row;
      }
      const Num& pv = a[pivot][col];
      const bool certain = pv.hi != 0 && pv.err * 4 <= std::fabs(pv.hi);
      if (!certain) {
        if (integers().det_sign() == 0) return std::nullopt;
        throw filtering::Undecided{__LINE__};
      }
      std::swap(a[pivot], a[col]);
      std::swap(inv[pivot], inv[col]);
      const Num p = a[col][col];
      for (int j = 0; j < 4; ++j) {
        a[col][j] = a[col][j] / p;
        inv[col][j] = inv[col][j] / p;
      }
      for (int row = 0; row < 4; ++row) {
        const Num f = a[row][col];
        if (row == col || certified::is_exact_zero(f)) continue;
        for (int j = 0; j < 4; ++j) {
          a[row][j] = a[row][j] - f * a[col][j];
          inv[row][j] = inv[row][j] - f * inv[col][j];
        }
      }
    }
    return inv;
  }

  int plane_sign(const Num& x, int k) const {
    return sign_or_exact(x, [&] { return integers().c_clip_sign(k); });
  }
  int clip_dot_sign(const Num& x, const std::array<int, 4>& p) const {
    return sign_or_exact(x, [&] { return integers().dot_sign(p); });
  }
  int w_sign(const Num& x, const std::array<int, 4>& p) const {
    return sign_or_exact(x, [&] { return integers().w_sign(p); });
  }
  /// Where C . Q's interval is too wide to divide by (C . Q cancelling), a tighter one from the
  /// integers (the same exact value, 2^(sm - sc) C . Q).
  void refine_corner_dot(Num& d, const std::array<int, 4>& q_clip2) const {
    if (!(d.err * 4 <= std::fabs(d.hi))) d = integers().c_dot_q(q_clip2, sm_ - sc_);
  }

  /// The integers behind M and C (built on first use).
  filtering::IntegerSigns<T>& integers() const {
    if (!integers_) integers_.emplace(m_, c_);
    return *integers_;
  }

 private:
  template <class Exact>
  static int sign_or_exact(const Num& x, Exact exact) {
    int s = 0;
    return certified::sign_known(x, s) ? s : exact();
  }

  Matrix4<T> m_;
  Vector4<T> c_;
  int sm_ = 0, sc_ = 0;
  mutable std::optional<filtering::IntegerSigns<T>> integers_;
};

}  // namespace oblique::oracle
