// The filtered checker: the same judgement as judge() on a Problem (problem.h, the exact
// oracle), decided first in certified double-double arithmetic (certified.h), with exact signs
// from integer determinants where a value may be exactly zero, and the exact GMP Problem built
// only when neither decides.
//
// FilteredProblem<T> mirrors Problem<T>'s quantities (the inverse by Gauss-Jordan with partial
// pivoting, C' = M^-T C, the eight corners, Q, C . Q, kappa, the Skeel condition number, the exact
// row 3) as certified intervals. Signs that may be exactly zero are settled by Cramer's rule on
// the integers behind M and C (GMP, exact.h's to_integers and determinant):
//   sgn C'_k = sgn(Y_k) sgn(D),  sgn C . p = sgn(C' . p') = sgn(sum_k p'_k Y_k) sgn(D),
//   (M^-1 p')_w = sum_j p'_j X_j / D,
// with D = det M, Y_k = det(M with row k replaced by C), X_j = det(M with column 4 replaced by
// e_j). A status decision, a property, the row-3 accuracy test or the ulps promise that the
// intervals do not settle throws certified::Undecided; so does any check that fails. judge() on a
// FilteredProblem then returns judge() on the exact Problem: every violation, and every close
// call, is the exact checker's own finding, word for word. Where the filter decides that every
// check holds, the findings are the exact checker's (kind, holds, relation) with the residual
// sides left out ("certified") and the ratio approximate (`every`, which lists residuals, always
// goes to the exact checker).
//
// tests/filtered_checker_test.cpp runs both checkers on generated cases and wrong answers and
// fails on any disagreement.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "oblique/numeric/magnitudes.h"
#include "oblique/oracle/certified.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"

namespace oblique::oracle {

namespace filtering {

using certified::Num;
using certified::Undecided;

/// The tolerance constants of tolerance.h as certified intervals.
template <class T>
struct Constants {
  int p = oracle::tolerance::precision_bits<T>();
  Num entry_gamma, scale_gamma;
  Num unit_roundoff;

  Constants() {
    unit_roundoff = certified::constant(std::ldexp(1.0, -p));
    entry_gamma = gamma(oracle::tolerance::kEntryRoundings);
    scale_gamma = gamma(oracle::tolerance::kScaleRoundings);
  }
  /// The underflow unit (denorm_min / 2 of T: 2^-150, 2^-1075, 2^-16446) times 2^e, for a
  /// quantity the filter holds scaled by 2^-e (an interval above 0 below double's range).
  static Num underflow_unit(int e) {
    return certified::power_of_two(std::numeric_limits<T>::min_exponent -
                                   std::numeric_limits<T>::digits - 1 + e);
  }
  Num gamma(int n) const {
    const Num nu = certified::constant(n * std::ldexp(1.0, -p));
    return nu / (certified::constant(1) - nu);
  }
};

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

using NumVec = std::array<Num, 4>;

inline Num dot(const NumVec& a, const NumVec& b) {
  Num s;
  bool first = true;
  for (int i = 0; i < 4; ++i) {
    if (certified::is_exact_zero(a[i]) || certified::is_exact_zero(b[i])) continue;
    s = first ? a[i] * b[i] : s + a[i] * b[i];
    first = false;
  }
  return s;
}

using RangeVec = std::array<certified::Range, 4>;
inline RangeVec magnitudes(const NumVec& v) {
  return {certified::magnitude_of(v[0]), certified::magnitude_of(v[1]),
          certified::magnitude_of(v[2]), certified::magnitude_of(v[3])};
}
inline certified::Range dot(const RangeVec& a, const RangeVec& b) {
  certified::Range s;
  for (int i = 0; i < 4; ++i) s = s + a[i] * b[i];
  return s;
}
inline RangeVec mul(const std::array<RangeVec, 4>& m, const RangeVec& v) {
  return {dot(m[0], v), dot(m[1], v), dot(m[2], v), dot(m[3], v)};
}
/// v . p' for p' with entries -1, 0 or 1: a signed sum, no products.
inline Num signed_sum(const NumVec& v, const std::array<int, 4>& p) {
  Num s;
  bool first = true;
  for (int j = 0; j < 4; ++j) {
    if (p[j] == 0 || certified::is_exact_zero(v[j])) continue;
    const Num term = p[j] > 0 ? v[j] : -v[j];
    s = first ? term : s + term;
    first = false;
  }
  return s;
}

/// M^-1 p' for p' with entries -1, 0 or 1: sums of columns, no products.
inline NumVec signed_column_sum(const std::array<NumVec, 4>& m, const std::array<int, 4>& p) {
  return {signed_sum(m[0], p), signed_sum(m[1], p), signed_sum(m[2], p), signed_sum(m[3], p)};
}
inline NumVec abs(const NumVec& v) {
  return {certified::abs(v[0]), certified::abs(v[1]), certified::abs(v[2]), certified::abs(v[3])};
}
inline NumVec mul(const std::array<NumVec, 4>& m, const NumVec& v) {
  return {dot(m[0], v), dot(m[1], v), dot(m[2], v), dot(m[3], v)};
}
inline NumVec combine(const Num& a, const NumVec& x, const Num& b, const NumVec& y) {
  NumVec out;
  for (int i = 0; i < 4; ++i) out[i] = a * x[i] + b * y[i];
  return out;
}
inline NumVec integers(const std::array<int, 4>& p) {
  return {certified::constant(p[0]), certified::constant(p[1]), certified::constant(p[2]),
          certified::constant(p[3])};
}

}  // namespace filtering

/// A Problem whose status decisions and judgements are filtered (see the top of this file); the
/// exact Problem is built on first use (exact()).
template <class T>
class FilteredProblem {
 public:
  /// Runs the filter on (M, C) in `convention` (out of the class: compiled once in
  /// oblique::properties, OBLIQUE_CHECKER_INSTANCES).
  FilteredProblem(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);

  /// The exact Problem (built now if not yet).
  const Problem<T>& exact() const {
    if (!exact_) exact_.emplace(m_, c_, convention_);
    return *exact_;
  }
  /// Whether the filter decided the statuses (otherwise every question goes to exact()).
  bool statuses_decided() const { return decided_; }
  /// The source line (in filtered.h or certified.h) where the filter last gave up, or 0.
  int undecided_at() const { return undecided_at_; }

  Status exact_status() const { return decided_ ? status_ : exact().exact_status(); }
  std::vector<Status> acceptable_statuses() const {
    return decided_ ? acceptable_ : exact().acceptable_statuses();
  }
  Convention convention() const { return convention_; }
  const Matrix4<T>& matrix() const { return m_; }
  const Vector4<T>& plane() const { return c_; }

  /// The judgement of `outcome` when the filter decides that every check holds; empty when a
  /// check fails or the filter cannot decide (then judge() asks the exact Problem).
  std::optional<Judgement> filtered_judgement(const Answer<T>& outcome,
                                              const Checks& checks) const {
    if (!decided_ || checks.every) return std::nullopt;
    try {
      return judge_holding(outcome, checks);
    } catch (const filtering::Undecided& u) {
      undecided_at_ = u.line;
      return std::nullopt;
    }
  }

 private:
  using Num = filtering::Num;
  using NumVec = filtering::NumVec;

  static int far_z(Convention convention) {
    const DepthRange range = clip_depth_range(convention);
    return convention == Convention::reversed_z ? range.z_low : range.z_high;
  }

  // Problem's constructor, exact_status() and acceptable_statuses(), certified.
  void build() {
    namespace cert = certified;
    finite_ = all_finite(m_) && all_finite(c_);
    if (!finite_) {
      status_ = Status::invalid_input;
      acceptable_ = {status_};
      return;
    }
    const bool too_spread = magnitude_spread(m_) > max_magnitude_spread<T>();
    // M and C scaled by 2^-sm_ and 2^-sc_ (their largest entries in [1, 2)); see "Scaling" at
    // the members.
    sm_ = largest_exponent(m_);
    sc_ = largest_exponent(c_);
    for (int i = 0; i < 4; ++i) {
      cx_[i] = cert::scaled(c_(i), -sc_);
      for (int j = 0; j < 4; ++j) mx_[i][j] = cert::scaled(m_(i, j), -sm_);
    }
    underflow_row_ = filtering::Constants<T>::underflow_unit(-sm_);
    underflow_dot_ = filtering::Constants<T>::underflow_unit(sm_ - sc_);
    invertible_ = invert();
    if (!invertible_) {
      status_ = Status::singular_projection;
      acceptable_ = {status_};
      if (too_spread) acceptable_.push_back(Status::out_of_range);
      return;
    }
    // C' = M^-T C, its signs exact.
    for (int k = 0; k < 4; ++k) {
      Num s;
      for (int j = 0; j < 4; ++j) s = s + inverse_[j][k] * cx_[j];
      c_clip_[k] = s;
    }
    for (int k = 0; k < 3; ++k) {
      c_clip_sign_[k] = sign_or_exact(c_clip_[k], [&] { return integers().c_clip_sign(k); });
      if (c_clip_sign_[k] == 0) c_clip_[k] = Num{};
    }
    const DepthRange range = clip_depth_range(convention_);
    int index = 0;
    for (int x : {-1, 1}) {
      for (int y : {-1, 1}) {
        for (int z : {range.z_low, range.z_high}) {
          clip_corners_[index] = {x, y, z, 1};
          corners_[index] = filtering::signed_column_sum(inverse_, clip_corners_[index]);
          corner_dots_[index] = filtering::signed_sum(c_clip_, clip_corners_[index]);
          const std::array<int, 4> p = clip_corners_[index];
          corner_sign_[index] =
              sign_or_exact(corner_dots_[index], [&] { return integers().dot_sign(p); });
          if (corner_sign_[index] == 0) corner_dots_[index] = Num{};
          ++index;
        }
      }
    }
    // Q' (twice, in integers: the middle of the depth range may be a half).
    const int sz = c_clip_sign_[2];
    q_clip2_ = {2 * c_clip_sign_[0], 2 * c_clip_sign_[1],
                sz > 0 ? 2 * range.z_high : (sz < 0 ? 2 * range.z_low : range.z_low + range.z_high),
                2};
    NumVec q_clip;
    for (int i = 0; i < 4; ++i) q_clip[i] = cert::constant(q_clip2_[i] * 0.5);
    q_ = filtering::mul(inverse_, q_clip);
    d_ = filtering::dot(cx_, q_);
    infinite_ = true;
    for (int i = 0; i < 8 && infinite_; ++i) {
      if (clip_corners_[i][2] != far_z(convention_)) continue;
      const std::array<int, 4> p = clip_corners_[i];
      if (sign_or_exact(corners_[i][3], [&] { return integers().w_sign(p); }) != 0)
        infinite_ = false;
      else
        corners_[i][3] = Num{};
    }
    far_at_infinity_ = infinite_ && q_clip2_[2] == 2 * far_z(convention_);
    // Q on the far face at infinity is an affine combination of corners with w = 0.
    if (far_at_infinity_) q_[3] = Num{};
    // kappa's numerator and Skeel's row sums: sums of products of magnitudes, as ranges.
    std::array<filtering::RangeVec, 4> abs_m, abs_inv;
    for (int i = 0; i < 4; ++i) {
      abs_m[i] = filtering::magnitudes(mx_[i]);
      abs_inv[i] = filtering::magnitudes(inverse_[i]);
    }
    const filtering::RangeVec abs_c = filtering::magnitudes(cx_), abs_q = filtering::magnitudes(q_);
    filtering::RangeVec abs_q_clip;
    for (int i = 0; i < 4; ++i) {
      const double v = std::abs(q_clip2_[i]) * 0.5;
      abs_q_clip[i] = cert::Range{v, v};
    }
    kappa_numerator_ =
        cert::as_num(filtering::dot(abs_c, abs_q) +
                     filtering::dot(abs_c, filtering::mul(abs_inv, filtering::mul(abs_m, abs_q))) +
                     filtering::dot(filtering::magnitudes(c_clip_),
                                    filtering::mul(abs_m, filtering::mul(abs_inv, abs_q_clip))));
    const bool camera_behind = c_(3) < T(0);
    // The sign of C . Q = C' . Q' (exact from the integers where the interval holds 0).
    if (camera_behind) {
      const int d_sign = sign_or_exact(d_, [&] { return integers().dot_sign(q_clip2_); });
      if (d_sign == 0) d_ = Num{};
      d_positive_ = d_sign > 0;
      // Where the interval is too wide to divide by (C . Q cancelling), a tighter one from the
      // integers (the same exact value, 2^(sm_ - sc_) C . Q).
      if (d_positive_ && !(d_.err * 4 <= std::fabs(d_.hi)))
        d_ = integers().c_dot_q(q_clip2_, sm_ - sc_);
    }
    status_ = !camera_behind ? Status::camera_not_behind_plane
              : !d_positive_ ? Status::plane_misses_view_volume
                             : Status::ok;

    // acceptable_statuses(), in its order.
    acceptable_ = {status_};
    auto add = [this](Status s) {
      if (std::find(acceptable_.begin(), acceptable_.end(), s) == acceptable_.end())
        acceptable_.push_back(s);
    };
    if (too_spread) add(Status::out_of_range);
    // Skeel's condition number (its double, truncated) times 256 eps >= 1, i.e. some row sum of
    // |M^-1| |M| 1 at least 2^(p - 9).
    const cert::Range one{1, 1};
    const filtering::RangeVec row_sums =
        filtering::mul(abs_inv, filtering::mul(abs_m, filtering::RangeVec{one, one, one, one}));
    const double skeel_threshold = std::ldexp(1.0, constants_.p - 9);
    bool skeel_decided = true, skeel_large = false;
    for (const cert::Range& r : row_sums) {
      if (r.lo >= skeel_threshold)
        skeel_large = true;
      else if (!(r.hi < skeel_threshold))
        skeel_decided = false;
    }
    if (!skeel_large && !skeel_decided) throw filtering::Undecided{__LINE__};
    if (skeel_large) add(Status::singular_projection);
    if (!camera_behind) return;
    const Num d_error = constants_.scale_gamma * kappa_numerator_ +
                        cert::constant(oracle::tolerance::kScaleRoundings) * underflow_dot_;
    const bool d_unresolved = cert::less_equal(cert::abs(d_), d_error);
    if (d_unresolved) {
      add(Status::plane_misses_view_volume);
      add(Status::ok);
      add(Status::out_of_range);
    }
    if (d_positive_) row3_ = exact_row3();
    // biggest_corner * 256 >= largest: some |entry| of Q, of the exact row 3 or of a far-corner
    // candidate.
    const Num f256 = cert::constant(256);
    bool near_overflow = false;
    auto big = [&](const Num& v, int k) {
      if (!near_overflow && filtering::at_least_largest<T>(cert::abs(v) * f256, false, k))
        near_overflow = true;
    };
    for (const Num& v : q_) big(v, -sm_);
    if (d_positive_) {
      for (const Num& v : row3_) big(v, sm_);
    }
    for (int i = 0; i < 8; ++i) {
      if (!is_far_corner_candidate(i)) continue;
      for (const Num& v : corners_[i]) big(v, -sm_);
    }
    if (near_overflow) add(Status::out_of_range);
    if (d_positive_) {
      const RowCombination nr = near_rows(convention_);
      const Num a = cert::constant(range.z_high - range.z_low) / d_;
      Num noise;
      for (int i = 0; i < 4; ++i) {
        noise = noise + (cert::constant(4) * constants_.unit_roundoff *
                             cert::abs(cert::constant(nr.m4) * mx_[3][i]) +
                         cert::constant(4) * underflow_row_) *
                            cert::abs(cx_[i]);
      }
      if (cert::less_equal(a * filtering::dot(cx_, cx_), noise)) add(Status::out_of_range);
    }
    if (d_positive_ && !d_unresolved) {
      bool overflows = false;
      for (const Num& v : q_)
        overflows = overflows || filtering::at_least_largest<T>(cert::abs(v), true, -sm_);
      for (const Num& v : row3_)
        overflows = overflows || filtering::at_least_largest<T>(cert::abs(v), true, sm_);
      if (overflows)
        acceptable_.erase(std::remove(acceptable_.begin(), acceptable_.end(), Status::ok),
                          acceptable_.end());
    }
  }

  /// Gauss-Jordan with partial pivoting on the intervals; false when M is exactly singular.
  bool invert() {
    std::array<NumVec, 4> a = mx_;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) inverse_[i][j] = certified::constant(i == j ? 1 : 0);
    }
    for (int col = 0; col < 4; ++col) {
      int pivot = col;
      for (int row = col + 1; row < 4; ++row) {
        if (std::fabs(a[row][col].hi) > std::fabs(a[pivot][col].hi)) pivot = row;
      }
      const Num& pv = a[pivot][col];
      const bool certain = pv.hi != 0 && pv.err * 4 <= std::fabs(pv.hi);
      if (!certain) {
        if (integers().det_sign() == 0) return false;
        throw filtering::Undecided{__LINE__};
      }
      std::swap(a[pivot], a[col]);
      std::swap(inverse_[pivot], inverse_[col]);
      const Num p = a[col][col];
      for (int j = 0; j < 4; ++j) {
        a[col][j] = a[col][j] / p;
        inverse_[col][j] = inverse_[col][j] / p;
      }
      for (int row = 0; row < 4; ++row) {
        const Num f = a[row][col];
        if (row == col || (f.hi == 0 && f.lo == 0 && f.err == 0)) continue;
        for (int j = 0; j < 4; ++j) {
          a[row][j] = a[row][j] - f * a[col][j];
          inverse_[row][j] = inverse_[row][j] - f * inverse_[col][j];
        }
      }
    }
    return true;
  }

  template <class Exact>
  static int sign_or_exact(const Num& x, Exact exact) {
    int s = 0;
    return certified::sign_known(x, s) ? s : exact();
  }

  filtering::IntegerSigns<T>& integers() const {
    if (!integers_) integers_.emplace(m_, c_);
    return *integers_;
  }

  bool is_far_corner_candidate(int i) const {
    for (int k = 0; k < 3; ++k) {
      if (c_clip_sign_[k] != 0 && 2 * clip_corners_[i][k] != q_clip2_[k]) return false;
    }
    return true;
  }

  NumVec exact_row3() const {
    const DepthRange range = clip_depth_range(convention_);
    const RowCombination nr = near_rows(convention_);
    const Num a = certified::constant(range.z_high - range.z_low) / d_;
    return filtering::combine(certified::constant(nr.m3) * a, cx_,
                              certified::constant(-nr.m3 * nr.m4), mx_[3]);
  }

  /// scale_error(): empty when eps >= 1.
  std::optional<Num> scale_error() const {
    const Num eps = constants_.scale_gamma * (kappa_numerator_ / d_) +
                    certified::constant(oracle::tolerance::kScaleRoundings) * underflow_dot_ / d_;
    if (!certified::less(eps, certified::constant(1))) return std::nullopt;
    return eps / (certified::constant(1) - eps);
  }

  // judge() when every check holds; throws Undecided otherwise.
  Judgement judge_holding(const Answer<T>& outcome, const Checks& checks) const {
    namespace cert = certified;
    Judgement out;
    if (judging::status_finding(status_, acceptable_, outcome.status, checks.statuses))
      throw filtering::Undecided{__LINE__};  // a status violation: the exact checker reports it
    if (outcome.status != Status::ok) return out;
    const Matrix4<T>& result = outcome.projection;
    if (!all_finite(result)) throw filtering::Undecided{__LINE__};
    if (status_ != Status::ok) return out;
    auto wanted = [&](Property p) {
      return std::find(checks.properties.begin(), checks.properties.end(), p) !=
             checks.properties.end();
    };
    auto holding = [&](Check check, double ratio) {
      Finding f;
      f.check = check;
      f.holds = true;
      f.shows = Shows::certified;
      f.ratio = ratio;
      out.checks.push_back(std::move(f));
    };
    const bool any_of_the_five = std::any_of(std::begin(all_properties), std::end(all_properties),
                                             [&](Property p) { return wanted(p); });
    if (any_of_the_five) {
      std::array<NumVec, 4> r;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) r[i][j] = cert::scaled(result(i, j), -sm_);
      }
      const RowCombination nr = near_rows(convention_), fr = far_rows(convention_);
      const NumVec& m4 = mx_[3];
      const NumVec near =
          filtering::combine(cert::constant(nr.m3), r[2], cert::constant(nr.m4), r[3]);
      const NumVec far =
          filtering::combine(cert::constant(fr.m3), r[2], cert::constant(fr.m4), r[3]);
      const Num& g = constants_.entry_gamma;
      const Num t_near = cert::constant(1);  // row 3's own error, as the exact checker's
      const Num underflow = cert::constant(oracle::tolerance::kEntryRoundings) * underflow_row_;
      // 1. The interval test: every entry's lower bound on lambda below every upper bound, and
      //    every upper bound above 0 (there is one: C_w < 0). Each entry's bounds are formed in
      //    its own scale (near'_i and M4_i by 2^-e_i, C_i by 2^-f_i, so an entry far below the
      //    others keeps its bits): lows_i = low_i 2^k_i, k_i = e_i - f_i.
      std::array<Num, 4> lows, highs;
      std::array<int, 4> k{};
      std::array<bool, 4> bounded{};
      for (int i = 0; i < 4; ++i) {
        const T entries[] = {result(2, i), result(3, i), m_(3, i)};
        T largest = 0;
        for (T x : entries) largest = std::max(largest, T(std::fabs(x)));
        const int e = largest == T(0) ? 0 : std::ilogb(largest);
        const Num y_i = cert::constant(nr.m3) * cert::scaled(result(2, i), -e) +
                        cert::constant(nr.m4) * cert::scaled(result(3, i), -e);
        const Num b = g * t_near * cert::abs(cert::scaled(m_(3, i), -e)) +
                      cert::constant(oracle::tolerance::kEntryRoundings) *
                          filtering::Constants<T>::underflow_unit(-e);
        if (c_(i) == T(0)) {
          if (!cert::within(cert::abs(y_i), b)) throw filtering::Undecided{__LINE__};
          continue;
        }
        const int f = std::ilogb(c_(i));
        const Num c = cert::abs(cert::scaled(c_(i), -f));
        const Num y = c_(i) > T(0) ? y_i : -y_i;
        lows[i] = (y - b) / (c * (cert::constant(1) + g));
        highs[i] = (y + b) / (c * (cert::constant(1) - g));
        k[i] = e - f;
        bounded[i] = true;
      }
      // x 2^kx <= y 2^ky, the one with the larger exponent scaled down to the other's.
      auto less_equal_scaled = [](const Num& x, int kx, const Num& y, int ky) {
        return kx >= ky ? cert::less_equal(x, cert::times_power_of_two(y, ky - kx))
                        : cert::less_equal(cert::times_power_of_two(x, kx - ky), y);
      };
      int common = std::numeric_limits<int>::min();  // lambda's exponent: the largest k_j
      for (int j = 0; j < 4; ++j) {
        if (!bounded[j]) continue;
        if (!cert::positive(highs[j])) throw filtering::Undecided{__LINE__};
        for (int i = 0; i < 4; ++i) {
          if (bounded[i] && !less_equal_scaled(lows[i], k[i], highs[j], k[j]))
            throw filtering::Undecided{__LINE__};
        }
        common = std::max(common, k[j]);
      }
      if (common == std::numeric_limits<int>::min()) throw filtering::Undecided{__LINE__};
      Num lambda_low = Num{}, lambda_high;
      bool has_high = false;
      for (int j = 0; j < 4; ++j) {
        if (!bounded[j]) continue;
        const Num low = cert::times_power_of_two(lows[j], k[j] - common);
        const Num high = cert::times_power_of_two(highs[j], k[j] - common);
        lambda_low = cert::larger_of(lambda_low, low);
        lambda_high = has_high ? cert::smaller_of(lambda_high, high) : high;
        has_high = true;
      }
      // lambda 2^common; lambda C_i in the units of the rows (2^sm_).
      const Num lambda = (lambda_low + lambda_high) * cert::constant(0.5);
      NumVec lambda_c;
      for (int i = 0; i < 4; ++i) {
        if (c_(i) == T(0)) continue;
        const int f = std::ilogb(c_(i));
        lambda_c[i] = cert::times_power_of_two(lambda * cert::scaled(c_(i), -f), common + f - sm_);
      }
      NumVec entry_bound;
      double p1_worst = 0;
      for (int i = 0; i < 4; ++i) {
        entry_bound[i] = g * (cert::abs(lambda_c[i]) + t_near * cert::abs(m4[i])) + underflow;
        const double bound = cert::approx(entry_bound[i]);
        if (bound > 0)
          p1_worst = std::max(p1_worst, std::fabs(cert::approx(near[i] - lambda_c[i])) / bound);
      }
      // 2. Rows 1, 2, 4 equal in value (-0 equals +0), as the exact checker has them; anything
      //    else (a changed entry, a NaN) goes to the exact checker.
      for (int row : {0, 1, 3}) {
        for (int j = 0; j < 4 && wanted(Property::side_rows_unchanged); ++j) {
          const T before = m_(row, j), after = result(row, j);
          if (!(before == after)) throw filtering::Undecided{__LINE__};
        }
      }
      // Property 3 to 5's bounds.
      const DepthRange range = clip_depth_range(convention_);
      const std::optional<Num> scale = scale_error();
      const bool corners_judged = scale.has_value();
      const Num scale_term =
          corners_judged ? cert::constant(range.z_high - range.z_low) * *scale : Num{};
      const cert::Range scale_range = cert::magnitude_of(scale_term);
      filtering::RangeVec twice_entry_bound;
      for (int i = 0; i < 4; ++i) {
        const cert::Range e = cert::magnitude_of(entry_bound[i]);
        twice_entry_bound[i] = cert::Range{2 * e.lo, 2 * e.hi};
      }
      auto point_bound = [&](const NumVec& point, bool through_scale) {
        const cert::Range b = filtering::dot(twice_entry_bound, filtering::magnitudes(point));
        return cert::as_num(through_scale ? scale_range + b : b);
      };
      const Num far_q = filtering::dot(far, q_);
      const Num far_q_bound = point_bound(q_, true);
      const bool far_q_holds = cert::within(cert::abs(far_q), far_q_bound);
      const double far_q_ratio = cert::approx(far_q_bound) > 0
                                     ? std::fabs(cert::approx(far_q)) / cert::approx(far_q_bound)
                                     : 0.0;
      // 4. far' . p >= -bound at every vertex.
      double p4_worst = 0;
      auto visit = [&](const NumVec& point, bool through_scale) {
        const Num value = filtering::dot(far, point);
        const Num bound = point_bound(point, through_scale);
        if (!cert::within(-value, bound)) throw filtering::Undecided{__LINE__};
        if (cert::approx(value) < 0 && cert::approx(bound) > 0)
          p4_worst = std::max(p4_worst, -cert::approx(value) / cert::approx(bound));
      };
      const bool p4 = wanted(Property::no_clipping);
      for (int i = 0; i < 8 && p4; ++i) {
        if (corners_judged && corner_sign_[i] >= 0) visit(corners_[i], true);
        for (int j = i + 1; j < 8; ++j) {
          int differing = 0;
          for (int axis = 0; axis < 3; ++axis)
            differing += clip_corners_[i][axis] != clip_corners_[j][axis];
          if (differing != 1 || corner_sign_[i] * corner_sign_[j] >= 0) continue;
          const Num alpha = corner_dots_[j] / (corner_dots_[j] - corner_dots_[i]);
          visit(filtering::combine(alpha, corners_[i], cert::constant(1) - alpha, corners_[j]),
                false);
        }
      }
      const bool p5_applies = far_at_infinity_ && corners_judged;
      for (Property p : all_properties) {
        if (!wanted(p)) continue;
        switch (p) {
          case Property::near_is_clip_plane: holding(check_of(p), std::min(p1_worst, 1.0)); break;
          case Property::side_rows_unchanged: holding(check_of(p), 0); break;
          case Property::far_plane_through_corner:
            if (!corners_judged) break;
            if (!far_q_holds) throw filtering::Undecided{__LINE__};
            holding(check_of(p), far_q_ratio);
            break;
          case Property::no_clipping: holding(check_of(p), p4_worst); break;
          case Property::infinite_edge_parallel:
            if (!p5_applies) break;
            if (!far_q_holds) throw filtering::Undecided{__LINE__};
            holding(check_of(p), far_q_ratio);
            break;
          default: break;
        }
      }
    }
    if (wanted(Property::extracted_planes_match)) {
      const FrustumPlanes<T> before = frustum_planes(m_, convention_);
      const FrustumPlanes<T> after = frustum_planes(result, convention_);
      const Vector4<T> sides_before[] = {before.left, before.right, before.bottom, before.top};
      const Vector4<T> sides_after[] = {after.left, after.right, after.bottom, after.top};
      for (int i = 0; i < 4; ++i) {
        if (!(sides_after[i] == sides_before[i])) throw filtering::Undecided{__LINE__};
      }
      if (!all_finite(after.near_plane)) throw filtering::Undecided{__LINE__};
      NumVec n;
      // Only the sign of n . C counts: n scaled by its own power of two.
      const int sn = largest_exponent(after.near_plane);
      for (int i = 0; i < 4; ++i) n[i] = cert::scaled(T(after.near_plane(i)), -sn);
      if (!cert::positive(filtering::dot(n, cx_))) throw filtering::Undecided{__LINE__};
      holding(Check::extracted_planes_match, 0);
    }
    if (checks.row3_accuracy) {
      const std::optional<Num> scale = scale_error();
      double worst = 0;
      if (scale) {
        const DepthRange range = clip_depth_range(convention_);
        const Num a = cert::constant(range.z_high - range.z_low) / d_;
        for (int i = 0; i < 4; ++i) {
          const Num ac = cert::abs(a * cx_[i]);
          const Num bound = constants_.entry_gamma * (ac + cert::abs(mx_[3][i])) + ac * *scale +
                            cert::constant(oracle::tolerance::kEntryRoundings) * underflow_row_;
          const Num error = cert::abs(cert::scaled(result(2, i), -sm_) - row3_[i]);
          if (!cert::within(error, bound)) throw filtering::Undecided{__LINE__};
          if (cert::approx(bound) > 0)
            worst = std::max(worst, cert::approx(error) / cert::approx(bound));
        }
      }
      holding(Check::row3_accuracy, worst);
    }
    if (checks.max_ulps < std::numeric_limits<double>::infinity()) {
      // Rows 1, 2, 4 are M's own (0 ulp when equal); row 3 against the exact value's rounding,
      // known when the interval lies strictly between the midpoints around one T value, or one of
      // two neighbours when it holds the midpoint between them (a tie, as simple inputs give):
      // then the entry must be within max_ulps of both. The
      // checker's figure is the double of gap / quantum, truncated: it is <= max_ulps exactly when
      // gap < next(max_ulps) quantum.
      for (int row : {0, 1, 3}) {
        for (int j = 0; j < 4; ++j) {
          if (!(result(row, j) == m_(row, j))) throw filtering::Undecided{__LINE__};
        }
      }
      const double limit = std::nextafter(checks.max_ulps, std::numeric_limits<double>::infinity());
      double worst = 0;
      for (int j = 0; j < 4; ++j) {
        const Roundings roundings = roundings_or_exact(j);
        for (int k = 0; k < roundings.count; ++k) {
          const T rounded = roundings.value[k];
          if (result(2, j) == rounded) continue;  // 0 ulp
          constexpr int digits = std::numeric_limits<T>::digits;
          const int lowest = std::numeric_limits<T>::min_exponent - digits;
          const int quantum_exponent =
              rounded == T(0) ? lowest : std::max(std::ilogb(rounded) - digits + 1, lowest);
          if (quantum_exponent - sm_ < -1074) throw filtering::Undecided{__LINE__};
          const Num quantum = cert::power_of_two(quantum_exponent - sm_);
          const Num gap = cert::abs(cert::scaled(result(2, j), -sm_) - cert::scaled(rounded, -sm_));
          if (!cert::less(gap, cert::constant(limit) * quantum))
            throw filtering::Undecided{__LINE__};
          worst = std::max(worst, cert::approx(gap) / cert::approx(quantum));
        }
      }
      holding(Check::accurate_ulps, worst / checks.max_ulps);
      out.checks.back().residual = worst;
      out.checks.back().bound = checks.max_ulps;
    }
    return out;
  }

  /// What the exact value x 2^e stands for may round to (to nearest T, ties to even): one value
  /// where the interval lies strictly between the midpoints around it; two neighbours where it
  /// lies strictly between the midpoints around the pair (it holds, or may hold, the midpoint
  /// between them); Undecided otherwise.
  struct Roundings {
    std::array<T, 2> value{};
    int count = 0;
  };
  static Roundings roundings_of(const Num& x, int e) {
    namespace cert = certified;
    T candidate;
    if constexpr (std::is_same_v<T, long double>) {
      candidate = std::ldexp(static_cast<long double>(x.hi) + static_cast<long double>(x.lo), e);
    } else {
      candidate = static_cast<T>(std::ldexp(x.hi, e));
    }
    if (!std::isfinite(candidate)) throw filtering::Undecided{__LINE__};
    const Num c = cert::scaled(candidate, -e);
    if (x.err == 0 && c.err == 0 && c.hi == x.hi && c.lo == x.lo)
      return Roundings{{candidate, candidate}, 1};  // exact
    constexpr T inf = std::numeric_limits<T>::infinity();
    const T below = std::nextafter(candidate, -inf), above = std::nextafter(candidate, inf);
    if (!std::isfinite(below) || !std::isfinite(above) || candidate == T(0))
      throw filtering::Undecided{__LINE__};
    const Num half = cert::constant(0.5);
    auto midpoint = [&](T a, const Num& b) { return (cert::scaled(a, -e) + b) * half; };
    // Whether y < z certainly (false where the intervals do not say).
    auto certainly_less = [](const Num& y, const Num& z) {
      int sign = 0;
      return cert::sign_known(z - y, sign) && sign > 0;
    };
    const bool above_low = certainly_less(midpoint(below, c), x);
    const bool below_high = certainly_less(x, midpoint(above, c));
    if (above_low && below_high) return Roundings{{candidate, candidate}, 1};
    if (above_low) {  // at or above the midpoint to `above`, below the one beyond
      const T beyond = std::nextafter(above, inf);
      if (std::isfinite(beyond) && certainly_less(x, midpoint(beyond, cert::scaled(above, -e))))
        return Roundings{{candidate, above}, 2};
    } else if (below_high) {
      const T beyond = std::nextafter(below, -inf);
      if (std::isfinite(beyond) && certainly_less(midpoint(beyond, cert::scaled(below, -e)), x))
        return Roundings{{below, candidate}, 2};
    }
    throw filtering::Undecided{__LINE__};
  }

  /// roundings_of(row 3's entry j), from the interval of row3_ or, where that is too wide (a
  /// cancelling entry, a tie), from the integers (IntegerSigns::row3).
  Roundings roundings_or_exact(int j) const {
    try {
      return roundings_of(row3_[j], sm_);
    } catch (const filtering::Undecided&) {
      const DepthRange range = clip_depth_range(convention_);
      return roundings_of(
          integers().row3(j, q_clip2_, range.z_high - range.z_low, near_rows(convention_), sm_),
          sm_);
    }
  }

  /// The exponent of the largest |entry| (0 when all are 0): the power of two the filter scales by.
  template <class V>
  static int largest_exponent(const V& v) {
    const T largest = v.cwiseAbs().maxCoeff();
    return largest == T(0) ? 0 : std::ilogb(largest);
  }

  Matrix4<T> m_;
  Vector4<T> c_;
  Convention convention_;
  bool decided_ = false;
  mutable int undecided_at_ = 0;
  Status status_ = Status::invalid_input;
  std::vector<Status> acceptable_;
  mutable std::optional<Problem<T>> exact_;
  mutable std::optional<filtering::IntegerSigns<T>> integers_;
  filtering::Constants<T> constants_;

  bool finite_ = false, invertible_ = false, infinite_ = false, far_at_infinity_ = false;
  bool d_positive_ = false;
  std::array<NumVec, 4> mx_{}, inverse_{};
  NumVec cx_{}, c_clip_{}, q_{}, row3_{};
  std::array<int, 3> c_clip_sign_{};
  std::array<int, 4> q_clip2_{};
  std::array<std::array<int, 4>, 8> clip_corners_{};
  std::array<NumVec, 8> corners_{};
  std::array<Num, 8> corner_dots_{};
  std::array<int, 8> corner_sign_{};
  Num d_, kappa_numerator_;
  // Scaling: the filter holds M 2^-sm_ and C 2^-sc_ (certified::scaled: exactly, or within
  // 2^-1074 for an entry that lands below double's normal range), so every quantity is that of
  // the scaled problem, which is the exact one's times a power of two: the inverse, the corners and
  // Q times 2^sm_, C', C . Q (d_), its corner values and kappa's numerator times 2^(sm_ - sc_), the
  // exact row 3 and every row of an answer (scaled alike) times 2^-sm_; lambda (property 1) times
  // 2^(sc_ - sm_); ratios, Skeel's condition number and eps alike. Only the absolute terms (the
  // underflow unit) and the overflow thresholds are not homogeneous: the underflow unit enters
  // the bounds on entries of rows as underflow_row_ = u_min 2^-sm_ and those on C . Q as
  // underflow_dot_ = u_min 2^(sm_ - sc_); at_least_largest() and rounding_of() take the exponent
  // that brings their value back.
  int sm_ = 0, sc_ = 0;
  Num underflow_row_, underflow_dot_;
};

template <class T>
FilteredProblem<T>::FilteredProblem(const Matrix4<T>& m, const Vector4<T>& c, Convention convention)
    : m_(m), c_(c), convention_(convention) {
  try {
    build();
    decided_ = true;
  } catch (const filtering::Undecided& u) {
    decided_ = false;
    undecided_at_ = u.line;
  }
}

/// judge() on a FilteredProblem: the filter's judgement where it decides that every check holds,
/// otherwise the exact checker's.
template <class T>
Judgement judge(const FilteredProblem<T>& problem, const Answer<T>& outcome,
                const Checks& checks = {}) {
  if (std::optional<Judgement> j = problem.filtered_judgement(outcome, checks)) return *j;
  return judge(problem.exact(), outcome, checks);
}

/// The checker's constructors and judgements oblique::properties compiles
/// (oracle/instances.cpp), for T = float, double and long double: `declare` is `template` there
/// and `extern template` in a program that links them (OBLIQUE_LINKED_CHECKER, which the
/// oblique::properties target sets), so that a file judging answers does not compile the checker
/// again. OBLIQUE_CHECKER_HEADER_ONLY turns that off (for generators.h too): a file compiled with
/// other SIMD flags than the library (-mavx2, -march=native) lays Eigen's fixed-size members out
/// with another alignment, so the cases and answers it would pass across differ from the
/// library's; it compiles its own copies, which come first at link.
#define OBLIQUE_CHECKER_INSTANCES(declare, T)                                                    \
  declare Problem<T>::Problem(const Matrix4<T>&, const Vector4<T>&, Convention);                 \
  declare FilteredProblem<T>::FilteredProblem(const Matrix4<T>&, const Vector4<T>&, Convention); \
  declare Judgement judge<T>(const Problem<T>&, const Answer<T>&, const Checks&);                \
  declare Judgement judge<T>(const FilteredProblem<T>&, const Answer<T>&, const Checks&);

#if defined(OBLIQUE_LINKED_CHECKER) && !defined(OBLIQUE_CHECKER_HEADER_ONLY)
OBLIQUE_CHECKER_INSTANCES(extern template, float)
OBLIQUE_CHECKER_INSTANCES(extern template, double)
OBLIQUE_CHECKER_INSTANCES(extern template, long double)
#endif

}  // namespace oblique::oracle
