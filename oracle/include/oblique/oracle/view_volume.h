// What the checker knows of one input (M, C, convention) before it sees an answer, written once
// over its arithmetic: the inverse, the clip-space plane C' = M^-T C, the eight corners of the view
// volume and C's value at each, the far corner Q by the sign rule, C . Q and its condition, the
// exact row 3, the status an exact implementation gives and the statuses a careful one in T may
// give.
//
// The arithmetic A is the exact oracle's (ExactArithmetic, exact_arithmetic.h: rationals, every
// predicate decided) or the filter's (CertifiedArithmetic, certified_arithmetic.h: certified
// intervals on M and C scaled by powers of two, exact signs from integer determinants), whose
// predicates throw certified::Undecided where the intervals cannot decide. Problem (problem.h)
// and FilteredProblem (filtered.h) each hold one and judge answers against it.
//
// A provides: Num and Magnitude (a nonnegative quantity: the same rational, or a certified
// range); matrix_entry(), plane_entry() and the scales they apply (row_scale(), plane_scale());
// the underflow unit in the units of a row entry and of C . Q; constant(), gamma(), abs(),
// less_equal(), less(); magnitude(), as_num(), some_at_least(); at_least_largest(x, threshold, k)
// (x 2^k against the largest finite T); inverse(); the signs of C'_k, of C' . p' and of
// (M^-1 p')_w; and refine_corner_dot().
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/oracle/algebra.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique::oracle {

template <class T, class A>
class ViewVolume {
 public:
  using Num = typename A::Num;
  using Magnitude = typename A::Magnitude;
  using Vec = algebra::Vec<Num>;
  using Mat = algebra::Mat<Num>;

  /// Builds everything about (M, C) in `convention`; with the filter's arithmetic it throws
  /// certified::Undecided where the intervals do not decide.
  ViewVolume(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);

  A arithmetic;
  Convention convention;
  bool finite = false, too_spread = false, invertible = false, infinite = false;
  /// The far face is at infinity and Q lies on it (C leans toward the far face).
  bool far_at_infinity = false;
  bool camera_behind = false, d_positive = false, d_unresolved = false;
  Mat mx{}, inverse{};
  /// C, C' = M^-T C, the far corner Q (normalised so that M_4 . Q = 1) and the exact row 3 (where
  /// C . Q > 0).
  Vec cx{}, c_clip{}, q{}, row3{};
  std::array<int, 3> c_clip_sign{};
  /// Q' in clip space, twice (integers: the middle of the depth range may be a half).
  std::array<int, 4> q_clip2{};
  std::array<std::array<int, 4>, 8> clip_corners{};
  std::array<Vec, 8> corners{};
  /// C . p at each corner p, and its sign.
  std::array<Num, 8> corner_dots{};
  std::array<int, 8> corner_sign{};
  /// C . Q and kappa's numerator (tolerance.h).
  Num d{}, kappa_numerator{};
  /// The row sums of |M^-1| |M|: Skeel's condition number is the largest.
  algebra::Vec<Magnitude> skeel_row_sums{};
  /// The status an exact implementation returns, and those a careful one in T may.
  Status status = Status::invalid_input;
  std::vector<Status> acceptable;

  /// The far face's depth in clip space (z_high, or z_low for reversed Z).
  static int far_z(Convention convention) {
    const DepthRange range = clip_depth_range(convention);
    return convention == Convention::reversed_z ? range.z_low : range.z_high;
  }

  /// Whether corner i is a far corner: it agrees with Q' wherever C' has a nonzero component.
  /// (Where a component of C' is exactly zero the far corner is not unique: every point of that
  /// edge or face is equally far.)
  bool is_far_corner_candidate(int i) const {
    for (int k = 0; k < 3; ++k) {
      if (c_clip_sign[k] != 0 && 2 * clip_corners[i][k] != q_clip2[k]) return false;
    }
    return true;
  }

  /// a = (z_high - z_low) / (C . Q). Precondition: d_positive.
  Num scale() const {
    const DepthRange range = clip_depth_range(convention);
    return A::constant(range.z_high - range.z_low) / d;
  }

  /// The bound on the error of C . Q computed in T (tolerance.h).
  Num corner_dot_error() const {
    return tolerance::corner_dot_error<A>(kappa_numerator, arithmetic.underflow_dot());
  }

  /// The bound on the relative error of a; empty where C . Q is not above its error bound's
  /// reach (eps >= 1) or not positive.
  std::optional<Num> scale_error() const {
    if (!d_positive) return std::nullopt;
    return tolerance::scale_error<A>(corner_dot_error(), d);
  }

  /// The bound on |M'_3i - row3_i| given a's relative error `scale` (tolerance.h).
  Num row3_bound(int i, const Num& scale_error) const {
    const Num ac = A::abs(this->scale() * cx[i]);
    return tolerance::row3_entry_bound<A>(ac, A::abs(mx[3][i]), scale_error,
                                          arithmetic.underflow_row());
  }

  /// What rounding may move entry i of an answer's row 3 (and so of near' and far'), lambda C_i
  /// given: gamma(kEntryRoundings) (|lambda C_i| + |M4_i|) plus the underflow unit's share, and
  /// `allowance` (property 1's for what no rasterizer sees, tolerance.h; zero for none).
  Num entry_bound(int i, const Num& lambda_c, const Num& allowance) const {
    const Num b = A::gamma(tolerance::kEntryRoundings) * (A::abs(lambda_c) + A::abs(mx[3][i])) +
                  A::constant(tolerance::kEntryRoundings) * arithmetic.underflow_row();
    return algebra::is_zero(allowance) ? b : Num(b + allowance);
  }

  /// What rounding may do to far' . p at a point p with M_4 . p = 1: the entries' bounds (twice:
  /// far' is row 3 combined with row 4, and row 3 carries them), weighted by |p|, and at a corner
  /// the error of a, (z_high - z_low) scale_error() (it reaches far' . p through a C . p <=
  /// a C . Q = z_high - z_low).
  Num point_bound(const algebra::Vec<Magnitude>& twice_entry_bound, const Magnitude& scale_term,
                  const Vec& p, bool at_corner) const {
    const algebra::Vec<Magnitude> abs_p{A::magnitude(p[0]), A::magnitude(p[1]), A::magnitude(p[2]),
                                        A::magnitude(p[3])};
    const Magnitude b = algebra::dot(twice_entry_bound, abs_p);
    return A::as_num(at_corner ? Magnitude(scale_term + b) : b);
  }
  /// twice_entry_bound and scale_term for point_bound().
  algebra::Vec<Magnitude> twice(const Vec& entry_bounds) const {
    algebra::Vec<Magnitude> out;
    for (int i = 0; i < 4; ++i) out[i] = A::magnitude(entry_bounds[i]) * A::magnitude_constant(2);
    return out;
  }
  Magnitude scale_term(const std::optional<Num>& scale_error) const {
    if (!scale_error) return Magnitude{};
    const DepthRange range = clip_depth_range(convention);
    return A::magnitude(A::constant(range.z_high - range.z_low) * *scale_error);
  }

  /// Calls visit(p, at_corner) for every vertex p of the view volume on C's positive side (no
  /// part of the original volume there may be clipped): the corners with C . p >= 0 (where
  /// `corners_judged`) and the points where C crosses an edge of the volume, normalised so that
  /// M_4 . p = 1.
  template <class Visit>
  void for_each_kept_vertex(bool corners_judged, Visit&& visit) const {
    for (int i = 0; i < 8; ++i) {
      if (corners_judged && corner_sign[i] >= 0) visit(corners[i], true);
      for (int j = i + 1; j < 8; ++j) {
        int differing = 0;
        for (int axis = 0; axis < 3; ++axis)
          differing += clip_corners[i][axis] != clip_corners[j][axis];
        if (differing != 1 || corner_sign[i] * corner_sign[j] >= 0) continue;
        const Num alpha = corner_dots[j] / (corner_dots[j] - corner_dots[i]);
        visit(algebra::combine<Num>(alpha, corners[i], A::constant(1) - alpha, corners[j]), false);
      }
    }
  }

 private:
  void build(const Matrix4<T>& m, const Vector4<T>& c);
  void decide_statuses();
};

template <class T, class A>
ViewVolume<T, A>::ViewVolume(const Matrix4<T>& m, const Vector4<T>& c, Convention convention)
    : arithmetic(m, c), convention(convention) {
  build(m, c);
}

template <class T, class A>
void ViewVolume<T, A>::build(const Matrix4<T>& m, const Vector4<T>& c) {
  finite = all_finite(m) && all_finite(c);
  if (!finite) {
    status = Status::invalid_input;
    acceptable = {status};
    return;
  }
  too_spread = magnitude_spread(m) > max_magnitude_spread<T>();
  for (int i = 0; i < 4; ++i) {
    cx[i] = arithmetic.plane_entry(c(i));
    for (int j = 0; j < 4; ++j) mx[i][j] = arithmetic.matrix_entry(m(i, j));
  }
  std::optional<Mat> inv = arithmetic.inverse(mx);
  invertible = inv.has_value();
  if (!invertible) {
    status = Status::singular_projection;
    acceptable = {status};
    if (too_spread) acceptable.push_back(Status::out_of_range);
    return;
  }
  inverse = *inv;
  // C' = M^-T C, its signs exact.
  for (int k = 0; k < 4; ++k) {
    c_clip[k] = algebra::dot(Vec{inverse[0][k], inverse[1][k], inverse[2][k], inverse[3][k]}, cx);
  }
  for (int k = 0; k < 3; ++k) {
    c_clip_sign[k] = arithmetic.plane_sign(c_clip[k], k);
    if (c_clip_sign[k] == 0) c_clip[k] = Num{};
  }
  const DepthRange range = clip_depth_range(convention);
  int index = 0;
  for (int x : {-1, 1}) {
    for (int y : {-1, 1}) {
      for (int z : {range.z_low, range.z_high}) {
        const std::array<int, 4> p{x, y, z, 1};
        clip_corners[index] = p;
        corners[index] = algebra::signed_column_sum(inverse, p);
        corner_dots[index] = algebra::signed_sum(c_clip, p);  // C . M^-1 p' = C' . p'
        corner_sign[index] = arithmetic.clip_dot_sign(corner_dots[index], p);
        if (corner_sign[index] == 0) corner_dots[index] = Num{};
        ++index;
      }
    }
  }
  // The far corner by the sign rule (a zero sign gives the middle of the edge: equally far).
  const int sz = c_clip_sign[2];
  q_clip2 = {2 * c_clip_sign[0], 2 * c_clip_sign[1],
             sz > 0 ? 2 * range.z_high : (sz < 0 ? 2 * range.z_low : range.z_low + range.z_high),
             2};
  Vec q_clip;
  for (int i = 0; i < 4; ++i) q_clip[i] = A::constant(q_clip2[i] * 0.5);
  q = algebra::mul(inverse, q_clip);
  d = algebra::dot(cx, q);
  // Infinite: the far face maps to the plane at infinity (every far corner has w = 0).
  infinite = true;
  for (int i = 0; i < 8 && infinite; ++i) {
    if (clip_corners[i][2] != far_z(convention)) continue;
    if (arithmetic.w_sign(corners[i][3], clip_corners[i]) != 0)
      infinite = false;
    else
      corners[i][3] = Num{};
  }
  far_at_infinity = infinite && q_clip2[2] == 2 * far_z(convention);
  // Q on the far face at infinity is an affine combination of corners with w = 0.
  if (far_at_infinity) q[3] = Num{};
  // kappa's numerator and Skeel's row sums: sums of products of magnitudes.
  algebra::Mat<Magnitude> abs_m, abs_inv;
  auto magnitudes = [](const Vec& v) {
    return algebra::Vec<Magnitude>{A::magnitude(v[0]), A::magnitude(v[1]), A::magnitude(v[2]),
                                   A::magnitude(v[3])};
  };
  for (int i = 0; i < 4; ++i) {
    abs_m[i] = magnitudes(mx[i]);
    abs_inv[i] = magnitudes(inverse[i]);
  }
  algebra::Vec<Magnitude> abs_q_clip;
  for (int i = 0; i < 4; ++i) abs_q_clip[i] = A::magnitude_constant(std::abs(q_clip2[i]) * 0.5);
  kappa_numerator = A::as_num(tolerance::corner_dot_numerator(
      magnitudes(cx), magnitudes(q), magnitudes(c_clip), abs_q_clip, abs_m, abs_inv));
  const Magnitude one = A::magnitude_constant(1);
  skeel_row_sums =
      algebra::mul(abs_inv, algebra::mul(abs_m, algebra::Vec<Magnitude>{one, one, one, one}));
  camera_behind = c(3) < T(0);
  // The sign of C . Q = C' . Q'.
  const int d_sign = arithmetic.clip_dot_sign(d, q_clip2);
  if (d_sign == 0) d = Num{};
  d_positive = d_sign > 0;
  if (camera_behind && d_positive) arithmetic.refine_corner_dot(d, q_clip2);
  status = !camera_behind ? Status::camera_not_behind_plane
           : !d_positive  ? Status::plane_misses_view_volume
                          : Status::ok;
  decide_statuses();
}

// The statuses a careful implementation computing in T may give: the exact one, and its
// neighbours where the input lies within rounding of a boundary:
//  - C . Q within its error bound gamma(16) kappa C . Q of zero: ok, plane_misses_view_volume or
//    out_of_range;
//  - a matrix with Skeel condition number at least 1 / (256 eps): singular_projection too;
//  - an exact answer (or Q, or an equally far corner where C' has a zero component) within 2^8
//    of the largest finite T: out_of_range too, and at or above the overflow threshold (answer
//    or Q), not ok;
//  - a C within a few roundings of M_4 (the extracted near plane a C - M_4 + M_4 may vanish):
//    out_of_range too;
//  - M spanning more than max_magnitude_spread<T>() binades: out_of_range too.
template <class T, class A>
void ViewVolume<T, A>::decide_statuses() {
  acceptable = {status};
  auto add = [this](Status s) {
    if (std::find(acceptable.begin(), acceptable.end(), s) == acceptable.end())
      acceptable.push_back(s);
  };
  if (too_spread) add(Status::out_of_range);  // the core's documented domain
  // Skeel's condition number times 256 eps >= 1: some row sum at least 2^(p - 9).
  const int p = tolerance::precision_bits<T>();
  if (A::some_at_least(skeel_row_sums, std::ldexp(1.0, p - 9))) add(Status::singular_projection);
  if (!camera_behind) return;
  d_unresolved = A::less_equal(A::abs(d), corner_dot_error());
  if (d_unresolved) {
    add(Status::plane_misses_view_volume);
    add(Status::ok);
    add(Status::out_of_range);
  }
  if (d_positive) {
    const RowCombination nr = near_rows(convention);
    row3 =
        algebra::combine<Num>(A::constant(nr.m3) * scale(), cx, A::constant(-nr.m3 * nr.m4), mx[3]);
  }
  // Some |entry| of Q, of the exact row 3 or of a far-corner candidate times 2^8 at least the
  // largest finite T (the corners and Q are held times 2^row_scale(), row 3 times its inverse).
  const int sm = arithmetic.row_scale();
  const Num f256 = A::constant(256);
  bool near_overflow = false;
  auto big = [&](const Num& v, int k) {
    if (!near_overflow && A::at_least_largest(A::abs(v) * f256, false, k)) near_overflow = true;
  };
  for (const Num& v : q) big(v, -sm);
  if (d_positive) {
    for (const Num& v : row3) big(v, sm);
  }
  for (int i = 0; i < 8; ++i) {
    if (!is_far_corner_candidate(i)) continue;
    for (const Num& v : corners[i]) big(v, -sm);
  }
  if (near_overflow) add(Status::out_of_range);
  if (d_positive) {
    const RowCombination nr = near_rows(convention);
    Num noise{};
    for (int i = 0; i < 4; ++i) {
      noise = noise + (A::constant(4) * A::unit_roundoff() * A::abs(A::constant(nr.m4) * mx[3][i]) +
                       A::constant(4) * arithmetic.underflow_row()) *
                          A::abs(cx[i]);
    }
    if (A::less_equal(scale() * algebra::dot(cx, cx), noise)) add(Status::out_of_range);
  }
  // Values from the largest finite T up to half an ulp beyond it still round to it. (Unless C . Q
  // is within its rounding error of zero: then a computed C . Q, and the answer, may be any size.)
  if (d_positive && !d_unresolved) {
    bool overflows = false;
    for (const Num& v : q) overflows = overflows || A::at_least_largest(A::abs(v), true, -sm);
    for (const Num& v : row3) overflows = overflows || A::at_least_largest(A::abs(v), true, sm);
    if (overflows)
      acceptable.erase(std::remove(acceptable.begin(), acceptable.end(), Status::ok),
                       acceptable.end());
  }
}

}  // namespace oblique::oracle
