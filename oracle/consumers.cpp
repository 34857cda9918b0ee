// The consumer properties (consumers.h), judged in exact rational arithmetic; compiled once for
// float, double and long double.
#include "oblique/oracle/consumers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "oblique/oblique.h"
#include "oblique/oracle/certified.h"
#include "oblique/oracle/consumer_cases.h"
#include "oblique/oracle/consumer_wire.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

namespace {

using oracle::exact::Mat;
using oracle::exact::Rational;
using oracle::exact::Vec;

template <class T>
Rational gamma_of(int roundings) {
  return oracle::tolerance::gamma(roundings, oracle::tolerance::precision_bits<T>());
}

template <class T>
Rational unit() {
  return oracle::tolerance::unit_roundoff(oracle::tolerance::precision_bits<T>());
}

/// The 4 x 4 matrix whose every entry is oracle::tolerance::lu_entry_bound(m): what |L||U| of m's
/// LU factors is at most, entry by entry.
Mat lu_bound(const Mat& m) {
  const Rational b = oracle::tolerance::lu_entry_bound(m);
  Mat out;
  for (auto& row : out) row.fill(b);
  return out;
}

Mat mul(const Mat& a, const Mat& b) {
  Mat out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      Rational s = 0;
      for (int k = 0; k < 4; ++k) s += a[i][k] * b[k][j];
      out[i][j] = s;
    }
  }
  return out;
}

/// The rows r and columns c of m's 3 x 3 minor without row i and column j.
void minor_indices(int i, int j, int (&r)[3], int (&c)[3]) {
  for (int k = 0, n = 0; k < 4; ++k)
    if (k != i) r[n++] = k;
  for (int k = 0, n = 0; k < 4; ++k)
    if (k != j) c[n++] = k;
}

/// The six products of the minor of m without row i and column j, with their signs in its
/// determinant: permanent = false gives the determinant, true the permanent of its magnitudes
/// (the sum of the magnitudes of the products the cofactor of m_ij adds up).
Rational minor_sum(const Mat& m, int i, int j, bool permanent) {
  int r[3], c[3];
  minor_indices(i, j, r, c);
  constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  Rational sum = 0;
  for (int k = 0; k < 6; ++k) {
    const auto& o = kOrders[k];
    const Rational p = m[r[0]][c[o[0]]] * m[r[1]][c[o[1]]] * m[r[2]][c[o[2]]];
    if (permanent)
      sum += oracle::exact::abs(p);
    else
      sum += k < 3 ? p : Rational(-p);
  }
  return sum;
}

/// One pivot order of an elimination with partial pivoting in T on m (consumers' solves), from
/// step k on: a holds the rows in pivot order, reduced through step k - 1, exactly; sum[r] bounds
/// the part of row r of |L||U| the steps before k gave; row_of[r] is the row of m at position r.
/// Entry by entry, `out` becomes the largest bound on |L^||U^| (rows in m's order) over every
/// pivot order rounding in T could take: at each step every candidate within the elimination's
/// error e = g sum of the largest is followed. The computed factors are bounded from the exact
/// ones: |u^| <= |u| + e and |l^| <= (|a_rk| + e_rk) / (|a_kk| - e_kk) (1 + u), at most 1 (the
/// pivot is the largest in T). False where a pivot is not determined in T (within e of 0).
bool lu_orders(Mat a, Mat sum, std::array<int, 4> row_of, int k, const Rational& g,
               const Rational& u, Mat& out) {
  Rational largest = -1;
  int at = k;
  for (int r = k; r < 4; ++r) {
    if (oracle::exact::abs(a[r][k]) > largest) {
      largest = oracle::exact::abs(a[r][k]);
      at = r;
    }
  }
  const Rational reach = largest - g * sum[at][k];
  for (int r = k; r < 4; ++r) {
    const Rational e = g * sum[r][k];
    if (oracle::exact::abs(a[r][k]) + e < reach) continue;
    if (oracle::exact::abs(a[r][k]) <= e) return false;
    Mat b = a, s = sum;
    std::array<int, 4> order = row_of;
    std::swap(b[r], b[k]);
    std::swap(s[r], s[k]);
    std::swap(order[r], order[k]);
    Vec u_bar{};  // |u^| of the pivot row
    for (int c = k; c < 4; ++c) u_bar[c] = oracle::exact::abs(b[k][c]) + g * s[k][c];
    for (int c = 0; c < 4; ++c) {
      const Rational row = s[k][c] + u_bar[c];
      out[order[k]][c] = std::max(out[order[k]][c], row);
    }
    const Rational pivot_low = oracle::exact::abs(b[k][k]) - g * s[k][k];
    for (int q = k + 1; q < 4; ++q) {
      const Rational l_bar = std::min(
          Rational(1), Rational((oracle::exact::abs(b[q][k]) + g * s[q][k]) / pivot_low * (1 + u)));
      const Rational l = b[q][k] / b[k][k];
      for (int c = k; c < 4; ++c) {
        s[q][c] += l_bar * u_bar[c];
        if (c > k) b[q][c] -= l * b[k][c];
      }
      b[q][k] = 0;
    }
    if (k < 3 && !lu_orders(b, s, order, k + 1, g, u, out)) return false;
  }
  return true;
}

/// The bound on |L^||U^| for m's LU factors with partial pivoting computed in T (lu_orders()),
/// rows in m's order; the worst case, lu_bound(), where a pivot is not determined in T.
template <class T>
Mat lu_magnitudes(const Mat& m) {
  Mat out{};
  for (auto& row : out) row.fill(0);
  Mat sum{};
  for (auto& row : sum) row.fill(0);
  if (!lu_orders(m, sum, {0, 1, 2, 3}, 0, gamma_of<T>(oracle::tolerance::kSolveRoundings),
                 unit<T>(), out))
    return lu_bound(m);
  return out;
}

/// A bound S, entry by entry, on the error of v = M^-1 b computed in T by a correct
/// implementation: |v^ - v| <= S |b| (tolerance.h, "a solve with a projection"). The larger of
/// the two ways engines compute it, each bounded from this matrix rather than the worst case:
///  - an inverse by cofactors (adjugate over determinant), then applied: each cofactor within
///    gamma(kCofactorRoundings) of the permanent of its minor of |M|, the determinant within
///    that of the permanent of |M|; then 4 roundings applying it;
///  - an elimination with partial pivoting (an inverse, or an LU solve): backward error
///    gamma(kConsumerSolveRoundings) |L^||U^|, so gamma |M^-1| G |M^-1| with G = lu_magnitudes().
/// Empty where the determinant computed by cofactors is not determined in T.
template <class T>
std::optional<Mat> solve_error(const Mat& m, const Mat& inv) {
  const Rational g = gamma_of<T>(oracle::tolerance::kCofactorRoundings);
  Mat perm;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) perm[i][j] = minor_sum(m, i, j, true);
  Rational det = 0, det_perm = 0;  // along row 0
  for (int j = 0; j < 4; ++j) {
    det += (j % 2 == 0 ? 1 : -1) * m[0][j] * minor_sum(m, 0, j, false);
    det_perm += oracle::exact::abs(m[0][j]) * perm[0][j];
  }
  const Rational size = oracle::exact::abs(det);
  const Rational det_error = g * det_perm;
  if (det_error >= size) return std::nullopt;
  // Applying the inverse: 4 roundings, and the window depth's conversion to NDC 2 more.
  const Rational g_apply = gamma_of<T>(6);
  const Mat lu = mul(mul(oracle::exact::abs(inv), lu_magnitudes<T>(m)), oracle::exact::abs(inv));
  const Rational g_lu = gamma_of<T>(oracle::tolerance::kConsumerSolveRoundings);
  Mat out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Rational x = oracle::exact::abs(inv[i][j]);
      // adj_ij is the cofactor of m_ji; then the quotient (or the reciprocal and a product).
      const Rational e = (1 + g) * (g * perm[j][i] + x * det_error) / (size - det_error) + g * x;
      out[i][j] = std::max(Rational(e + g_apply * (x + e)), Rational(g_lu * lu[i][j]));
    }
  }
  return out;
}

Rational max_abs(const Vec& v) {
  Rational m = 0;
  for (const Rational& x : v) m = std::max(m, oracle::exact::abs(x));
  return m;
}

Rational sum_abs(const Vec& v) {
  Rational s = 0;
  for (const Rational& x : v) s += oracle::exact::abs(x);
  return s;
}

/// A rational as a certified number: its double (mpq_get_d truncates toward zero) and, unless
/// that is the rational exactly, the step to the next double away from zero as its error.
certified::Num certified_of(const Rational& r) {
  const double d = r.get_d();
  if (!std::isfinite(d)) throw certified::Undecided{__LINE__};
  if (r == d) return certified::constant(d);
  const double next = std::nextafter(d, r > 0 ? std::numeric_limits<double>::infinity()
                                              : -std::numeric_limits<double>::infinity());
  if (!std::isfinite(next)) throw certified::Undecided{__LINE__};
  return certified::Num{d, 0, std::fabs(next - d)};
}

/// A rational >= 0 as a certified range: its double (truncated) and the next one up.
certified::Range range_of(const Rational& r) {
  const double d = r.get_d();
  if (!std::isfinite(d)) throw certified::Undecided{__LINE__};  // beyond double (a long double)
  if (r == d) return certified::Range{d, d};
  const double up = std::nextafter(d, std::numeric_limits<double>::infinity());
  if (!std::isfinite(up)) throw certified::Undecided{__LINE__};
  return certified::Range{d, up};
}

/// 1 - x for a range x below 1 (Undecided where x may reach 1).
certified::Range one_minus(const certified::Range& x) {
  if (!(x.hi < 1)) throw certified::Undecided{__LINE__};
  return certified::widened(1 - x.hi, 1 - x.lo);
}

/// x / y for ranges, y > 0 (Undecided where y may be 0, or the quotient overflows).
certified::Range quotient(const certified::Range& x, const certified::Range& y) {
  if (!(y.lo > 0)) throw certified::Undecided{__LINE__};
  const certified::Range q = certified::widened(x.lo / y.hi, x.hi / y.lo);
  if (!std::isfinite(q.hi)) throw certified::Undecided{__LINE__};
  return q;
}

template <class T>
Vec point_of(const Vector3<T>& p) {
  return {oracle::exact::to_rational(p(0)), oracle::exact::to_rational(p(1)),
          oracle::exact::to_rational(p(2)), Rational(1)};
}

/// A rational as the nearest double, shortest digits.
std::string text(const Rational& x) {
  return protocol::format_number(x.get_d());
}

std::string text(const Vec& v, int n = 4) {
  std::string out = "(";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + text(v[static_cast<std::size_t>(i)]);
  return out + ")";
}

Eigen::Vector3d approx_point(const Vec& v) {
  return {v[0].get_d(), v[1].get_d(), v[2].get_d()};
}

using Lines = std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>;

/// A square of half-size `half` in `plane` around its point nearest `near`, and the normal from
/// its centre toward the kept side; nothing for a plane without a finite normal.
Lines plane_square(const Eigen::Vector4d& plane, const Eigen::Vector3d& near, double half) {
  const Eigen::Vector3d n = plane.head<3>();
  const double nn = n.squaredNorm();
  if (!(nn > 0) || !std::isfinite(nn) || !std::isfinite(plane.w())) return {};
  const Eigen::Vector3d c = near - (n.dot(near) + plane.w()) / nn * n;
  const Eigen::Vector3d u = n.unitOrthogonal() * half, v = n.normalized().cross(u);
  const Eigen::Vector3d k[4] = {c + u + v, c - u + v, c - u - v, c + u - v};
  Lines out;
  for (int i = 0; i < 4; ++i) out.push_back({k[i], k[(i + 1) % 4]});
  out.push_back({c, c + n.normalized() * half / 2});
  return out;
}

/// A camera of `view` (world -> camera) drawn in world space: its eye, its view direction
/// (-z, `length` long) and its up (y, shorter); nothing for a singular or non-finite view.
ConsumerFinding::Drawn camera_drawn(const std::string& name, const Eigen::Matrix4d& view,
                                    double length) {
  ConsumerFinding::Drawn d;
  d.name = name;
  const Eigen::Matrix3d r = view.topLeftCorner<3, 3>();
  if (!view.allFinite() || r.determinant() == 0) return d;
  const Eigen::Matrix3d to_world = r.inverse();
  const Eigen::Vector3d eye = -to_world * view.topRightCorner<3, 1>();
  d.points = {eye};
  d.lines = {{eye, eye + length * (to_world * -Eigen::Vector3d::UnitZ()).normalized()},
             {eye, eye + 0.4 * length * (to_world * Eigen::Vector3d::UnitY()).normalized()}};
  return d;
}

Eigen::Matrix4d approx_matrix(const Mat& m) {
  Eigen::Matrix4d out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out(i, j) = m[i][j].get_d();
  return out;
}

/// |a| / b as a double ratio; 0 for 0 / 0, infinity for x / 0.
double ratio_of(const Rational& a, const Rational& b) {
  const Rational x = oracle::exact::abs(a);
  if (b == 0) return x == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return Rational(x / b).get_d();
}

Rational ndc_of(const Rational& window, Convention convention) {
  return convention == Convention::gl ? Rational(2 * window - 1) : window;
}

Rational window_of(const Rational& ndc, Convention convention) {
  return convention == Convention::gl ? Rational((ndc + 1) / 2) : ndc;
}

/// The window depths the stored value stands for, with the value the shader reads, in [0, 1].
template <class T>
std::pair<Rational, Rational> depth_interval(const DepthSample<T>& s) {
  Rational lo, hi;
  if (s.buffer == DepthBuffer::fixed24) {
    const Rational k(static_cast<unsigned long>(s.stored));
    lo = (k - Rational(1, 2)) / kFixed24Max;
    hi = (k + Rational(1, 2)) / kFixed24Max;
  } else {
    float f;
    std::memcpy(&f, &s.stored, sizeof f);
    const Rational v = oracle::exact::to_rational(f);
    lo = (v + oracle::exact::to_rational(std::nextafter(f, -1.0f))) / 2;
    hi = (v + oracle::exact::to_rational(std::nextafter(f, 2.0f))) / 2;
  }
  const Rational read = oracle::exact::to_rational(s.depth);
  lo = std::max(Rational(0), std::min(lo, read));
  hi = std::min(Rational(1), std::max(hi, read));
  return {lo, hi};
}

/// What judge_view_position() and judge_linear_depth() share: the segment of the ray the stored
/// depth stands for, and how far a reconstruction computed in T may be from it. A solve in T
/// gives homogeneous coordinates v^ within `box` of v = M'^-1 (x, y, z, 1), z in the depth's
/// interval, and its divide by w rounds once more; the answer is judged against that set, which
/// stays bounded in homogeneous coordinates even where rounding can reach w = 0 (a point that
/// float cannot place along its ray is still judged by the ray and the depths it can reach).
struct Segment {
  bool judged = false;
  std::string why;
  Vec a, b;                  ///< the ends (w = 1)
  Vec ha, hb;                ///< the ends in homogeneous coordinates, v at the interval's ends
  Vec box;                   ///< |v^ - v| (with the divide's rounding), per coordinate (x, y, z, w)
  std::optional<Vec> bound;  ///< per coordinate (x, y, z) of the point, where w is determined
  bool w_reaches_zero = false;  ///< whether box_w reaches the segment's w (it keeps its sign)
  int axis = -1;  ///< view_axis_sign of the original; 0 where rounding in T decides it
  bool axis_is_z = true;
};

/// view_axis_sign() in exact arithmetic, from the inverse of the original projection: the sign
/// of the z of its view volume's centre. Given `error` (solve_error()'s S for the original), 0
/// where a solve in T can give the other sign: the centre's z or w within its error of 0, or no
/// S (the inverse not determined in T).
int axis_sign(const Mat& original_inverse, Convention convention,
              const std::optional<std::optional<Mat>>& error = std::nullopt) {
  const DepthRange range = clip_depth_range(convention);
  const Vec b{0, 0, Rational(range.z_low + range.z_high, 2), 1};
  const Vec centre = oracle::exact::mul(original_inverse, b);
  if (error) {
    if (!*error) return 0;
    const Vec dv = oracle::exact::mul(**error, oracle::exact::abs(b));
    if (oracle::exact::abs(centre[2]) <= dv[2] || oracle::exact::abs(centre[3]) <= dv[3]) return 0;
  }
  return (centre[2] > 0) == (centre[3] > 0) ? 1 : -1;
}

/// What a depth judge says before it looks at the answer: not judged where the stored depth
/// has no segment to judge by, violated where the answer is not finite; empty otherwise.
std::optional<ConsumerFinding> before_the_answer(ConsumerCheck check, const Segment& seg,
                                                 bool finite, bool none_finite,
                                                 const std::string& answered) {
  ConsumerFinding f;
  f.check = check;
  if (!seg.judged) {
    f.judged = false;
    f.detail = seg.why;
    return f;
  }
  if (finite) return std::nullopt;
  if (seg.w_reaches_zero && none_finite) {
    // A correct solve in T can give w^ = 0 here, and its divide then gives an infinity (or
    // 0 / 0) in every coordinate: what it answered is one of the answers float arithmetic
    // allows. A finite coordinate beside a non-finite one is not.
    f.holds = true;
    f.ratio = 1;
    f.detail = "answered " + answered + ": a solve in T can reach w = 0 at this depth (w within " +
               text(seg.box[3]) + " of the segment's), and then divides by 0";
    return f;
  }
  f.holds = false;
  f.ratio = std::numeric_limits<double>::infinity();
  f.detail = "answered " + answered + ", not finite";
  return f;
}

template <class T>
Segment ray_segment(const DepthSample<T>& s) {
  Segment out;
  const Mat m = oracle::exact::to_rational(s.projection);
  const std::optional<Mat> inv = oracle::exact::inverse(m);
  const std::optional<Mat> original_inv =
      oracle::exact::inverse(oracle::exact::to_rational(s.original));
  if (!inv || !original_inv) {
    out.why = "a singular projection";
    return out;
  }
  {
    // The view axis is z only where M's fourth row is (0, 0, a, b); elsewhere (a rotated or
    // general matrix) linear depth has no axis to be measured along.
    const Mat original = oracle::exact::to_rational(s.original);
    out.axis_is_z = original[3][0] == 0 && original[3][1] == 0;
    if (out.axis_is_z)
      out.axis = axis_sign(*original_inv, s.convention, solve_error<T>(original, *original_inv));
  }
  const auto [lo, hi] = depth_interval(s);
  const Rational x = oracle::exact::to_rational(s.ndc_x), y = oracle::exact::to_rational(s.ndc_y);
  const std::optional<Mat> error = solve_error<T>(m, *inv);
  if (!error) {
    out.why =
        "the projection's determinant is within T's rounding of 0: its inverse is not "
        "determined in T";
    return out;
  }
  const Rational u = unit<T>();
  Vec ends[2];
  out.box = {0, 0, 0, 0};
  Vec bound{0, 0, 0, 0};
  bool determined = true;
  const Rational depths[2] = {lo, hi};
  for (int e = 0; e < 2; ++e) {
    const Vec b{x, y, ndc_of(depths[e], s.convention), 1};
    const Vec v = oracle::exact::mul(*inv, b);
    if (v[3] == 0) {
      out.why = "the stored depth's interval reaches the ray's point at infinity";
      return out;
    }
    ends[e] = v;
    // |v^ - v| <= dv; the divide v^_i / v^_w rounds once: the answer times v^_w is within
    // u |v^_i| <= u (|v_i| + dv_i) of v^_i. Along the segment, |b| and |v| are at most the
    // larger of their ends' (both linear in the depth, which keeps its sign or passes 0).
    const Vec dv = oracle::exact::mul(*error, oracle::exact::abs(b));
    for (int i = 0; i < 4; ++i) {
      const Rational divide =
          i < 3 ? Rational(u * (oracle::exact::abs(v[i]) + dv[i])) : Rational(0);
      out.box[i] = std::max(out.box[i], Rational(dv[i] + divide));
    }
    if (dv[3] >= oracle::exact::abs(v[3])) {
      determined = false;
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      const Rational p = v[i] / v[3];
      const Rational bound_i =
          (dv[i] + oracle::exact::abs(p) * dv[3]) / (oracle::exact::abs(v[3]) - dv[3]) +
          u * oracle::exact::abs(p);
      bound[i] = std::max(bound[i], bound_i);
    }
  }
  if (ends[0][3] * ends[1][3] < 0) {
    out.why = "the stored depth's interval reaches the ray's point at infinity";
    return out;
  }
  if (determined) out.bound = bound;
  out.w_reaches_zero =
      out.box[3] >= std::min(oracle::exact::abs(ends[0][3]), oracle::exact::abs(ends[1][3]));
  out.ha = ends[0];
  out.hb = ends[1];
  for (int i = 0; i < 4; ++i) {
    out.a[i] = ends[0][i] / ends[0][3];
    out.b[i] = ends[1][i] / ends[1][3];
  }
  out.judged = true;
  return out;
}

/// Whether some lambda and t in [0, 1] put lambda p within `scale` box of v(t) = a + t (b - a)
/// in every coordinate of `coordinates` and lambda within `scale` box_w of v_w(t): whether the
/// point p is the divide of a homogeneous point within the box of the segment. Exact for
/// Rational. Each constraint bounds lambda by lines in t (or, where p_i = 0, bounds t alone);
/// max(lower lines) - min(upper lines) is convex in t, so it is least at an end of t's range or
/// where two of the lines cross.
template <class R>
bool on_projected_segment(const std::array<R, 4>& a, const std::array<R, 4>& b,
                          const std::array<R, 4>& box, const std::array<R, 4>& p,
                          const std::vector<int>& coordinates, const R& scale) {
  struct Line {
    R at0, slope;  // at0 + slope t
    R at(const R& t) const { return at0 + slope * t; }
  };
  std::vector<Line> lower, upper;
  R t_lo = 0, t_hi = 1;
  std::vector<int> all = coordinates;
  all.push_back(3);
  for (int i : all) {
    const R d = b[i] - a[i];
    const R low = a[i] - scale * box[i], high = a[i] + scale * box[i];
    if (p[i] == 0) {
      // low + d t <= 0 <= high + d t
      if (d == 0) {
        if (low > 0 || high < 0) return false;
        continue;
      }
      R t1 = -high / d, t2 = -low / d;
      if (t1 > t2) std::swap(t1, t2);
      t_lo = std::max(t_lo, t1);
      t_hi = std::min(t_hi, t2);
      continue;
    }
    Line l{low / p[i], d / p[i]}, h{high / p[i], d / p[i]};
    if (p[i] < 0) std::swap(l, h);
    lower.push_back(l);
    upper.push_back(h);
  }
  if (t_lo > t_hi) return false;
  auto gap = [&](const R& t) {
    R most = lower.front().at(t), least = upper.front().at(t);
    for (const Line& l : lower) most = std::max(most, l.at(t));
    for (const Line& h : upper) least = std::min(least, h.at(t));
    return most <= least;
  };
  if (gap(t_lo) || gap(t_hi)) return true;
  std::vector<Line> lines = lower;
  lines.insert(lines.end(), upper.begin(), upper.end());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const R ds = lines[i].slope - lines[j].slope;
      if (ds == 0) continue;
      const R t = (lines[j].at0 - lines[i].at0) / ds;
      if (t > t_lo && t < t_hi && gap(t)) return true;
    }
  }
  return false;
}

/// How far a reconstruction in T may be from the segment, for a finding's detail: per
/// coordinate of the point where w is determined, else in homogeneous coordinates.
std::string within_text(const Segment& seg, const std::vector<int>& coordinates) {
  if (seg.bound) {
    if (coordinates.size() == 1) return ", within " + text((*seg.bound)[coordinates.front()]);
    return ", each coordinate within " + text(*seg.bound, 3);
  }
  return "; a solve in T can reach w = 0 there, so the answer is judged in homogeneous "
         "coordinates: (x, y, z, w) within " +
         text(seg.box, 4) + " of the segment's";
}

/// The verdict of on_projected_segment() at scale 1, exactly, with the ratio residual / bound:
/// the least scale of the box that holds p (by bisection in double, kept on the verdict's side
/// of 1).
std::pair<bool, double> judge_on_segment(const Segment& seg, const Vec& p,
                                         const std::vector<int>& coordinates) {
  const bool holds = on_projected_segment<Rational>(seg.ha, seg.hb, seg.box, p, coordinates, 1);
  std::array<double, 4> a, b, box, q;
  for (int i = 0; i < 4; ++i) {
    a[i] = seg.ha[i].get_d();
    b[i] = seg.hb[i].get_d();
    box[i] = seg.box[i].get_d();
    q[i] = p[i].get_d();
  }
  auto within = [&](double scale) {
    return on_projected_segment<double>(a, b, box, q, coordinates, scale);
  };
  double hi = 1;
  for (int k = 0; k < 64 && !within(hi); ++k) hi *= 2;
  double ratio = std::numeric_limits<double>::infinity();
  if (within(hi)) {
    double lo = 0;
    for (int k = 0; k < 60; ++k) {
      const double mid = (lo + hi) / 2;
      (within(mid) ? hi : lo) = mid;
    }
    ratio = hi;
  }
  if (holds) return {true, std::min(ratio, 1.0)};
  return {false, std::max(ratio, std::nextafter(1.0, 2.0))};
}

constexpr const char* kNotProper =
    "a corner of the original view volume is behind the eye in exact arithmetic";

/// The kept region's vertices, exactly (polytope::clip_volume on M's exact corners); empty when
/// M is singular or a corner of its volume is behind the eye (w < 0: the volume wraps through
/// infinity, and has no kept region to judge by).
template <class T>
std::optional<std::vector<Vec>> exact_kept_region(const Matrix4<T>& m, const Vector4<T>& c,
                                                  Convention convention) {
  const std::optional<Mat> inv = oracle::exact::inverse(oracle::exact::to_rational(m));
  if (!inv) return std::nullopt;
  std::array<Vec, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const std::array<int, 4> q = clip_corner(i, convention);
    Vec v = oracle::exact::mul(*inv, {q[0], q[1], q[2], q[3]});
    if (v[3] < 0) return std::nullopt;
    corners[static_cast<std::size_t>(i)] = v;
  }
  std::vector<Vec> out;
  for (const Vec& x : polytope::clip_volume(corners, oracle::exact::to_rational(c))) {
    if (std::find(out.begin(), out.end(), x) == out.end()) out.push_back(x);
  }
  return out;
}

}  // namespace

std::string_view not_applicable(ConsumerCheck check, cases::Family family) {
  using cases::Family;
  if (check == ConsumerCheck::corners_contain_kept && family == Family::infinite)
    return "an infinite frustum's kept region is unbounded";
  if (check == ConsumerCheck::linear_depth &&
      (family == Family::rotated || family == Family::general))
    return "its camera does not look along z";
  return "";
}

std::string describe(const ConsumerFinding& f) {
  std::string out(consumer_check_name(f.check));
  if (!f.judged) return out + ": not judged: " + f.detail;
  out += f.holds ? " holds: " : " violated: ";
  out += f.detail;
  out += " (residual / bound " + protocol::format_number(f.ratio) + ")";
  return out;
}

template <class T>
std::optional<DepthSample<T>> depth_sample(const Matrix4<T>& projection, const Matrix4<T>& original,
                                           Convention convention, DepthBuffer buffer,
                                           const Vector4<T>& point) {
  if (!projection.allFinite() || !point.allFinite()) return std::nullopt;
  const Vec clip =
      oracle::exact::mul(oracle::exact::to_rational(projection), oracle::exact::to_rational(point));
  if (!(clip[3] > 0)) return std::nullopt;
  const Rational window = window_of(clip[2] / clip[3], convention);
  if (window < 0 || window > 1) return std::nullopt;
  DepthSample<T> s;
  s.projection = projection;
  s.original = original;
  s.convention = convention;
  s.buffer = buffer;
  s.ndc_x = oracle::exact::round_to<T>(clip[0] / clip[3]);
  s.ndc_y = oracle::exact::round_to<T>(clip[1] / clip[3]);
  if (buffer == DepthBuffer::fixed24) {
    const Rational scaled = window * kFixed24Max + Rational(1, 2);
    const mpz_class k = scaled.get_num() / scaled.get_den();  // floor: both positive
    s.stored = static_cast<std::uint32_t>(k.get_ui());
    s.depth = oracle::exact::round_to<T>(Rational(k) / kFixed24Max);
  } else {
    const float f = oracle::exact::round_to<float>(window);
    std::memcpy(&s.stored, &f, sizeof f);
    s.depth = static_cast<T>(f);
  }
  return s;
}

/// ray_segment() of the last sample judged on this thread: a round asks view_position and
/// linear_depth of the same sample, and its exact analysis is most of either judge's time.
template <class T>
const Segment& ray_segment_of(const DepthSample<T>& s) {
  thread_local std::optional<std::pair<DepthSample<T>, Segment>> last;
  const bool same = last && last->first.projection == s.projection &&
                    last->first.original == s.original && last->first.convention == s.convention &&
                    last->first.buffer == s.buffer && last->first.ndc_x == s.ndc_x &&
                    last->first.ndc_y == s.ndc_y && last->first.depth == s.depth &&
                    last->first.stored == s.stored;
  if (!same) last.emplace(s, ray_segment(s));
  return last->second;
}

template <class T>
ConsumerFinding judge_view_position(const DepthSample<T>& s, const Vector3<T>& answer) {
  const Segment& seg = ray_segment_of(s);
  if (auto early = before_the_answer(ConsumerCheck::view_position, seg, answer.allFinite(),
                                     !answer.array().isFinite().any(), numbers_text(answer)))
    return *early;
  ConsumerFinding f;
  f.check = ConsumerCheck::view_position;
  const auto [ok, ratio] = judge_on_segment(seg, point_of(answer), {0, 1, 2});
  f.holds = ok;
  f.ratio = ratio;
  f.points = {answer.template cast<double>(), approx_point(seg.a), approx_point(seg.b)};
  f.points_what = "the answer, and the ends of the pixel ray's segment the stored depth stands for";
  f.detail = "answered " + numbers_text(answer) + "; the stored depth stands for the points from " +
             text(seg.a, 3) + " to " + text(seg.b, 3) + within_text(seg, {0, 1, 2});
  return f;
}

template <class T>
ConsumerFinding judge_linear_depth(const DepthSample<T>& s, T answer) {
  const Segment& seg = ray_segment_of(s);
  if (auto early = before_the_answer(ConsumerCheck::linear_depth, seg, std::isfinite(answer),
                                     !std::isfinite(answer), protocol::format_number(answer)))
    return *early;
  ConsumerFinding f;
  f.check = ConsumerCheck::linear_depth;
  if (!seg.axis_is_z) {
    f.judged = false;
    f.detail = "the camera does not look along z (M's fourth row is not (0, 0, a, b))";
    return f;
  }
  if (seg.axis == 0) {
    // Which way the camera looks (the sign of its view volume's centre's z) is rounding in T.
    f.judged = false;
    f.detail =
        "the camera's axis is not determined in T (its view volume's centre is within a "
        "solve's rounding of z = 0 or of w = 0)";
    return f;
  }
  const Rational sign = seg.axis;
  // The answer is axis z: the point's z is axis times it.
  const Vec given{0, 0, sign * oracle::exact::to_rational(answer), 1};
  const auto [ok, ratio] = judge_on_segment(seg, given, {2});
  f.holds = ok;
  f.ratio = ratio;
  f.points = {approx_point(seg.a), approx_point(seg.b)};
  f.points_what = "the ends of the pixel ray's segment the stored depth stands for";
  f.detail = "answered " + protocol::format_number(answer) +
             "; the stored depth stands for linear depths from " + text(Rational(sign * seg.a[2])) +
             " to " + text(Rational(sign * seg.b[2])) + within_text(seg, {2});
  return f;
}

template <class T>
std::vector<ConsumerFinding> judge_culling_planes(const Matrix4<T>& m, const Vector4<T>& c,
                                                  Convention convention, const Matrix4<T>& oblique,
                                                  const FrustumPlanes<T>& answer) {
  ConsumerFinding keeps, near;
  keeps.check = ConsumerCheck::culling_keeps_visible;
  near.check = ConsumerCheck::culling_near_is_c;
  const Problem<T> problem(m, c, convention);
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
  const std::optional<std::vector<Vec>> region = exact_kept_region(m, c, convention);
  if (!region) {
    keeps.judged = false;
    keeps.detail = kNotProper;
  }
  const std::vector<Vec> kept = region ? *region : std::vector<Vec>{};
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
    for (const Vec& v : kept) {
      const Rational value = oracle::exact::dot(p, v);
      const Rational slack = g * oracle::exact::dot(oracle::exact::abs(p), oracle::exact::abs(v)) +
                             rho * max_abs(p) * sum_abs(v);
      if (value >= 0) continue;
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

template <class T>
std::vector<ConsumerFinding> judge_camera_plane(const Matrix4<T>& pass_view,
                                                const Vector4<T>& world_plane,
                                                const std::vector<Vector4<T>>& surface_points,
                                                const Vector4<T>& front_point,
                                                const Vector4<T>& answer) {
  ConsumerFinding on, side;
  on.check = ConsumerCheck::plane_on_surface;
  side.check = ConsumerCheck::plane_kept_side;
  const Mat w = oracle::exact::to_rational(pass_view);
  const std::optional<Mat> inv = oracle::exact::inverse(w);
  if (!inv || !answer.allFinite()) {
    on.judged = side.judged = !inv ? false : true;
    if (!inv) {
      on.detail = side.detail = "a singular view";
      return {on, side};
    }
    on.holds = side.holds = false;
    on.ratio = side.ratio = std::numeric_limits<double>::infinity();
    on.detail = side.detail = "answered " + numbers_text(answer) + ", not a finite plane";
    return {on, side};
  }
  const Mat inv_t = oracle::exact::transpose(*inv);
  const Vec world = oracle::exact::to_rational(world_plane);
  const Vec reference = oracle::exact::mul(inv_t, world);
  const Vec p = oracle::exact::to_rational(answer);
  const Rational rr = oracle::exact::dot(reference, reference);
  const Rational lambda = rr > 0 ? Rational(oracle::exact::dot(p, reference) / rr) : Rational(0);
  const Vec chain =
      oracle::exact::mul(mul(mul(oracle::exact::abs(inv_t), lu_bound(oracle::exact::transpose(w))),
                             oracle::exact::abs(inv_t)),
                         oracle::exact::abs(world));
  Vec bound;
  for (int i = 0; i < 4; ++i)
    bound[i] = oracle::exact::abs(lambda) * gamma_of<T>(oracle::tolerance::kCameraPlaneRoundings) *
                   chain[i] +
               gamma_of<T>(oracle::tolerance::kPlaneRoundings) * oracle::exact::abs(p[i]);

  double worst = 0;
  for (const Vector4<T>& x : surface_points) {
    Vec xe = oracle::exact::to_rational(x);
    // On the plane exactly: x projected onto it in rational arithmetic.
    const Rational nn = world[0] * world[0] + world[1] * world[1] + world[2] * world[2];
    const Rational off = oracle::exact::dot(world, xe) / nn;
    for (int i = 0; i < 3; ++i) xe[i] -= off * world[i] * xe[3];
    const Vec y = oracle::exact::mul(w, xe);
    const Rational value = oracle::exact::dot(p, y);
    const Rational slack = oracle::exact::dot(bound, oracle::exact::abs(y));
    const double r = ratio_of(value, slack);
    if (r > worst) {
      worst = r;
      if (oracle::exact::abs(value) > slack) {
        on.holds = false;
        on.detail = "the surface's point " + text(xe, 3) + " is at camera-space " + text(y, 3) +
                    ", where the plane " + numbers_text(answer) + " gives " + text(value) +
                    " instead of 0 (within " + text(slack) + ")";
      }
    }
  }
  on.ratio = on.holds ? std::min(worst, 1.0) : worst;
  if (on.holds)
    on.detail = "the surface's " + std::to_string(surface_points.size()) +
                " points land on the plane " + numbers_text(answer);

  const Vec y = oracle::exact::mul(w, oracle::exact::to_rational(front_point));
  const Rational value = oracle::exact::dot(p, y);
  const Rational slack = oracle::exact::dot(bound, oracle::exact::abs(y));
  side.holds = !(value < 0 && -value > slack);
  side.ratio = value >= 0 ? 0.0 : ratio_of(value, slack);
  side.detail = "a point in front of the surface, camera-space " + text(y, 3) + ", is on the " +
                (value > 0   ? "kept"
                 : value < 0 ? "clipped"
                             : "boundary") +
                " side of " + numbers_text(answer) + " (P . x = " + text(value) + ")";
  if (!on.holds || !side.holds) {
    // The pass camera's space: the camera, the surface's points and the one in front, the plane
    // as it should be and as answered, each a square around the points.
    std::vector<Eigen::Vector3d> points;
    for (const Vector4<T>& x : surface_points)
      points.push_back(approx_point(oracle::exact::mul(w, oracle::exact::to_rational(x))));
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& x : points) centre += x;
    centre /= static_cast<double>(std::max<std::size_t>(points.size(), 1));
    double half = 0;
    for (const Eigen::Vector3d& x : points) half = std::max(half, (x - centre).norm());
    if (!(half > 0) || !std::isfinite(half)) half = 1;
    const Eigen::Vector4d should(reference[0].get_d(), reference[1].get_d(), reference[2].get_d(),
                                 reference[3].get_d());
    std::vector<ConsumerFinding::Drawn> drawn = {
        {"the pass camera (eye, view direction, up)",
         {{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, -half)},
          {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0.4 * half, 0)}},
         {Eigen::Vector3d::Zero()}},
        {"the plane as it should be (normal toward the kept side)",
         plane_square(should, centre, half),
         {}},
        {"the plane as answered", plane_square(answer.template cast<double>(), centre, half), {}},
        {"the surface's points", {}, points},
        {"a point in front of the surface", {}, {approx_point(y)}}};
    for (ConsumerFinding* f : {&on, &side}) {
      if (f->holds) continue;
      f->drawn = drawn;
      f->drawn_space = "the pass camera's space";
    }
  }
  return {on, side};
}

namespace {

template <class T>
ConsumerFinding compare_matrix(ConsumerCheck check, const Mat& reference, const Mat& bound,
                               const Matrix4<T>& answer) {
  ConsumerFinding f;
  f.check = check;
  if (!answer.allFinite()) {
    f.holds = false;
    f.ratio = std::numeric_limits<double>::infinity();
    f.detail = "the answer is not finite";
    return f;
  }
  const Mat given = oracle::exact::to_rational(answer);
  double worst = 0;
  int wi = 0, wj = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Rational diff = given[i][j] - reference[i][j];
      const double r = ratio_of(diff, bound[i][j]);
      if (r > worst) {
        worst = r;
        wi = i;
        wj = j;
      }
      if (oracle::exact::abs(diff) > bound[i][j]) f.holds = false;
    }
  }
  f.ratio = worst;
  auto det3 = [](const Mat& m) -> Rational {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  f.detail = "entry (" + std::to_string(wi + 1) + ", " + std::to_string(wj + 1) + ") is " +
             protocol::format_number(answer(wi, wj)) + ", should be " + text(reference[wi][wj]) +
             " within " + text(bound[wi][wj]) + "; det of its 3 x 3 (the handedness) is " +
             (det3(given) < 0 ? "negative" : "positive") + ", should be " +
             (det3(reference) < 0 ? "negative" : "positive");
  return f;
}

}  // namespace

template <class T>
ConsumerFinding judge_mirror_view(const Matrix4<T>& view, const Vector4<T>& world_plane,
                                  const Matrix4<T>& answer, MirrorDesign design) {
  const Mat v = oracle::exact::to_rational(view);
  const Vec plane = oracle::exact::to_rational(world_plane);
  const Rational nn = plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2];
  if (nn == 0) {
    ConsumerFinding f;
    f.check = ConsumerCheck::mirror_view;
    f.judged = false;
    f.detail = "a plane without a normal";
    return f;
  }
  Mat r{}, r_abs{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      r[i][j] = i == j ? 1 : 0;
      r_abs[i][j] = r[i][j];
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Rational term = 2 * plane[i] * plane[j] / nn;
      r[i][j] -= term;
      r_abs[i][j] += oracle::exact::abs(term);
    }
    r[i][3] = -2 * plane[3] * plane[i] / nn;
    r_abs[i][3] = oracle::exact::abs(r[i][3]);
  }
  // The two designs: view R, and diag(-1, 1, 1, 1) view R (row 1 negated, exactly: the bound
  // is the same).
  const Mat reflected = mul(v, r);
  Mat proper = reflected;
  for (Rational& x : proper[0]) x = -x;
  const bool proper_declared = design == MirrorDesign::proper_camera;
  const Mat& reference = proper_declared ? proper : reflected;
  Mat bound = mul(oracle::exact::abs(v), r_abs);
  const Rational g = gamma_of<T>(oracle::tolerance::kPassViewRoundings);
  for (auto& row : bound) {
    for (auto& x : row) x *= g;
  }
  // A pass camera built as a camera (a look-at of the reflected eye: normalised axes, cross
  // products) errs relative to its rows, not to each entry: an entry that is 1e-19 exactly may
  // come out 0. So each entry of the 3 x 3 block is held within its row's largest bound, and the
  // translation, t_i = -row_i . eye, within that times |eye|_1 more (eye: the pass camera's
  // position, exact). What a point at unit distance sees is the same either way.
  const std::optional<Mat> to_world = oracle::exact::inverse(reference);
  Rational eye_size = 0;
  if (to_world) {
    for (int k = 0; k < 3; ++k) eye_size += oracle::exact::abs((*to_world)[k][3]);
  }
  for (auto& row : bound) {
    const Rational largest = std::max({row[0], row[1], row[2]});
    for (int j = 0; j < 3; ++j) row[j] = largest;
    row[3] += largest * eye_size;
  }
  ConsumerFinding f = compare_matrix(ConsumerCheck::mirror_view, reference, bound, answer);
  if (f.holds) {
    f.detail = std::string("the ") + (proper_declared ? "proper_camera" : "reflected_view") +
               " design's matrix (" + (proper_declared ? "diag(-1, 1, 1, 1) view R" : "view R") +
               "), " + f.detail;
  } else if (answer.allFinite() &&
             compare_matrix(ConsumerCheck::mirror_view, proper_declared ? reflected : proper, bound,
                            answer)
                 .holds) {
    // The other design: named as such, not as a broken mirror.
    f.detail =
        proper_declared
            ? "the answer is the reflected_view design, view R (an improper camera, det < 0), "
              "while the proper_camera design is declared (diag(-1, 1, 1, 1) view R, the flip done "
              "in the projection or the texture): with both, the image is flipped twice. " +
                  f.detail
            : "the answer is the proper_camera design, diag(-1, 1, 1, 1) view R (a proper camera, "
              "det > 0, looking at the reflected scene), not the reflected view R: right only "
              "when the horizontal flip is done in the projection or the texture lookup; if it "
              "is, declare the design (Consumers::mirror_design = MirrorDesign::proper_camera; "
              "verify --mirror-design proper_camera). " +
                  f.detail;
  }
  if (!f.holds) {
    const Eigen::Matrix4d main_view = view.template cast<double>();
    const ConsumerFinding::Drawn main = camera_drawn("the main camera", main_view, 1);
    const Eigen::Vector4d mirror = world_plane.template cast<double>();
    const Eigen::Vector3d eye = main.points.empty() ? Eigen::Vector3d::Zero() : main.points[0];
    const double distance =
        std::abs(mirror.head<3>().dot(eye) + mirror.w()) / mirror.head<3>().norm();
    const double length = std::isfinite(distance) && distance > 0 ? distance : 1;
    f.drawn = {
        camera_drawn("the main camera", main_view, length),
        camera_drawn("the mirror pass's camera as it should be", approx_matrix(reference), length),
        camera_drawn("the mirror pass's camera as answered", answer.template cast<double>(),
                     length),
        {"the mirror (normal toward its front)", plane_square(mirror, eye, length), {}}};
    f.drawn_space = "world space";
  }
  return f;
}

template <class T>
ConsumerFinding judge_portal_view(const Matrix4<T>& view, const Matrix4<T>& frame,
                                  const Matrix4<T>& linked, const Matrix4<T>& answer) {
  const Mat l = oracle::exact::to_rational(linked);
  const std::optional<Mat> l_inv = oracle::exact::inverse(l);
  if (!l_inv) {
    ConsumerFinding f;
    f.check = ConsumerCheck::portal_view;
    f.judged = false;
    f.detail = "a singular portal frame";
    return f;
  }
  Mat turn{};
  turn[0][0] = -1;
  turn[1][1] = 1;
  turn[2][2] = -1;
  turn[3][3] = 1;
  const Mat v = oracle::exact::to_rational(view), fr = oracle::exact::to_rational(frame);
  const Mat reference = mul(mul(mul(v, fr), turn), *l_inv);
  Mat bound = mul(mul(oracle::exact::abs(v), oracle::exact::abs(fr)),
                  mul(mul(oracle::exact::abs(*l_inv), lu_bound(l)), oracle::exact::abs(*l_inv)));
  const Rational g = gamma_of<T>(oracle::tolerance::kPassViewRoundings);
  for (auto& row : bound)
    for (auto& x : row) x *= g;
  ConsumerFinding f = compare_matrix(ConsumerCheck::portal_view, reference, bound, answer);
  if (!f.holds) {
    const Eigen::Matrix4d main_view = view.template cast<double>();
    const Eigen::Matrix4d here = frame.template cast<double>(),
                          there = linked.template cast<double>();
    const ConsumerFinding::Drawn main = camera_drawn("the main camera", main_view, 1);
    const Eigen::Vector3d eye = main.points.empty() ? Eigen::Vector3d::Zero() : main.points[0];
    const double distance = (here.col(3).head<3>() - eye).norm();
    const double length = std::isfinite(distance) && distance > 0 ? distance : 1;
    auto portal = [](const Eigen::Matrix4d& fr) {
      return plane_square(
          plane_from_normal_and_point<double>(fr.block<3, 1>(0, 2), fr.block<3, 1>(0, 3)),
          fr.block<3, 1>(0, 3), 1);
    };
    f.drawn = {
        camera_drawn("the main camera", main_view, length),
        camera_drawn("the portal pass's camera as it should be", approx_matrix(reference), length),
        camera_drawn("the portal pass's camera as answered", answer.template cast<double>(),
                     length),
        {"this portal (normal toward its front)", portal(here), {}},
        {"the linked portal", portal(there), {}}};
    f.drawn_space = "world space";
  }
  return f;
}

template <class T>
ConsumerFinding judge_corners(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                              const Matrix4<T>& oblique, const std::vector<Vector3<T>>& answer,
                              Arithmetic arithmetic) {
  ConsumerFinding f;
  f.check = ConsumerCheck::corners_contain_kept;
  const Problem<T> problem(m, c, convention);
  const std::optional<oracle::exact::Vec> row3 =
      problem.exact_status() == Status::ok ? problem.row3_bounds() : std::nullopt;
  if (!row3 || problem.infinite()) {
    f.judged = false;
    f.detail = row3 ? "an infinite projection: the kept region is unbounded"
                    : "the case has no answer to judge against";
    return f;
  }
  const std::optional<std::vector<Vec>> region = exact_kept_region(m, c, convention);
  if (!region) {
    f.judged = false;
    f.detail = kNotProper;
    return f;
  }
  const std::vector<Vec>& kept = *region;
  for (const Vec& v : kept) {
    if (v[3] == 0) {
      f.judged = false;
      f.detail = "the kept region is unbounded";
      return f;
    }
  }
  std::vector<Vec> points;
  for (const Vector3<T>& p : answer) {
    if (!p.allFinite()) {
      f.holds = false;
      f.ratio = std::numeric_limits<double>::infinity();
      f.detail = "the corner " + numbers_text(p) + " is not finite";
      return f;
    }
    const Vec x = point_of(p);
    if (std::find(points.begin(), points.end(), x) == points.end()) points.push_back(x);
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
  const Mat mo = oracle::exact::to_rational(oblique);
  const Mat mx = oracle::exact::to_rational(m);
  const std::optional<Mat> inv = oracle::exact::inverse(mo);
  const std::optional<Mat> m_inv = oracle::exact::inverse(mx);
  if (!inv || !m_inv) {
    f.judged = false;
    f.detail = "a singular matrix";
    return f;
  }
  // Each solve's error from the matrix at hand (solve_error(): cofactors or elimination, the
  // larger), not partial pivoting's worst case.
  const std::optional<Mat> chain = solve_error<T>(mo, *inv);
  const std::optional<Mat> m_chain = solve_error<T>(mx, *m_inv);
  if (!chain || !m_chain) {
    f.judged = false;
    f.detail = "a projection's determinant is within T's rounding of 0";
    return f;
  }
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
    for (const auto& [solve, with_m] : {std::pair{&*chain, true}, std::pair{&*m_chain, false}}) {
      const Mat& matrix = with_m ? mo : mx;
      Vec q =
          oracle::exact::abs(oracle::exact::mul(matrix, x));  // its clip-space point, widened below
      for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 3; ++k) q[r] += oracle::exact::abs(matrix[r][k]) * widen;
      Vec dv = oracle::exact::mul(*solve, q);
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
        const Mat& error = out.with_m ? *chain : *m_chain;
        const Mat& inverse = out.with_m ? *inv : *m_inv;
        for (std::size_t i = 0; i < 4; ++i) {
          out.inverse_column[i] = range_of(oracle::exact::abs(inverse[i][2]));
          for (std::size_t j = 0; j < 4; ++j) {
            out.matrix[i][j] = certified_of(matrix[i][j]);
            out.magnitude[i][j] = range_of(oracle::exact::abs(matrix[i][j]));
            out.error[i][j] = range_of(error[i][j]);
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
  // The hull's facets: planes through three corners with every corner on one side.
  struct Facet {
    Vec origin, normal;  // inward normal (x, y, z; w unused)
  };
  std::vector<Facet> facets;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Vec e1, e2, normal{0, 0, 0, 0};
        for (int d = 0; d < 3; ++d) {
          e1[d] = points[j][d] - points[i][d];
          e2[d] = points[k][d] - points[i][d];
        }
        normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
        normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
        normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
        if (normal[0] == 0 && normal[1] == 0 && normal[2] == 0) continue;
        bool any_above = false, any_below = false;
        for (const Vec& x : points) {
          Rational s = 0;
          for (int d = 0; d < 3; ++d) s += normal[d] * (x[d] - points[i][d]);
          any_above = any_above || s > 0;
          any_below = any_below || s < 0;
        }
        if (!any_below) facets.push_back({points[i], normal});
        if (!any_above) {
          Vec flipped = normal;
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
  for (const Vec& v : kept) {
    for (const Facet& facet : facets) {
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

namespace {

using protocol::ConsumerKind;

template <class T>
ConsumerAsk<T> depth_ask(ConsumerKind kind, const DepthSample<T>& s, const std::string& inputs) {
  ConsumerAsk<T> a;
  a.kind = kind;
  a.request = [kind, s] { return wire::depth_request(kind, s); };
  if (kind == ConsumerKind::view_position) {
    a.call = [s](const Consumers<T>& c) { return wire::numbers_of(c.view_position(s)); };
    a.judge = [s, inputs](const std::vector<T>& v, const Settle& settle) {
      const Vector3<T> answer = wire::vector3(v);
      settle(judge_view_position(s, answer), inputs + "- answered: " + numbers_text(answer) + "\n",
             true);
    };
  } else {
    a.call = [s](const Consumers<T>& c) { return std::vector<T>{c.linear_depth(s)}; };
    a.judge = [s, inputs](const std::vector<T>& v, const Settle& settle) {
      settle(judge_linear_depth(s, v.front()),
             inputs + "- answered: " + protocol::format_number(v.front()) + "\n", true);
    };
  }
  return a;
}

template <class T>
ConsumerAsk<T> culling_ask(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                           const Matrix4<T>& mo, const std::string& base) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::culling_planes;
  a.request = [mo, convention] { return wire::culling_request(mo, convention); };
  a.call = [mo, convention](const Consumers<T>& k) {
    return wire::numbers_of(k.culling_planes(mo, convention));
  };
  a.judge = [m, c, convention, mo, base](const std::vector<T>& v, const Settle& settle) {
    const FrustumPlanes<T> p = wire::planes(v);
    const std::string inputs =
        base + "- the planes: left " + numbers_text(p.left) + ", right " + numbers_text(p.right) +
        ", bottom " + numbers_text(p.bottom) + ", top " + numbers_text(p.top) + ", near " +
        numbers_text(p.near_plane) + ", far " + numbers_text(p.far_plane) + "\n";
    for (const auto& f : judge_culling_planes(m, c, convention, mo, p)) settle(f, inputs, true);
  };
  return a;
}

template <class T>
ConsumerAsk<T> corners_ask(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                           const Matrix4<T>& mo, const std::string& base) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::corners;
  a.request = [mo, m, convention] { return wire::corners_request(mo, m, convention); };
  a.call = [mo, m, convention](const Consumers<T>& k) {
    return wire::numbers_of(k.corners(mo, m, convention));
  };
  a.judge = [m, c, convention, mo, base](const std::vector<T>& v, const Settle& settle) {
    const std::vector<Vector3<T>> corners = wire::points(v);
    std::string listed;
    for (const auto& x : corners) listed += " " + numbers_text(x);
    settle(judge_corners(m, c, convention, mo, corners), base + "- the corners:" + listed + "\n",
           true);
  };
  return a;
}

template <class T>
ConsumerAsk<T> camera_plane_ask(const oracle::consumer_cases::PassPlaneCase<T>& p) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::camera_plane;
  a.request = [p] {
    return wire::view_and_plane_request(ConsumerKind::camera_plane, p.pass_view, p.kept_plane);
  };
  a.call = [p](const Consumers<T>& k) {
    return wire::numbers_of(k.camera_plane(p.pass_view, p.kept_plane));
  };
  a.judge = [p](const std::vector<T>& v, const Settle& settle) {
    const Vector4<T> answer = wire::vector4(v);
    const std::string inputs = std::string("- pass: ") +
                               std::string(oracle::consumer_cases::pass_kind_name(p.kind)) +
                               "\n- main view: " + numbers_text(p.main_view) +
                               "\n- pass view: " + numbers_text(p.pass_view) +
                               "\n- world plane kept: " + numbers_text(p.kept_plane) +
                               "\n- answered: " + numbers_text(answer) + "\n";
    for (const auto& f :
         judge_camera_plane(p.pass_view, p.kept_plane, p.surface_points, p.front_point, answer))
      settle(f, inputs, false);
  };
  return a;
}

template <class T>
ConsumerAsk<T> mirror_view_ask(const Matrix4<T>& view, const Vector4<T>& mirror,
                               MirrorDesign design) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::mirror_view;
  a.request = [view, mirror] {
    return wire::view_and_plane_request(ConsumerKind::mirror_view, view, mirror);
  };
  a.call = [view, mirror](const Consumers<T>& k) {
    return wire::numbers_of(k.mirror_view(view, mirror));
  };
  a.judge = [view, mirror, design](const std::vector<T>& v, const Settle& settle) {
    const Matrix4<T> answer = wire::matrix4(v);
    settle(judge_mirror_view(view, mirror, answer, design),
           "- view: " + numbers_text(view) + "\n- mirror plane: " + numbers_text(mirror) +
               "\n- answered: " + numbers_text(answer) + "\n",
           false);
  };
  return a;
}

template <class T>
ConsumerAsk<T> portal_view_ask(const Matrix4<T>& view, const Matrix4<T>& frame,
                               const Matrix4<T>& linked) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::portal_view;
  a.request = [view, frame, linked] { return wire::portal_request(view, frame, linked); };
  a.call = [view, frame, linked](const Consumers<T>& k) {
    return wire::numbers_of(k.portal_view(view, frame, linked));
  };
  a.judge = [view, frame, linked](const std::vector<T>& v, const Settle& settle) {
    const Matrix4<T> answer = wire::matrix4(v);
    settle(judge_portal_view(view, frame, linked, answer),
           "- view: " + numbers_text(view) + "\n- frame: " + numbers_text(frame) +
               "\n- linked frame: " + numbers_text(linked) +
               "\n- answered: " + numbers_text(answer) + "\n",
           false);
  };
  return a;
}

/// Asks an in-process Consumers and judges its answer.
template <class T>
void ask_and_judge(const ConsumerAsk<T>& a, const Consumers<T>& consumers, const Settle& settle) {
  a.judge(a.call(consumers), settle);
}

}  // namespace

template <class T>
std::vector<ConsumerAsk<T>> consumer_asks(const Matrix4<T>& m, const Vector4<T>& c,
                                          Convention convention, const Consumers<T>& consumers,
                                          const Pick& pick, const Settle& settle) {
  std::vector<ConsumerAsk<T>> asks;
  const bool needs_oblique = consumers.view_position || consumers.linear_depth ||
                             consumers.culling_planes || consumers.corners;
  // A case none of `checks` can be judged on: one finding left out for each of them.
  auto left_out = [&settle](std::initializer_list<std::pair<bool, ConsumerCheck>> checks,
                            const std::string& why) {
    for (const auto& [asked, check] : checks) {
      if (!asked) continue;
      ConsumerFinding none;
      none.check = check;
      none.judged = false;
      none.detail = why;
      settle(none, "", false);
    }
  };
  const bool depth = consumers.view_position || consumers.linear_depth;
  if (needs_oblique && consumers.accepts && !consumers.accepts(convention, m)) {
    left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
              {bool(consumers.linear_depth), ConsumerCheck::linear_depth},
              {bool(consumers.culling_planes), ConsumerCheck::culling_keeps_visible},
              {bool(consumers.culling_planes), ConsumerCheck::culling_near_is_c},
              {bool(consumers.corners), ConsumerCheck::corners_contain_kept}},
             "refused by accepts (" + consumers.name + ")");
  } else if (needs_oblique) {
    const ObliqueResult<T> result = apply<T>(m, c, convention);
    if (result.status != Status::ok) {
      const bool culling = bool(consumers.culling_planes);
      left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
                {bool(consumers.linear_depth), ConsumerCheck::linear_depth},
                {culling, ConsumerCheck::culling_keeps_visible},
                {culling, ConsumerCheck::culling_near_is_c},
                {bool(consumers.corners), ConsumerCheck::corners_contain_kept}},
               "no oblique matrix for M and C (" + std::string(status_code(result.status)) + ")");
    } else {
      const Matrix4<T>& mo = result.projection;
      const std::string base =
          "- convention: " + std::string(convention_name(convention)) +
          "\n- M: " + numbers_text(m) + "\n- C: " + numbers_text(c) +
          "\n- M' (the core's answer, what the consumer was given): " + numbers_text(mo) + "\n";
      if (depth) {
        Vector4<T> point = oracle::consumer_cases::kept_point<T>(m, c, convention, pick);
        const DepthBuffer buffer = pick(0, 2) ? DepthBuffer::float32 : DepthBuffer::fixed24;
        auto s = depth_sample(mo, m, convention, buffer, point);
        // A vertex of the region rounds to either side of its plane, and a point pushed toward
        // infinity can pass behind the eye: moved inward step by step (to the centre at most),
        // it is still a point of the region, near where it was, with a sample to judge.
        for (int k : {20, 10, 4, 1, 0}) {
          if (s) break;
          point =
              oracle::consumer_cases::toward_centre(m, c, convention, point, std::ldexp(1.0L, -k));
          s = depth_sample(mo, m, convention, buffer, point);
        }
        if (!s) {
          left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
                    {bool(consumers.linear_depth), ConsumerCheck::linear_depth}},
                   "the point leaves no depth sample (behind the eye or outside [0, 1])");
        } else {
          const std::string inputs = base + "- buffer: " + std::string(depth_buffer_name(buffer)) +
                                     "\n- the point: " + numbers_text(point) +
                                     "\n- the sample: NDC x " + protocol::format_number(s->ndc_x) +
                                     ", y " + protocol::format_number(s->ndc_y) +
                                     ", window depth " + protocol::format_number(s->depth) +
                                     " (stored " + std::to_string(s->stored) + ")\n";
          if (consumers.view_position)
            asks.push_back(depth_ask(ConsumerKind::view_position, *s, inputs));
          if (consumers.linear_depth)
            asks.push_back(depth_ask(ConsumerKind::linear_depth, *s, inputs));
        }
      }
      if (consumers.culling_planes) asks.push_back(culling_ask(m, c, convention, mo, base));
      if (consumers.corners) asks.push_back(corners_ask(m, c, convention, mo, base));
    }
  }
  if (consumers.camera_plane)
    asks.push_back(camera_plane_ask(oracle::consumer_cases::pass_plane_case<T>(pick)));
  if (consumers.mirror_view) {
    const Matrix4<T> view = oracle::consumer_cases::rigid_view<T>(pick);
    asks.push_back(mirror_view_ask(view, oracle::consumer_cases::world_plane<T>(pick),
                                   consumers.mirror_design));
  }
  if (consumers.portal_view) {
    const Matrix4<T> view = oracle::consumer_cases::rigid_view<T>(pick);
    const Matrix4<T> frame = oracle::consumer_cases::portal_frame<T>(pick);
    asks.push_back(portal_view_ask(view, frame, oracle::consumer_cases::portal_frame<T>(pick)));
  }
  return asks;
}

template <class T>
void consumer_round(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                    const Consumers<T>& consumers, const Pick& pick, const Settle& settle) {
  for (const ConsumerAsk<T>& a : consumer_asks(m, c, convention, consumers, pick, settle))
    ask_and_judge(a, consumers, settle);
}

}  // namespace oblique::oracle

namespace oblique::oracle::consumer_cases {

template <class T>
void ask_camera_plane(const Consumers<T>& consumers, const PassPlaneCase<T>& p,
                      const oracle::Settle& settle) {
  oracle::ask_and_judge(oracle::camera_plane_ask(p), consumers, settle);
}

template <class T>
void ask_mirror_view(const Consumers<T>& consumers, const Matrix4<T>& view,
                     const Vector4<T>& mirror, const oracle::Settle& settle) {
  oracle::ask_and_judge(oracle::mirror_view_ask(view, mirror, consumers.mirror_design), consumers,
                        settle);
}

template <class T>
void ask_portal_view(const Consumers<T>& consumers, const Matrix4<T>& view, const Matrix4<T>& frame,
                     const Matrix4<T>& linked, const oracle::Settle& settle) {
  oracle::ask_and_judge(oracle::portal_view_ask(view, frame, linked), consumers, settle);
}

#define OBLIQUE_CONSUMER_ASKS(T)                                                           \
  template void ask_camera_plane(const Consumers<T>&, const PassPlaneCase<T>&,             \
                                 const oracle::Settle&);                                   \
  template void ask_mirror_view(const Consumers<T>&, const Matrix4<T>&, const Vector4<T>&, \
                                const oracle::Settle&);                                    \
  template void ask_portal_view(const Consumers<T>&, const Matrix4<T>&, const Matrix4<T>&, \
                                const Matrix4<T>&, const oracle::Settle&);
OBLIQUE_CONSUMER_ASKS(float)
OBLIQUE_CONSUMER_ASKS(double)
OBLIQUE_CONSUMER_ASKS(long double)
#undef OBLIQUE_CONSUMER_ASKS

}  // namespace oblique::oracle::consumer_cases

namespace oblique::oracle {

template <class T>
Consumers<T> reference_consumers() {
  Consumers<T> c;
  c.name = "core_references";
  c.view_position = [](const DepthSample<T>& s) {
    return view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
  };
  c.linear_depth = [](const DepthSample<T>& s) {
    return linear_depth(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention,
                        view_axis_sign(s.original, s.convention));
  };
  c.culling_planes = [](const Matrix4<T>& m, Convention k) { return frustum_planes(m, k); };
  c.camera_plane = [](const Matrix4<T>& view, const Vector4<T>& plane) {
    return plane_in_camera(view, plane);
  };
  c.mirror_view = [](const Matrix4<T>& view, const Vector4<T>& plane) {
    return oblique::mirror_view(view, plane);
  };
  c.portal_view = [](const Matrix4<T>& view, const Matrix4<T>& frame, const Matrix4<T>& linked) {
    return oblique::portal_view(view, frame, linked);
  };
  c.corners = [](const Matrix4<T>& m, const Matrix4<T>& original, Convention k) {
    std::vector<Vector3<T>> out;
    for (const auto& v : kept_region_vertices(original, near_plane(m, k), k))
      out.push_back(v.template head<3>());
    return out;
  };
  return c;
}

#define OBLIQUE_CONSUMER_INSTANCES(T)                                                              \
  template std::optional<DepthSample<T>> depth_sample(const Matrix4<T>&, const Matrix4<T>&,        \
                                                      Convention, DepthBuffer, const Vector4<T>&); \
  template ConsumerFinding judge_view_position(const DepthSample<T>&, const Vector3<T>&);          \
  template ConsumerFinding judge_linear_depth(const DepthSample<T>&, T);                           \
  template std::vector<ConsumerFinding> judge_culling_planes(const Matrix4<T>&, const Vector4<T>&, \
                                                             Convention, const Matrix4<T>&,        \
                                                             const FrustumPlanes<T>&);             \
  template std::vector<ConsumerFinding> judge_camera_plane(const Matrix4<T>&, const Vector4<T>&,   \
                                                           const std::vector<Vector4<T>>&,         \
                                                           const Vector4<T>&, const Vector4<T>&);  \
  template ConsumerFinding judge_mirror_view(const Matrix4<T>&, const Vector4<T>&,                 \
                                             const Matrix4<T>&, MirrorDesign);                     \
  template ConsumerFinding judge_portal_view(const Matrix4<T>&, const Matrix4<T>&,                 \
                                             const Matrix4<T>&, const Matrix4<T>&);                \
  template ConsumerFinding judge_corners(const Matrix4<T>&, const Vector4<T>&, Convention,         \
                                         const Matrix4<T>&, const std::vector<Vector3<T>>&,        \
                                         Arithmetic);                                              \
  template Consumers<T> reference_consumers<T>();                                                  \
  template void consumer_round(const Matrix4<T>&, const Vector4<T>&, Convention,                   \
                               const Consumers<T>&, const Pick&, const Settle&);                   \
  template std::vector<ConsumerAsk<T>> consumer_asks(const Matrix4<T>&, const Vector4<T>&,         \
                                                     Convention, const Consumers<T>&, const Pick&, \
                                                     const Settle&);

OBLIQUE_CONSUMER_INSTANCES(float)
OBLIQUE_CONSUMER_INSTANCES(double)
OBLIQUE_CONSUMER_INSTANCES(long double)

}  // namespace oblique::oracle
