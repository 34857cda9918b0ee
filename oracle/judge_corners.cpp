// The corners judge (consumers.h): the corners a shadow or cluster pass fits its volume to
// contain the kept region, judged with the error bound of a correct computation in T, in
// certified ranges first and exact rationals where they cannot decide (Arithmetic).
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
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

using namespace consumer_judging;

template <class T>
ConsumerFinding judge_corners(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                              const Matrix4<T>& oblique, const std::vector<Vector3<T>>& answer,
                              Arithmetic arithmetic) {
  ConsumerFinding f;
  f.check = ConsumerCheck::corners_contain_kept;
  const std::shared_ptr<const Problem<T>> problem_ptr = problem_of(m, c, convention);
  const Problem<T>& problem = *problem_ptr;
  const std::optional<oracle::exact::Vec> row3 =
      problem.exact_status() == Status::ok ? problem.row3_bounds() : std::nullopt;
  if (!row3 || problem.infinite()) {
    f.judged = false;
    if (row3) f.unjudged = ConsumerFinding::Unjudged::not_applicable;
    f.detail = row3 ? "an infinite projection: the kept region is unbounded"
                    : "the case has no answer to judge against";
    return f;
  }
  const auto region_ptr = exact_kept_region(m, c, convention);
  const std::optional<std::vector<Vec>>& region = *region_ptr;
  if (!region) {
    f.judged = false;
    f.detail = kNotProper;
    return f;
  }
  const std::vector<Vec>& kept = *region;
  for (const Vec& v : kept) {
    if (v[3] == 0) {
      f.judged = false;
      f.unjudged = ConsumerFinding::Unjudged::not_applicable;
      f.detail = "the kept region is unbounded";
      return f;
    }
  }
  std::vector<Vec> points;
  std::vector<Vector3<T>> distinct;  // the same, in T
  for (const Vector3<T>& p : answer) {
    if (!p.allFinite()) {
      f.holds = false;
      f.ratio = std::numeric_limits<double>::infinity();
      f.detail = "the corner " + numbers_text(p) + " is not finite";
      return f;
    }
    const Vec x = point_of(p);
    if (std::find(points.begin(), points.end(), x) == points.end()) {
      points.push_back(x);
      distinct.push_back(p);
    }
  }
  // The hull is found from every triple of points (n^4 exact products): a corner set, not a
  // point cloud.
  if (points.size() > kMaxCorners) {
    f.judged = false;
    f.detail = std::to_string(points.size()) + " distinct points: the hull test takes at most " +
               std::to_string(kMaxCorners);
    return f;
  }
  // How far each given corner may be from a correct one, in the directions the hull's facets
  // face: a point computed by a solve in T with M' (the oblique volume's corners) or with M (the
  // original's, then clipped by C), M' itself off the exact answer by row 3's bound, and a point
  // where C crosses an edge off C by its rounding (gamma(kPlaneRoundings) |C| . |x| over |n_C|;
  // along the edge, inside the hull's other facets, it costs nothing). The bound comes from the
  // correct corners (the kept region's exact vertices), never from the answer: corners far from
  // the right ones must not widen what they are judged by. A correct corner is within its
  // vertex's bound d of it, so the bound is taken once more at each vertex widened by its own d
  // (every term grows with |x|): it then holds for any corner a correct computation can give.
  const std::shared_ptr<const Inverse> oblique_facts = inverse_of(oblique), m_facts = inverse_of(m);
  const Mat& mo = oblique_facts->m;
  const Mat& mx = m_facts->m;
  const std::optional<Mat>& inv = oblique_facts->inv;
  const std::optional<Mat>& m_inv = m_facts->inv;
  if (!inv || !m_inv) {
    f.judged = false;
    f.detail = "a singular matrix";
    return f;
  }
  // Each solve's error from the matrix at hand (solve_error(): cofactors or elimination, the
  // larger), not partial pivoting's worst case.
  const std::shared_ptr<const SolveBound> chain = solve_bound_of(oblique),
                                          m_chain = solve_bound_of(m);
  if (!chain->exists || !m_chain->exists) {
    f.judged = false;
    f.detail = "a projection's determinant is within T's rounding of 0";
    return f;
  }
  // The exact bounds, asked only by the exact path.
  std::shared_ptr<const std::optional<Mat>> chain_exact, m_chain_exact;
  auto exact_solve = [&](bool with_m) -> const Mat& {
    std::shared_ptr<const std::optional<Mat>>& kept = with_m ? chain_exact : m_chain_exact;
    if (!kept) kept = solve_error_of(with_m ? oblique : m);
    return **kept;
  };
  const Rational u = unit<T>();
  const Vec cx = oracle::exact::to_rational(c);
  const Rational c_normal =
      std::max({oracle::exact::abs(cx[0]), oracle::exact::abs(cx[1]), oracle::exact::abs(cx[2])});
  const Rational plane_gamma = gamma_of<T>(oracle::tolerance::kPlaneRoundings);
  // The bound at a vertex x (w = 1) of every corner within `widen` of it in x, y and z; < 0 when
  // a solve in T cannot determine w there.
  auto bound_near = [&](const Vec& x, const Rational& widen) -> Rational {
    Vec size;  // |x| widened
    for (int i = 0; i < 3; ++i) size[i] = oracle::exact::abs(x[i]) + widen;
    size[3] = 1;
    Rational d = 0;
    for (const bool with_m : {true, false}) {
      const Mat& solve = exact_solve(with_m);
      const Mat& matrix = with_m ? mo : mx;
      Vec q =
          oracle::exact::abs(oracle::exact::mul(matrix, x));  // its clip-space point, widened below
      for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 3; ++k) q[r] += oracle::exact::abs(matrix[r][k]) * widen;
      Vec dv = oracle::exact::mul(solve, q);
      const Rational row3_part = with_m ? oracle::exact::dot(*row3, size) : Rational(0);
      const Mat& inverse = with_m ? *inv : *m_inv;
      for (int i = 0; i < 4; ++i) dv[i] += oracle::exact::abs(inverse[i][2]) * row3_part;
      if (dv[3] >= 1) return -1;  // w not determined: no bound from this solve
      for (int i = 0; i < 3; ++i) d += (dv[i] + size[i] * dv[3]) / (1 - dv[3]) + u * size[i];
    }
    if (c_normal > 0)
      d += plane_gamma * oracle::exact::dot(oracle::exact::abs(cx), size) / c_normal;
    return d;
  };
  // delta, the largest bound over the kept region's vertices, exactly; empty where a solve in T
  // cannot determine w at one of them.
  auto exact_delta = [&]() -> std::optional<Rational> {
    Rational delta = 0;
    for (const Vec& v : kept) {
      const Rational at_vertex = bound_near(v, 0);
      const Rational d = at_vertex < 0 ? at_vertex : bound_near(v, at_vertex);
      if (d < 0) return std::nullopt;
      delta = std::max(delta, d);
    }
    return delta;
  };
  // The same bound in certified ranges (every term is a sum, product or quotient of magnitudes,
  // monotone in each): [delta_low, delta_high] holds delta. Exact arithmetic on the kept region's
  // vertices and the solves' error matrices (rationals of thousands of bits) is what made this
  // judge slow; the comparisons below take the exact delta only where the range cannot decide.
  std::optional<Rational> delta_exact;
  Rational delta_low, delta_high;
  bool determined = true;
  bool ranged = arithmetic == Arithmetic::filtered;
  if (ranged) {
    try {
      using certified::Range;
      // The inputs converted once: the two matrices (exact numbers and magnitudes), the solves'
      // error matrices, the inverses' third columns, row 3's bounds and the constants.
      struct Solve {
        std::array<std::array<certified::Num, 4>, 4> matrix;
        std::array<std::array<Range, 4>, 4> magnitude, error;
        std::array<Range, 4> inverse_column;
        bool with_m = false;
      };
      std::array<Solve, 2> solves;
      for (int s = 0; s < 2; ++s) {
        Solve& out = solves[static_cast<std::size_t>(s)];
        out.with_m = s == 0;
        const Mat& matrix = out.with_m ? mo : mx;
        const SolveBound& error = out.with_m ? *chain : *m_chain;
        if (!error.ranged) throw certified::Undecided{__LINE__};
        const Mat& inverse = out.with_m ? *inv : *m_inv;
        for (std::size_t i = 0; i < 4; ++i) {
          out.inverse_column[i] = range_of(oracle::exact::abs(inverse[i][2]));
          for (std::size_t j = 0; j < 4; ++j) {
            out.matrix[i][j] = certified_of(matrix[i][j]);
            out.magnitude[i][j] = range_of(oracle::exact::abs(matrix[i][j]));
            out.error[i][j] = error.range[i][j];
          }
        }
      }
      std::array<Range, 4> row3_range, c_magnitude;
      for (std::size_t i = 0; i < 4; ++i) {
        row3_range[i] = range_of((*row3)[i]);
        c_magnitude[i] = range_of(oracle::exact::abs(cx[i]));
      }
      const Range u_range = range_of(u), plane_gamma_range = range_of(plane_gamma),
                  c_normal_range = range_of(c_normal);
      const Range no_widening{};
      auto bound_range = [&](const Vec& x, const Range& widen) -> std::optional<Range> {
        std::array<certified::Num, 4> point;
        for (std::size_t i = 0; i < 4; ++i) point[i] = certified_of(x[i]);
        std::array<Range, 4> size;
        for (std::size_t i = 0; i < 3; ++i) size[i] = certified::magnitude_of(point[i]) + widen;
        size[3] = Range{1, 1};
        Range d{};
        for (const Solve& solve : solves) {
          std::array<Range, 4> q;
          for (std::size_t r = 0; r < 4; ++r) {
            certified::Num clip{};
            for (std::size_t k = 0; k < 4; ++k) clip = clip + solve.matrix[r][k] * point[k];
            q[r] = certified::magnitude_of(clip);
            for (std::size_t k = 0; k < 3; ++k) q[r] = q[r] + solve.magnitude[r][k] * widen;
          }
          Range row3_part{};
          if (solve.with_m)
            for (std::size_t i = 0; i < 4; ++i) row3_part = row3_part + row3_range[i] * size[i];
          std::array<Range, 4> dv;
          for (std::size_t i = 0; i < 4; ++i) {
            dv[i] = solve.inverse_column[i] * row3_part;
            for (std::size_t j = 0; j < 4; ++j) dv[i] = dv[i] + solve.error[i][j] * q[j];
          }
          if (dv[3].lo >= 1) return std::nullopt;  // w not determined: no bound from this solve
          const Range kept_w = one_minus(dv[3]);   // Undecided where dv[3] may reach 1
          for (std::size_t i = 0; i < 3; ++i)
            d = d + quotient(dv[i] + size[i] * dv[3], kept_w) + u_range * size[i];
        }
        if (c_normal > 0) {
          Range along{};
          for (std::size_t i = 0; i < 4; ++i) along = along + c_magnitude[i] * size[i];
          d = d + quotient(plane_gamma_range * along, c_normal_range);
        }
        return d;
      };
      Range delta{};
      for (const Vec& v : kept) {
        const std::optional<Range> at_vertex = bound_range(v, no_widening);
        const std::optional<Range> d = at_vertex ? bound_range(v, *at_vertex) : std::nullopt;
        if (!d) {
          determined = false;
          break;
        }
        delta = Range{std::max(delta.lo, d->lo), std::max(delta.hi, d->hi)};
      }
      if (!std::isfinite(delta.hi)) throw certified::Undecided{__LINE__};
      delta_low = delta.lo;
      delta_high = delta.hi;
    } catch (const certified::Undecided&) {
      ranged = false;
      determined = true;
    }
  }
  if (!ranged) {
    delta_exact = exact_delta();
    determined = delta_exact.has_value();
    if (delta_exact) delta_low = delta_high = *delta_exact;
  }
  if (!determined) {
    f.judged = false;
    f.detail = "a corner's w is not determined in T";
    return f;
  }
  // The exact delta, once a comparison needs it (a violation's message, a close call).
  auto settled_delta = [&]() -> const Rational& {
    if (!delta_exact) {
      delta_exact = exact_delta();
      delta_low = delta_high = *delta_exact;  // the range held it: w is determined
    }
    return *delta_exact;
  };
  // x <= delta^2 scale, for x and scale >= 0.
  auto within_delta = [&](const Rational& x, const Rational& scale) {
    if (x <= delta_low * delta_low * scale) return true;
    if (x > delta_high * delta_high * scale) return false;
    const Rational& delta = settled_delta();
    return x <= delta * delta * scale;
  };
  // delta as a double, for ratios: the exact one's when known, else the range's top.
  auto delta_double = [&] { return delta_exact ? delta_exact->get_d() : delta_high.get_d(); };
  // The hull's facets: planes through three corners with every corner on one side. Found on the
  // corners as integers in units of the lowest power of two any coordinate needs (GMP integers:
  // no gcd per operation), so a facet's normal is a positive multiple of the exact cross product;
  // what the tests below take of it (the side a point is on, s^2 / |normal|^2) is the same.
  struct Facet {
    Vec origin, normal;  // inward normal (x, y, z; w unused)
  };
  std::vector<Facet> facets;
  const std::size_t n = points.size();
  std::array<T, 3 * kMaxCorners> flat{};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) flat[3 * i + static_cast<std::size_t>(d)] = distinct[i](d);
  int unit_exponent = 0;
  const std::array<oracle::exact::Integer, 3 * kMaxCorners> corner_integers =
      oracle::exact::to_integers(flat, unit_exponent);
  auto at = [&](std::size_t i, int d) -> const oracle::exact::Integer& {
    return corner_integers[3 * i + static_cast<std::size_t>(d)];
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        oracle::exact::Integer e1[3], e2[3], normal[3];
        for (int d = 0; d < 3; ++d) {
          e1[d] = at(j, d) - at(i, d);
          e2[d] = at(k, d) - at(i, d);
        }
        normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
        normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
        normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (normal[0] == 0 && normal[1] == 0 && normal[2] == 0) continue;
        bool any_above = false, any_below = false;
        for (std::size_t x = 0; x < n && !(any_above && any_below); ++x) {
          oracle::exact::Integer s = 0;
          for (int d = 0; d < 3; ++d) s += normal[d] * (at(x, d) - at(i, d));
          any_above = any_above || s > 0;
          any_below = any_below || s < 0;
        }
        const Vec inward{Rational(normal[0]), Rational(normal[1]), Rational(normal[2]), 0};
        if (!any_below) facets.push_back({points[i], inward});
        if (!any_above) {
          Vec flipped = inward;
          for (auto& x : flipped) x = -x;
          facets.push_back({points[i], flipped});
        }
      }
    }
  }
  double worst = 0;
  if (n == 0) {
    f.holds = false;
    worst = std::numeric_limits<double>::infinity();
    f.detail = "no corners were given";
  } else if (facets.empty()) {
    // Every given point on one line (or one point): the hull is the segment between the two
    // farthest apart, and each vertex of the kept region must be within delta of it. (A correct
    // computation in T gives such corners where a solve with a matrix near singular in T
    // collapses them; delta, from that matrix, is then as large.)
    Vec lo = points[0], hi = points[0];
    if (n >= 2) {
      Vec e;
      for (int d = 0; d < 4; ++d) e[d] = points[1][d] - points[0][d];
      Rational t_lo = 0, t_hi = 0;
      for (const Vec& x : points) {
        Rational t = 0;
        for (int d = 0; d < 3; ++d) t += (x[d] - points[0][d]) * e[d];
        if (t < t_lo) t_lo = t, lo = x;
        if (t > t_hi) t_hi = t, hi = x;
      }
    }
    for (const Vec& v : kept) {
      Vec d, r;
      Rational dd = 0, t = 0;
      for (int k = 0; k < 3; ++k) {
        d[k] = hi[k] - lo[k];
        r[k] = v[k] - lo[k];
        dd += d[k] * d[k];
        t += r[k] * d[k];
      }
      if (dd > 0) t = std::clamp(Rational(t / dd), Rational(0), Rational(1));
      Rational dist2 = 0;
      for (int k = 0; k < 3; ++k) {
        const Rational off = r[k] - (dd > 0 ? t * d[k] : Rational(0));
        dist2 += off * off;
      }
      if (within_delta(dist2, 1)) {
        const Rational& delta = delta_exact ? *delta_exact : delta_high;
        worst =
            std::max(worst, delta > 0 ? std::sqrt(Rational(dist2 / (delta * delta)).get_d()) : 0.0);
        continue;
      }
      const Rational& delta = settled_delta();  // violated: the message gives it exactly
      const double distance = std::sqrt(dist2.get_d());
      const double r_v =
          delta > 0 ? distance / delta.get_d() : std::numeric_limits<double>::infinity();
      if (f.holds) {
        f.holds = false;
        f.detail = "the " + std::to_string(n) +
                   " distinct corners lie on one line, and the kept region's vertex " + text(v, 3) +
                   " is " + protocol::format_number(distance) + " from their segment (allowed " +
                   text(delta) + ")";
        f.points = {approx_point(v)};
        for (const Vec& x : points) f.points.push_back(approx_point(x));
        f.points_what =
            "the kept region's vertex off the corners' segment (first), and the given corners";
      }
      worst = std::max(worst, r_v);
    }
  }
  // The facets and the kept region's vertices enclosed, for the side a vertex is on: most are
  // certainly inside every facet (filtered; exact where the intervals cannot tell).
  std::vector<std::array<certified::Num, 6>> facets_num;  // normal, then origin (x, y, z)
  std::vector<std::array<certified::Num, 3>> kept_num;
  if (arithmetic == Arithmetic::filtered) {
    try {
      for (const Facet& facet : facets)
        facets_num.push_back({certified_of(facet.normal[0]), certified_of(facet.normal[1]),
                              certified_of(facet.normal[2]), certified_of(facet.origin[0]),
                              certified_of(facet.origin[1]), certified_of(facet.origin[2])});
      for (const Vec& v : kept)
        kept_num.push_back({certified_of(v[0]), certified_of(v[1]), certified_of(v[2])});
    } catch (const certified::Undecided&) {
      facets_num.clear();
      kept_num.clear();
    }
  }
  const bool signs_filtered =
      !facets.empty() && facets_num.size() == facets.size() && kept_num.size() == kept.size();
  for (std::size_t at = 0; at < kept.size(); ++at) {
    const Vec& v = kept[at];
    for (std::size_t fi = 0; fi < facets.size(); ++fi) {
      const Facet& facet = facets[fi];
      if (signs_filtered) {
        try {
          const std::array<certified::Num, 6>& q = facets_num[fi];
          certified::Num s{};
          for (std::size_t d = 0; d < 3; ++d) s = s + q[d] * (kept_num[at][d] - q[3 + d]);
          if (certified::non_negative(s)) continue;
        } catch (const certified::Undecided&) {
        }
      }
      Rational s = 0, nn = 0;
      for (int d = 0; d < 3; ++d) {
        s += facet.normal[d] * (v[d] - facet.origin[d]);
        nn += facet.normal[d] * facet.normal[d];
      }
      if (s >= 0) continue;
      // Outside by -s / |normal|; allowed delta.
      const double distance = std::sqrt(Rational(s * s / nn).get_d());
      const double delta = delta_double();
      const double r = delta > 0 ? distance / delta : std::numeric_limits<double>::infinity();
      if (f.holds && !within_delta(s * s, nn)) {
        f.holds = false;
        f.detail = "the kept region's vertex " + text(v, 3) + " is " +
                   protocol::format_number(distance) + " outside the corners' hull (allowed " +
                   text(settled_delta()) + ")";
        f.points = {approx_point(v)};
        for (const Vec& x : points) f.points.push_back(approx_point(x));
        f.points_what = "the kept region's vertex outside the hull (first), and the given corners";
      }
      worst = std::max(worst, r);
    }
  }
  f.ratio = f.holds ? std::min(worst, 1.0) : worst;
  // Depth waste along the view axis.
  const int axis = axis_sign(*m_inv, convention);
  auto extent = [axis](const std::vector<Vec>& xs) {
    Rational lo = axis * xs.front()[2], hi = lo;
    for (const Vec& x : xs) {
      lo = std::min(lo, Rational(axis * x[2]));
      hi = std::max(hi, Rational(axis * x[2]));
    }
    return Rational(hi - lo);
  };
  if (!points.empty() && !kept.empty() && extent(kept) > 0)
    f.depth_waste = Rational(extent(points) / extent(kept)).get_d();
  if (f.holds)
    f.detail = "the hull of " + std::to_string(n) + " corners contains the kept region's " +
               std::to_string(kept.size()) + " vertices; it spans " +
               protocol::format_number(f.depth_waste) + " times the kept region's depth";
  return f;
}

#define OBLIQUE_CORNERS_JUDGE(T)                                                            \
  template ConsumerFinding judge_corners(const Matrix4<T>&, const Vector4<T>&, Convention,  \
                                         const Matrix4<T>&, const std::vector<Vector3<T>>&, \
                                         Arithmetic);
OBLIQUE_CORNERS_JUDGE(float)
OBLIQUE_CORNERS_JUDGE(double)
OBLIQUE_CORNERS_JUDGE(long double)
#undef OBLIQUE_CORNERS_JUDGE

}  // namespace oblique::oracle
