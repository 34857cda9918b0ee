// The filtered checker: the same judgement as judge() on a Problem (problem.h, the exact
// oracle), decided first in certified double-double arithmetic (certified.h), with exact signs
// from integer determinants where a value may be exactly zero, and the exact GMP Problem built
// only when neither decides.
//
// FilteredProblem<T> and Problem<T> share what is known before an answer, written once over the
// arithmetic (view_volume.h: the inverse, C', the corners, Q, C . Q, kappa, Skeel's condition
// number, the exact row 3, the statuses); here it is built in certified intervals with exact
// integer signs (certified_arithmetic.h). The judgement of an answer is the filter's own decision
// procedure (judge_holding: property 1 scales each entry by its own power of two, so that an entry
// far below the others keeps its bits, where the exact checker needs no scaling).
// A status decision, a property, the row-3 accuracy test or the ulps promise that the
// intervals do not settle throws certified::Undecided; so does any check that fails. judge() on a
// FilteredProblem then returns judge() on the exact Problem: every violation, and every close
// call, is the exact checker's own finding, word for word. Where the filter decides that every
// check holds, the findings are the exact checker's (kind, holds, relation) with the residual
// sides left out ("certified") and the ratio approximate (`every`, which lists residuals, always
// goes to the exact checker).
//
// tests/oracle/filtered_checker_test.cpp runs both checkers on generated cases and wrong answers
// and fails on any disagreement.
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
#include "oblique/oracle/certified_arithmetic.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/view_volume.h"

namespace oblique::oracle {

namespace filtering {

using NumVec = algebra::Vec<Num>;
using RangeVec = algebra::Vec<certified::Range>;

inline RangeVec magnitudes(const NumVec& v) {
  return {certified::magnitude_of(v[0]), certified::magnitude_of(v[1]),
          certified::magnitude_of(v[2]), certified::magnitude_of(v[3])};
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

  Status exact_status() const { return decided_ ? volume().status : exact().exact_status(); }
  const std::vector<Status>& acceptable_statuses() const {
    return decided_ ? volume().acceptable : exact().acceptable_statuses();
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

  // judge() when every check holds; throws Undecided otherwise.
  Judgement judge_holding(const Answer<T>& outcome, const Checks& checks) const {
    namespace cert = certified;
    const Volume& v = volume();
    const int sm_ = v.arithmetic.row_scale();
    Judgement out;
    if (judging::status_finding(v.status, v.acceptable, outcome.status, checks.statuses))
      throw filtering::Undecided{__LINE__};  // a status violation: the exact checker reports it
    if (outcome.status != Status::ok) return out;
    const Matrix4<T>& result = outcome.projection;
    if (!all_finite(result)) throw filtering::Undecided{__LINE__};
    if (v.status != Status::ok) return out;
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
      const NumVec near =
          algebra::combine(cert::constant(nr.m3), r[2], cert::constant(nr.m4), r[3]);
      const NumVec far = algebra::combine(cert::constant(fr.m3), r[2], cert::constant(fr.m4), r[3]);
      const Num g = CertifiedArithmetic<T>::gamma(oracle::tolerance::kEntryRoundings);
      const Num t_near = cert::constant(1);  // row 3's own error, as the exact checker's
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
        const Num b =
            g * t_near * cert::abs(cert::scaled(m_(3, i), -e)) +
            cert::constant(oracle::tolerance::kEntryRoundings) * filtering::underflow_unit<T>(-e);
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
        entry_bound[i] = v.entry_bound(i, lambda_c[i], Num{});
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
      // Property 3 to 5's bounds (view_volume.h).
      const std::optional<Num> scale = v.scale_error();
      const bool corners_judged = scale.has_value();
      const filtering::RangeVec twice_entry_bound = v.twice(entry_bound);
      const cert::Range scale_term = v.scale_term(scale);
      auto point_bound = [&](const NumVec& point, bool at_corner) {
        return v.point_bound(twice_entry_bound, scale_term, point, at_corner);
      };
      const Num far_q = algebra::dot(far, v.q);
      const Num far_q_bound = point_bound(v.q, true);
      const bool far_q_holds = cert::within(cert::abs(far_q), far_q_bound);
      const double far_q_ratio = cert::approx(far_q_bound) > 0
                                     ? std::fabs(cert::approx(far_q)) / cert::approx(far_q_bound)
                                     : 0.0;
      // 4. far' . p >= -bound at every vertex.
      double p4_worst = 0;
      if (wanted(Property::no_clipping)) {
        v.for_each_kept_vertex(corners_judged, [&](const NumVec& point, bool at_corner) {
          const Num value = algebra::dot(far, point);
          const Num bound = point_bound(point, at_corner);
          if (!cert::within(-value, bound)) throw filtering::Undecided{__LINE__};
          if (cert::approx(value) < 0 && cert::approx(bound) > 0)
            p4_worst = std::max(p4_worst, -cert::approx(value) / cert::approx(bound));
        });
      }
      const bool p5_applies = v.far_at_infinity && corners_judged;
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
      const int sn = CertifiedArithmetic<T>::largest_exponent(after.near_plane);
      for (int i = 0; i < 4; ++i) n[i] = cert::scaled(T(after.near_plane(i)), -sn);
      if (!cert::positive(algebra::dot(n, v.cx))) throw filtering::Undecided{__LINE__};
      holding(Check::extracted_planes_match, 0);
    }
    if (checks.row3_accuracy) {
      const std::optional<Num> scale = v.scale_error();
      double worst = 0;
      if (scale) {
        for (int i = 0; i < 4; ++i) {
          const Num bound = v.row3_bound(i, *scale);
          const Num error = cert::abs(cert::scaled(result(2, i), -sm_) - v.row3[i]);
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

  /// roundings_of(row 3's entry j), from the interval of v.row3 or, where that is too wide (a
  /// cancelling entry, a tie), from the integers (IntegerSigns::row3).
  Roundings roundings_or_exact(int j) const {
    const Volume& v = volume();
    const int sm = v.arithmetic.row_scale();
    try {
      return roundings_of(v.row3[j], sm);
    } catch (const filtering::Undecided&) {
      const DepthRange range = clip_depth_range(convention_);
      return roundings_of(v.arithmetic.integers().row3(j, v.q_clip2, range.z_high - range.z_low,
                                                       near_rows(convention_), sm),
                          sm);
    }
  }

  using Volume = ViewVolume<T, CertifiedArithmetic<T>>;
  const Volume& volume() const { return *volume_; }

  Matrix4<T> m_;
  Vector4<T> c_;
  Convention convention_;
  bool decided_ = false;
  mutable int undecided_at_ = 0;
  /// Everything about (M, C) in certified arithmetic (certified_arithmetic.h says how it is
  /// scaled); empty where the filter could not decide it.
  std::optional<Volume> volume_;
  mutable std::optional<Problem<T>> exact_;
};

template <class T>
FilteredProblem<T>::FilteredProblem(const Matrix4<T>& m, const Vector4<T>& c, Convention convention)
    : m_(m), c_(c), convention_(convention) {
  try {
    volume_.emplace(m, c, convention);
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
