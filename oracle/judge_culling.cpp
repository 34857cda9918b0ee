// The culling judge (consumers.h): the frustum planes a culling pass extracts from the oblique
// matrix keep every point of the kept region, and their near plane is C; exact arithmetic.
#include "consumer_judging.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/algebra.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

using namespace consumer_judging;

template <class T>
std::vector<ConsumerFinding> judge_culling_planes(const Matrix4<T>& m, const Vector4<T>& c,
                                                  Convention convention, const Matrix4<T>& oblique,
                                                  const FrustumPlanes<T>& answer,
                                                  Arithmetic arithmetic) {
  ConsumerFinding keeps, near;
  keeps.check = ConsumerCheck::culling_keeps_visible;
  near.check = ConsumerCheck::culling_near_is_c;
  const std::shared_ptr<const Problem<T>> problem_ptr = problem_of(m, c, convention);
  const Problem<T>& problem = *problem_ptr;
  const std::optional<oracle::exact::Vec> row3 =
      problem.exact_status() == Status::ok ? problem.row3_bounds() : std::nullopt;
  if (!row3 || !oblique.allFinite()) {
    keeps.judged = near.judged = false;
    keeps.detail = near.detail =
        row3 ? "the oblique matrix is not finite" : "the case has no answer to judge against";
    return {keeps, near};
  }
  // How far the answer's near and far planes may be from the exact ones, relative to their size.
  const Mat mx = oracle::exact::to_rational(m);
  Mat exact_oblique = mx;
  exact_oblique[2] = problem.exact_row3();
  const RowCombination nr = near_rows(convention), fr = far_rows(convention);
  const Vec near_exact = oracle::exact::combine(nr.m3, exact_oblique[2], nr.m4, exact_oblique[3]);
  const Vec far_exact = oracle::exact::combine(fr.m3, exact_oblique[2], fr.m4, exact_oblique[3]);
  const Rational row3_error = max_abs(*row3);
  const Rational smallest_plane = std::min(max_abs(near_exact), max_abs(far_exact));
  // Where C is M_4 up to scale, M''s exact far plane (reversed Z: M_4 - a C) is the zero vector:
  // the one M' has in T is rounding alone, and no plane extracted from it can be judged.
  if (smallest_plane == 0) {
    keeps.judged = false;
    keeps.detail =
        "the exact oblique matrix's near or far plane is the zero vector (C is M_4 "
        "up to scale): the plane in T is rounding alone";
  }
  const Rational rho = smallest_plane > 0 ? Rational(row3_error / smallest_plane) : Rational(0);
  const Rational g = gamma_of<T>(oracle::tolerance::kPlaneRoundings);

  // (Without a proper original volume there is no kept region to cull, but near = C still
  // holds or not.)
  const auto region_ptr = exact_kept_region(m, c, convention);
  const std::optional<std::vector<Vec>>& region = *region_ptr;
  if (!region) {
    keeps.judged = false;
    keeps.detail = kNotProper;
  }
  const std::vector<Vec> kept = region ? *region : std::vector<Vec>{};
  // The vertices enclosed (certified_of), for the sign of P . v; none where a coordinate is beyond
  // double's range.
  std::vector<std::array<certified::Num, 4>> kept_num;
  try {
    for (const Vec& v : kept)
      kept_num.push_back(
          {certified_of(v[0]), certified_of(v[1]), certified_of(v[2]), certified_of(v[3])});
  } catch (const certified::Undecided&) {
    kept_num.clear();
  }
  const Vector4<T>* planes[] = {&answer.left, &answer.right,      &answer.bottom,
                                &answer.top,  &answer.near_plane, &answer.far_plane};
  const char* plane_names[] = {"left", "right", "bottom", "top", "near", "far"};
  double worst = 0;
  std::string culls_nothing;  // the non-finite planes that cull none of the kept region
  for (int k = 0; k < 6 && keeps.judged; ++k) {
    const Vector4<T>& plane = *planes[k];
    if (!plane.allFinite()) {
      // Judged by what it does: an engine culls x when P . x < 0, which a NaN never is, and a
      // plane (0, 0, 0, +inf) (the far plane at infinity of a head-on clip plane, normalised)
      // is +inf or NaN at every point: both cull nothing, which is conservative. A non-finite
      // plane that culls a vertex of the kept region (-inf there) violates.
      for (const Vec& v : kept) {
        double value = 0;
        for (int i = 0; i < 4; ++i) value += static_cast<double>(plane[i]) * v[i].get_d();
        if (!(value < 0)) continue;
        keeps.holds = false;
        worst = std::numeric_limits<double>::infinity();
        keeps.detail = std::string("the ") + plane_names[k] + " plane " + numbers_text(plane) +
                       " (not finite) culls the kept region's vertex " + text(v) +
                       ": P . v = " + protocol::format_number(value);
        keeps.points.clear();
        if (v[3] != 0) keeps.points.push_back(approx_point(v));
        keeps.points_what =
            "the kept region's vertex the " + std::string(plane_names[k]) + " plane culls";
        break;
      }
      if (!keeps.holds) break;
      culls_nothing += std::string(culls_nothing.empty() ? "" : ", ") + plane_names[k] + " " +
                       numbers_text(plane);
      continue;
    }
    const Vec p = oracle::exact::to_rational(plane);
    std::array<certified::Num, 4> p_num{};
    bool filtered = arithmetic == Arithmetic::filtered && kept_num.size() == kept.size();
    try {
      for (int i = 0; i < 4; ++i) p_num[static_cast<std::size_t>(i)] = certified::exactly(plane(i));
    } catch (const certified::Undecided&) {
      filtered = false;
    }
    for (std::size_t at = 0; at < kept.size(); ++at) {
      const Vec& v = kept[at];
      // P . v >= 0 shown in certified intervals where they can: most vertices are well inside.
      if (filtered) {
        try {
          if (certified::non_negative(algebra::dot(p_num, kept_num[at]))) continue;
        } catch (const certified::Undecided&) {
        }
      }
      const Rational value = oracle::exact::dot(p, v);
      if (value >= 0) continue;
      const Rational slack = g * oracle::exact::dot(oracle::exact::abs(p), oracle::exact::abs(v)) +
                             rho * max_abs(p) * sum_abs(v);
      const double r = ratio_of(value, slack);
      if (r > worst) {
        worst = r;
        if (-value > slack) {
          keeps.holds = false;
          keeps.detail = std::string("the ") + plane_names[k] + " plane " + numbers_text(plane) +
                         " culls the kept region's vertex " + text(v) + ": P . v = " + text(value) +
                         ", allowed down to -" + text(slack);
          keeps.points.clear();
          if (v[3] != 0) keeps.points.push_back(approx_point(v));
          keeps.points_what =
              "the kept region's vertex the " + std::string(plane_names[k]) + " plane culls";
        }
      }
    }
  }
  keeps.ratio = worst;
  if (keeps.holds && keeps.judged) {
    keeps.detail = "every one of the kept region's " + std::to_string(kept.size()) +
                   " vertices is inside all six planes";
    if (!culls_nothing.empty())
      keeps.detail += " (not finite, culling none of it: " + culls_nothing + ")";
  }

  // near = lambda C, lambda > 0: each coefficient within g |P_i| + lambda beta_i, where beta_i is
  // row 3's bound in C's units (over a) plus property 1's allowance for what no rasterizer sees.
  // The answer is checked before it meets exact arithmetic: GMP has no NaN or infinity.
  if (!answer.near_plane.allFinite()) {
    near.holds = false;
    near.ratio = std::numeric_limits<double>::infinity();
    near.detail = "the near plane " + numbers_text(answer.near_plane) + " is not finite";
    return {keeps, near};
  }
  const Vec cx = oracle::exact::to_rational(c);
  const Vec p = oracle::exact::to_rational(answer.near_plane);
  const DepthRange range = clip_depth_range(convention);
  const Rational a = Rational(range.z_high - range.z_low) / problem.corner_dot();
  const Rational invisible = oracle::tolerance::kInvisiblePlaneUlps * unit<T>() * max_abs(cx);
  Rational lambda_lo = 0, lambda_hi = -1;  // hi < 0: unbounded
  bool feasible = true;
  Vec beta;
  for (int i = 0; i < 4; ++i) {
    beta[i] = (*row3)[i] / a + invisible;
    const Rational slack = g * oracle::exact::abs(p[i]);
    // lambda (c_i + beta_i) >= p_i - slack and lambda (c_i - beta_i) <= p_i + slack.
    auto bound_by = [&](const Rational& coefficient, const Rational& rhs, bool at_least) {
      // coefficient * lambda (>= or <=) rhs
      if (coefficient == 0) {
        if (at_least ? rhs > 0 : rhs < 0) feasible = false;
        return;
      }
      const Rational t = rhs / coefficient;
      const bool lower = (coefficient > 0) == at_least;
      if (lower) {
        lambda_lo = std::max(lambda_lo, t);
      } else if (lambda_hi < 0 || t < lambda_hi) {
        lambda_hi = t;
        if (t < 0) feasible = false;
      }
    };
    bound_by(cx[i] + beta[i], p[i] - slack, true);
    bound_by(cx[i] - beta[i], p[i] + slack, false);
  }
  if (!(lambda_hi < 0) && lambda_lo > lambda_hi) feasible = false;
  // lambda must be positive: at lambda = 0 every coefficient would be within its own rounding.
  const bool positive = feasible && (lambda_hi < 0 || lambda_hi > 0);
  near.holds = feasible && positive && max_abs(p) > 0;
  const Rational lambda_fit = oracle::exact::dot(cx, cx) > 0
                                  ? Rational(oracle::exact::dot(p, cx) / oracle::exact::dot(cx, cx))
                                  : Rational(0);
  double worst_near = 0;
  if (lambda_fit > 0) {
    for (int i = 0; i < 4; ++i)
      worst_near = std::max(
          worst_near,
          ratio_of(p[i] - lambda_fit * cx[i], g * oracle::exact::abs(p[i]) + lambda_fit * beta[i]));
  } else {
    worst_near = std::numeric_limits<double>::infinity();
  }
  near.ratio =
      near.holds ? std::min(worst_near, 1.0) : std::max(worst_near, std::nextafter(1.0, 2.0));
  near.detail = "near plane " + numbers_text(answer.near_plane) +
                (near.holds ? " is " : " is not ") +
                "a positive multiple of C = " + numbers_text(c) +
                (lambda_fit > 0 ? " (best fit " + text(lambda_fit) + " C)"
                                : " (it keeps the other side of C)");
  return {keeps, near};
}

#define OBLIQUE_CULLING_JUDGE(T)                                                                   \
  template std::vector<ConsumerFinding> judge_culling_planes(const Matrix4<T>&, const Vector4<T>&, \
                                                             Convention, const Matrix4<T>&,        \
                                                             const FrustumPlanes<T>&, Arithmetic);
OBLIQUE_CULLING_JUDGE(float)
OBLIQUE_CULLING_JUDGE(double)
OBLIQUE_CULLING_JUDGE(long double)
#undef OBLIQUE_CULLING_JUDGE

}  // namespace oblique::oracle
