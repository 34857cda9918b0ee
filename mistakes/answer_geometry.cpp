// answer_geometry() and its words (answer_geometry.h).
#include "oblique/mistakes/answer_geometry.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "oblique/oracle/exact.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/protocol/numbers.h"

namespace oblique::mistakes {

namespace {

using oracle::exact::Rational;
using oracle::exact::Vec;

Rational largest_magnitude(const Vec& v) {
  Rational out = 0;
  for (const Rational& x : v) out = std::max(out, oracle::exact::abs(x));
  return out;
}

}  // namespace

template <class T>
AnswerGeometry answer_geometry(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                               const Matrix4<T>& answer) {
  AnswerGeometry g;
  if (!all_finite(answer)) return g;
  const oracle::Problem<T> problem(m, c, convention);
  if (problem.exact_status() != Status::ok) return g;
  g.described = true;
  const oracle::Verdicts verdicts = problem.check(answer);
  const oracle::Verdict& sides = verdicts[oracle::Property::side_rows_unchanged];
  g.side_rows_kept = sides.holds;
  g.changed_row = sides.row;
  g.changed_column = sides.column;
  const oracle::Verdict& near = verdicts[oracle::Property::near_is_clip_plane];
  g.near_is_c = near.holds;
  g.near_wrong_side = near.shows == oracle::Shows::wrong_side;

  // Row 3 against the span of C and M_4: the least-squares alpha, beta (exact normal equations).
  const oracle::exact::Mat r = oracle::exact::to_rational(answer);
  const Vec cx = oracle::exact::to_rational(c);
  const Vec m4 = oracle::exact::to_rational(Vector4<T>(m.row(3).transpose()));
  const Rational cc = oracle::exact::dot(cx, cx), cm = oracle::exact::dot(cx, m4),
                 mm = oracle::exact::dot(m4, m4);
  const Rational cr = oracle::exact::dot(cx, r[2]), mr = oracle::exact::dot(m4, r[2]);
  const Rational det = cc * mm - cm * cm;
  Rational alpha = 0, beta = 0;
  if (det != 0) {
    alpha = (cr * mm - mr * cm) / det;
    beta = (cc * mr - cm * cr) / det;
  } else if (cc != 0) {
    alpha = cr / cc;  // C is a multiple of M_4: C alone
  }
  // The rest of row 3 beyond alpha C + beta M_4, and whether it is within the rounding of each
  // entry in T (tolerance.h: row 3's own error per entry, gamma(kEntryRoundings)
  // (|alpha C_i| + |beta M4_i|), and the underflow unit).
  const Rational entry_gamma = oracle::tolerance::gamma(oracle::tolerance::kEntryRoundings,
                                                        oracle::tolerance::precision_bits<T>());
  auto rest_of = [&](const Rational& a_, const Rational& b_) {
    return oracle::exact::combine(1, oracle::exact::combine(1, r[2], Rational(-a_), cx),
                                  Rational(-b_), m4);
  };
  auto within_rounding = [&](const Rational& a_, const Rational& b_) {
    const Vec rest = rest_of(a_, b_);
    for (int i = 0; i < 4; ++i) {
      const Rational bound =
          entry_gamma * (oracle::exact::abs(a_ * cx[i]) + oracle::exact::abs(b_ * m4[i])) +
          oracle::tolerance::kEntryRoundings * oracle::tolerance::underflow_unit<T>();
      if (oracle::exact::abs(rest[i]) > bound) return false;
    }
    return true;
  };
  const Rational row_size = largest_magnitude(r[2]);
  g.alpha = alpha.get_d();
  g.beta = beta.get_d();
  g.rest_share =
      row_size > 0 ? Rational(largest_magnitude(rest_of(alpha, beta)) / row_size).get_d() : 0.0;
  g.in_span = within_rounding(alpha, beta);
  const DepthRange range = clip_depth_range(convention);
  const RowCombination nr = near_rows(convention);
  const Rational a = Rational(range.z_high - range.z_low) / problem.corner_dot();
  const Rational right_alpha = nr.m3 * a, right_beta = -nr.m3 * nr.m4;
  g.right_alpha = right_alpha.get_d();
  g.right_beta = right_beta.get_d();
  g.beta_right = within_rounding(alpha, right_beta);
  g.alpha_ratio = right_alpha != 0 ? Rational(alpha / right_alpha).get_d() : 0.0;

  // The far plane at Q.
  const oracle::Verdict& far = verdicts[oracle::Property::far_plane_through_corner];
  g.far_through_q = far.holds;
  g.far_at_q = far.residual;
  g.far_at_q_bound = far.bound;
  const Vec& q = problem.far_corner();
  g.q_at_infinity = q[3] == 0;
  const Rational w = oracle::exact::dot(r[3], q);
  g.q_depth = w == 0 ? std::numeric_limits<double>::quiet_NaN()
                     : Rational(oracle::exact::dot(r[2], q) / w).get_d();
  g.far_face = convention == Convention::reversed_z ? range.z_low : range.z_high;

  const oracle::Verdict& clipping = verdicts[oracle::Property::no_clipping];
  g.clips = !clipping.holds;
  if (g.clips && clipping.point) {
    g.clipped_at_corner = clipping.shows == oracle::Shows::below_at_corner;
    const Vec& p = *clipping.point;
    for (int i = 0; i < 4; ++i) g.clipped_point[static_cast<std::size_t>(i)] = p[i].get_d();
  }
  return g;
}

template AnswerGeometry answer_geometry<float>(const Matrix4<float>&, const Vector4<float>&,
                                               Convention, const Matrix4<float>&);
template AnswerGeometry answer_geometry<double>(const Matrix4<double>&, const Vector4<double>&,
                                                Convention, const Matrix4<double>&);
template AnswerGeometry answer_geometry<long double>(const Matrix4<long double>&,
                                                     const Vector4<long double>&, Convention,
                                                     const Matrix4<long double>&);

std::string answer_geometry_markdown(const AnswerGeometry& g) {
  if (!g.described) return "";
  auto number = [](double v) { return protocol::format_number(v); };
  auto short_number = [](double v) {
    std::ostringstream out;
    out.precision(4);
    out << v;
    return out.str();
  };
  std::ostringstream md;
  md << "What the first wrong answer does:\n\n";
  if (g.side_rows_kept) {
    md << "- Rows 1, 2 and 4 are M's: the side planes and w are kept.\n";
  } else {
    md << "- Rows 1, 2 and 4 are not M's (entry " << g.changed_row << ", " << g.changed_column
       << " changed): the side planes or w move.\n";
  }
  md << "- Row 3 is " << number(g.alpha) << " C + " << number(g.beta) << " M_4";
  if (!g.in_span) md << " + a rest " << short_number(g.rest_share) << " of its size";
  md << "; the correct row is " << number(g.right_alpha) << " C + " << number(g.right_beta)
     << " M_4.";
  if (g.right_alpha != 0 && g.in_span) {
    md << " C's multiple is " << short_number(g.alpha_ratio) << " times the right one";
    md << (g.beta_right ? ", M_4's is right." : "; M_4's differs.");
  }
  md << "\n";
  if (g.near_is_c) {
    md << "- The near plane is C, its kept side the right one.\n";
  } else if (g.near_wrong_side) {
    md << "- The near plane is C with the wrong side kept: it clips what C keeps.\n";
  } else {
    md << "- The near plane is not C.\n";
  }
  if (g.far_through_q) {
    md << "- The far plane passes through the far corner Q.\n";
  } else {
    md << "- The far plane misses the far corner Q: far' . Q = " << number(g.far_at_q) << " (bound "
       << number(g.far_at_q_bound) << ")";
    if (!std::isnan(g.q_depth))
      md << "; Q lands at depth " << number(g.q_depth) << " where the far face is "
         << number(g.far_face);
    md << ".\n";
  }
  if (g.clips) {
    md << "- Part of the original view volume on C's kept side is clipped: the far plane cuts "
          "away the point ("
       << number(g.clipped_point[0]) << ", " << number(g.clipped_point[1]) << ", "
       << number(g.clipped_point[2]) << ", " << number(g.clipped_point[3]) << ") (eye space, "
       << (g.clipped_at_corner ? "a corner of the volume" : "where C crosses an edge of the volume")
       << ").\n";
  } else {
    md << "- Nothing of the original view volume on C's kept side is clipped.\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace oblique::mistakes
