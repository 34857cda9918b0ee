// The five properties every oblique projection must have (the project's definitions), evaluated
// in exact rational arithmetic against the bounds in tolerance.h.
#pragma once

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/exact_arithmetic.h"
#include "oblique/oracle/finding.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/oracle/view_volume.h"
#include "oblique/oracle/vocabulary.h"
#include "oblique/plane.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/frustum_planes.h"
#include "oblique/status.h"

namespace oblique::oracle {

/// One property's verdict on one result (all_properties lists the five that check() judges):
/// its Finding (check_of(property)), whether it applies, and the point it is about.
struct [[nodiscard]] Verdict : Finding {
  explicit Verdict(Property p) {
    check = check_of(p);
    holds = true;
  }
  Property property() const { return *property_of(check); }
  bool applies = true;
  /// The point the verdict is about, homogeneous, in the space C is given in (eye space): for a
  /// violated no_clipping, the vertex of the view volume on C's positive side that far' cuts
  /// away farthest beyond its bound (normalised so that M_4 . p = 1). Empty otherwise.
  std::optional<oracle::exact::Vec> point;
};

struct [[nodiscard]] Verdicts {
  std::vector<Verdict> items;

  bool all_hold() const {
    for (const Verdict& v : items) {
      if (v.applies && !v.holds) return false;
    }
    return true;
  }
  const Verdict* first_failure() const {
    for (const Verdict& v : items) {
      if (v.applies && !v.holds) return &v;
    }
    return nullptr;
  }
  const Verdict& operator[](Property p) const { return items.at(static_cast<std::size_t>(p)); }
};

/// A rational's double, for a finding's numbers.
inline double approx(const oracle::exact::Rational& x) {
  return x.get_d();
}

/// Everything exact about one input (M, C, convention): the inverse, the clip-space plane C',
/// the eight corners of the view volume, the far corner Q and the conditioning of C . Q.
template <class T>
class Problem {
 public:
  /// Builds everything exact about (M, C) in `convention` (out of the class: compiled once in
  /// oblique::properties, OBLIQUE_CHECKER_INSTANCES).
  Problem(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);

  bool finite() const { return v_.finite; }
  bool invertible() const { return v_.invertible; }
  bool infinite() const { return v_.invertible && v_.infinite; }
  /// Property 5 applies: the far face is at infinity and Q lies on it (C leans toward the far
  /// face).
  bool far_corner_at_infinity() const { return v_.far_at_infinity; }
  Convention convention() const { return v_.convention; }
  const Matrix4<T>& matrix() const { return m_; }
  const Vector4<T>& plane() const { return c_; }
  const oracle::exact::Vec& far_corner() const { return v_.q; }
  const oracle::exact::Rational& corner_dot() const {
    return v_.d;
  }  ///< C . Q, the largest C . corner

  /// The bound on the relative error of a = k / (C . Q): with eps = gamma(16) kappa bounding the
  /// relative error of C . Q, |a^ / a - 1| <= eps / (1 - eps). Empty when eps >= 1: C lies within
  /// rounding of the far corner, no floating-point implementation can bound a, and properties 3
  /// to 5 cannot be judged at the corners (acceptable_statuses() then allows every verdict).
  std::optional<oracle::exact::Rational> scale_error() const { return v_.scale_error(); }

  /// kappa, the condition number of C . Q (tolerance.h); meaningful when C . Q > 0.
  oracle::exact::Rational kappa() const {
    return v_.d > 0 ? oracle::exact::Rational(v_.kappa_numerator / v_.d) : 0;
  }

  /// The status an exact implementation returns (ok, or the first precondition that fails).
  Status exact_status() const { return v_.status; }

  /// The statuses a careful implementation computing in T may give (view_volume.h).
  const std::vector<Status>& acceptable_statuses() const { return v_.acceptable; }

  double skeel_condition() const { return skeel_condition_; }

  /// The exact third row of M': s (a C - t M_4) with a = (z_high - z_low) / (C . Q).
  /// Precondition: exact_status() == Status::ok.
  const oracle::exact::Vec& exact_row3() const { return v_.row3; }

  /// How far a computed third row is from exact_row3(), against the bound a careful
  /// implementation meets: per entry gamma(kEntryRoundings) (|a C_i| + |M4_i|) plus the
  /// error of a, |a C_i| gamma(kScaleRoundings) kappa. `ratio` <= 1 is within.
  struct Closeness {
    bool judged = true;
    bool within = true;
    double ratio = 0;
    int worst_entry = 0;
  };
  /// The bound on |M'_3i - exact_row3()_i| for each entry i; empty where scale_error() is.
  std::optional<oracle::exact::Vec> row3_bounds() const {
    const std::optional<oracle::exact::Rational> scale = scale_error();
    if (!scale) return std::nullopt;
    oracle::exact::Vec bounds;
    for (int i = 0; i < 4; ++i) bounds[i] = v_.row3_bound(i, *scale);
    return bounds;
  }

  /// Closeness to the exact answer; `judged` is false (and `within` true) where no bound exists.
  Closeness compare_row3(const Matrix4<T>& result) const {
    const oracle::exact::Vec& expected = exact_row3();
    const std::optional<oracle::exact::Vec> maybe_bounds = row3_bounds();
    Closeness out;
    if (!all_finite(result)) {
      out.within = false;
      out.ratio = std::numeric_limits<double>::infinity();
      return out;
    }
    if (!maybe_bounds) {
      out.judged = false;
      return out;
    }
    const oracle::exact::Vec& bounds = *maybe_bounds;
    oracle::exact::Rational worst = -1;
    bool unbounded = false;  // an error where the bound is 0: the worst entry, ratio infinite
    for (int i = 0; i < 4; ++i) {
      const oracle::exact::Rational error =
          oracle::exact::abs(oracle::exact::to_rational(result(2, i)) - expected[i]);
      const oracle::exact::Rational& bound = bounds[i];
      if (error > bound) out.within = false;
      if (bound == 0) {
        if (error > 0 && !unbounded) {
          unbounded = true;
          out.worst_entry = i;
        }
        continue;
      }
      const oracle::exact::Rational ratio = error / bound;
      if (!unbounded && ratio > worst) {
        worst = ratio;
        out.worst_entry = i;
      }
    }
    out.ratio = unbounded ? std::numeric_limits<double>::infinity() : std::max(0.0, worst.get_d());
    return out;
  }

  /// The largest oracle::exact::ulp_distance of an entry of `result` from the correctly rounded
  /// exact M' (rows 1, 2 and 4 are M's own). Precondition: exact_status() == Status::ok.
  double ulps_from_exact(const Matrix4<T>& result) const {
    const oracle::exact::Vec& row3 = exact_row3();
    double worst = 0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const oracle::exact::Rational& expected = i == 2 ? row3[j] : v_.mx[i][j];
        worst = std::max(worst, oracle::exact::ulp_distance(result(i, j), expected));
      }
    }
    return worst;
  }

  /// The suite's cross-check through frustum_planes() in T: the side planes of M' equal those of
  /// M, and its near plane keeps C's positive side.
  Verdict check_extracted_planes(const Matrix4<T>& result) const {
    Verdict v(Property::extracted_planes_match);
    const FrustumPlanes<T> before = frustum_planes(m_, v_.convention);
    const FrustumPlanes<T> after = frustum_planes(result, v_.convention);
    const Vector4<T> sides_before[] = {before.left, before.right, before.bottom, before.top};
    const Vector4<T> sides_after[] = {after.left, after.right, after.bottom, after.top};
    for (int i = 0; i < 4; ++i) {
      if (!(sides_after[i] == sides_before[i])) {
        v.holds = false;
        v.shows = Shows::side_plane_differs;
        v.row = i + 1;
        v.residual = static_cast<double>((sides_after[i] - sides_before[i]).cwiseAbs().maxCoeff());
        return v;
      }
    }
    if (!all_finite(after.near_plane)) {
      v.holds = false;
      v.shows = Shows::near_plane_not_finite;
      return v;
    }
    const oracle::exact::Rational dot =
        oracle::exact::dot(oracle::exact::to_rational(Vector4<T>(after.near_plane)), v_.cx);
    v.holds = dot > 0;
    v.shows = Shows::near_plane_side;
    v.residual = approx(dot);
    return v;
  }

  /// Judges a result M' of this input. Precondition: exact_status() == Status::ok.
  Verdicts check(const Matrix4<T>& result) const {
    Verdicts out;
    if (!all_finite(result)) {  // a NaN or infinity in M' violates every property it touches
      for (Property p : all_properties) {
        Verdict v(p);
        v.applies = p != Property::infinite_edge_parallel || far_corner_at_infinity();
        v.holds = p == Property::side_rows_unchanged && all_finite(result.row(0)) &&
                  all_finite(result.row(1)) && all_finite(result.row(3)) &&
                  result.row(0) == m_.row(0) && result.row(1) == m_.row(1) &&
                  result.row(3) == m_.row(3);
        v.shows = Shows::non_finite_answer;
        out.items.push_back(v);
      }
      return out;
    }
    const oracle::exact::Mat r = oracle::exact::to_rational(result);
    const RowCombination nr = near_rows(v_.convention), fr = far_rows(v_.convention);
    const oracle::exact::Vec& m4 = v_.mx[3];
    const oracle::exact::Vec near = oracle::exact::combine(nr.m3, r[2], nr.m4, r[3]);
    const oracle::exact::Vec far = oracle::exact::combine(fr.m3, r[2], fr.m4, r[3]);
    const int p = oracle::tolerance::precision_bits<T>();
    const oracle::exact::Rational entry_gamma =
        oracle::tolerance::gamma(oracle::tolerance::kEntryRoundings, p);
    // Row 3's own error per entry, in every convention: gamma(kEntryRoundings) (|a C_i| + |M4_i|)
    // (as row3_accuracy's bound): an implementation may form any convention's row from another's
    // (a [0, 1] row as (M'_3(gl) + M_4) / 2), and then carries the |M_4| term (tolerance.h,
    // "a row formed through another convention's").
    const oracle::exact::Rational t_near = 1;

    // 1. near' = lambda C for some lambda > 0, every entry within its own rounding:
    //    |near'_i - lambda C_i| <= g (lambda |C_i| + |M4_i|) + w lambda, g =
    //    gamma(kEntryRoundings), first with w = 0; an answer that fails so is tried again with the
    //    allowance for what no rasterizer sees, w = kInvisiblePlaneUlps u max_j |C_j|
    //    (tolerance.h). Each entry bounds lambda to an interval; the property holds when they
    //    intersect above 0.
    const oracle::exact::Rational& g = entry_gamma;
    const oracle::exact::Rational underflow =
        oracle::tolerance::kEntryRoundings * oracle::tolerance::underflow_unit<T>();
    int k = 0;  // the largest |C_k|
    for (int i = 1; i < 4; ++i) {
      if (oracle::exact::abs(v_.cx[i]) > oracle::exact::abs(v_.cx[k])) k = i;
    }
    oracle::exact::Rational lambda_low = 0, lambda_high = 0;
    bool feasible = false;
    auto fit = [&](const oracle::exact::Rational& w) {
      // With y_i = sgn(C_i) near'_i, c_i = |C_i|, b_i = g |M4_i| + underflow:
      //   lambda >= (y_i - b_i) / (c_i (1 + g) + w), and lambda (c_i (1 - g) - w) <= y_i + b_i.
      // The largest |C_k| always gives an upper bound (c_k (1 - g) > w); the first sets it (a
      // negative upper bound is an answer, not "none yet": it makes the test fail).
      lambda_low = 0;
      bool has_high = false, ok = true;
      for (int i = 0; i < 4; ++i) {
        const oracle::exact::Rational b = g * t_near * oracle::exact::abs(m4[i]) + underflow;
        const oracle::exact::Rational c = oracle::exact::abs(v_.cx[i]);
        const oracle::exact::Rational y =
            v_.cx[i] >= 0 ? near[i] : oracle::exact::Rational(-near[i]);
        if (c == 0 && w == 0) {
          if (oracle::exact::abs(near[i]) > b) ok = false;
          continue;
        }
        lambda_low = std::max(
            lambda_low, oracle::exact::Rational((c == 0 ? oracle::exact::abs(near[i]) - b : y - b) /
                                                (c * (1 + g) + w)));
        if (c == 0) continue;
        const oracle::exact::Rational room = c * (1 - g) - w;
        if (room > 0) {
          const oracle::exact::Rational high = (y + b) / room;
          lambda_high = has_high ? std::min(lambda_high, high) : high;
          has_high = true;
        } else if (y + b < 0) {
          if (room == 0)
            ok = false;
          else
            lambda_low = std::max(lambda_low, oracle::exact::Rational((y + b) / room));
        }
      }
      return ok && has_high && lambda_high > 0 && lambda_low <= lambda_high;
    };
    oracle::exact::Rational invisible = 0;
    feasible = fit(0);
    if (!feasible) {
      const oracle::exact::Rational w = oracle::tolerance::kInvisiblePlaneUlps *
                                        oracle::tolerance::unit_roundoff(p) *
                                        oracle::exact::abs(v_.cx[k]);
      if (fit(w)) {
        feasible = true;
        invisible = w;
      }
    }
    // For the reports and the bounds below: a feasible lambda, or the one the largest |C_k| gives.
    const oracle::exact::Rational lambda =
        feasible ? oracle::exact::Rational((lambda_low + lambda_high) / 2)
                 : oracle::exact::Rational(near[k] / v_.cx[k]);
    oracle::exact::Vec entry_bound;  // what rounding may move one entry of M'_3
    for (int i = 0; i < 4; ++i)
      entry_bound[i] = v_.entry_bound(i, lambda * v_.cx[i], invisible * oracle::exact::abs(lambda));
    {
      Verdict v(Property::near_is_clip_plane);
      oracle::exact::Rational worst = 0;
      bool unbounded = false;  // a residual where the bound is 0
      for (int i = 0; i < 4; ++i) {
        const oracle::exact::Rational residual = oracle::exact::abs(near[i] - lambda * v_.cx[i]);
        if (entry_bound[i] > 0) {
          worst = std::max(worst, oracle::exact::Rational(residual / entry_bound[i]));
        } else if (residual > 0) {
          unbounded = true;
        }
      }
      v.holds = feasible;
      const double worst_ratio =
          unbounded ? std::numeric_limits<double>::infinity() : approx(worst);
      v.ratio = feasible ? std::min(worst_ratio, 1.0) : std::max(worst_ratio, 1.0 + 1e-9);
      // lambda <= 0 is the wrong side: near' keeps the half-space C cuts away, whatever the
      // residual (which may well be below its bound).
      v.shows = feasible ? Shows::lambda_fit : lambda <= 0 ? Shows::wrong_side : Shows::no_fit;
      v.lambda = approx(lambda);
      v.residual = worst_ratio;
      v.bound = 1;
      out.items.push_back(v);
    }
    // 2. Rows 1, 2, 4 unchanged in value: -0 and +0 are the same plane coefficient, so a changed
    // sign of zero (JavaScript's JSON.stringify(-0) writes 0) is not a changed side plane.
    {
      Verdict v(Property::side_rows_unchanged);
      for (int row : {0, 1, 3}) {
        for (int j = 0; j < 4; ++j) {
          const T before = m_(row, j), after = result(row, j);
          // Equal values (inputs are finite, so a NaN or an infinity here is a change).
          if (!(before == after)) {
            if (v.holds) {
              v.shows = Shows::entry;
              v.row = row + 1;
              v.column = j + 1;
              v.value = static_cast<double>(after);
              v.reference = static_cast<double>(before);
            }
            v.holds = false;
          }
        }
      }
      out.items.push_back(v);
    }
    // What rounding may do to far' . p at a point p with M_4 . p = 1 (view_volume.h).
    const std::optional<oracle::exact::Rational> scale = scale_error();
    const bool corners_judged = scale.has_value();
    const oracle::exact::Vec twice_entry_bound = v_.twice(entry_bound);
    const oracle::exact::Rational scale_term = v_.scale_term(scale);
    auto point_bound = [&](const oracle::exact::Vec& point, bool at_corner) {
      return v_.point_bound(twice_entry_bound, scale_term, point, at_corner);
    };
    // 3. and 5. far' . Q = 0.
    const oracle::exact::Rational far_q = oracle::exact::dot(far, v_.q);
    const oracle::exact::Rational far_q_bound = point_bound(v_.q, true);
    const double far_q_ratio = far_q_bound > 0 ? approx(oracle::exact::abs(far_q) / far_q_bound)
                               : far_q == 0    ? 0.0
                                               : std::numeric_limits<double>::infinity();
    {
      Verdict v(Property::far_plane_through_corner);
      v.applies = corners_judged;
      v.shows = corners_judged ? Shows::residual : Shows::no_bound;
      v.holds = oracle::exact::abs(far_q) <= far_q_bound;
      v.ratio = far_q_ratio;
      v.residual = approx(far_q);
      v.bound = approx(far_q_bound);
      out.items.push_back(v);
    }
    // 4. far' . p >= -bound at every vertex p of the view volume on C's positive side: the
    // corners with C . p >= 0 and the points where C crosses an edge of the volume.
    {
      Verdict v(Property::no_clipping);
      double worst = 0;
      v_.for_each_kept_vertex(corners_judged, [&](const oracle::exact::Vec& point, bool at_corner) {
        const oracle::exact::Rational value = oracle::exact::dot(far, point);
        if (value >= 0) return;
        const oracle::exact::Rational bound = point_bound(point, at_corner);
        const double ratio =
            bound > 0 ? approx(-value / bound) : std::numeric_limits<double>::infinity();
        if (-value > bound) {
          if (v.holds || ratio > worst) {
            v.shows = at_corner ? Shows::below_at_corner : Shows::below_at_edge_crossing;
            v.residual = approx(value);
            v.bound = approx(bound);
            v.point = point;
          }
          v.holds = false;
        }
        worst = std::max(worst, ratio);
      });
      v.ratio = worst;
      if (v.holds) v.shows = Shows::no_vertex_below;
      out.items.push_back(v);
    }
    {
      Verdict v(Property::infinite_edge_parallel);
      v.applies = far_corner_at_infinity() && corners_judged;
      v.holds = !v.applies || (v_.q[3] == 0 && oracle::exact::abs(far_q) <= far_q_bound);
      v.ratio = v.applies ? far_q_ratio : 0;
      v.shows = Shows::edge_direction;
      v.reference = approx(v_.q[3]);
      v.residual = approx(far_q);
      v.bound = approx(far_q_bound);
      out.items.push_back(v);
    }
    return out;
  }

 private:
  Matrix4<T> m_;
  Vector4<T> c_;
  ViewVolume<T, ExactArithmetic<T>> v_;
  double skeel_condition_ = 0;
};

template <class T>
Problem<T>::Problem(const Matrix4<T>& m, const Vector4<T>& c, Convention convention)
    : m_(m), c_(c), v_(m, c, convention) {
  // Skeel's condition number || |M^-1| |M| ||_inf, for reports.
  if (v_.invertible) {
    for (const auto& v : v_.skeel_row_sums)
      skeel_condition_ = std::max(skeel_condition_, v.get_d());
  }
}

}  // namespace oblique::oracle
