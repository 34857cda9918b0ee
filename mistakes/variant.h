// The model of the computation: the modification as one computation whose choices (Knobs) are
// each set to the correct alternative or to one real code takes (a known mistake, mistakes.h);
// all knobs at their defaults is the correct method. A variant first decides (integers only:
// decide()), then computes (evaluate()). Written once for any scalar: computed in float or double
// it is an engine's code (mistaken_implementation(), the numerical routes); in exact rationals it
// is the answer the mistakes give when nothing rounds, against which diagnosis.cpp compares a
// user's answer. Internal to oblique::mistakes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/mistakes/mistakes.h"
#include "oblique/oracle/exact.h"
#include "oblique/plane.h"
#include "oblique/projection.h"
#include "oblique/status.h"

namespace oblique::mistakes::variant {

/// Where the far corner Q comes from the perspective closed form instead of a solve.
enum class ClosedForm { never, perspective_shape, always };
/// Where a corner sign is read: from C' = M^-T C (right), from C (everywhere, or where M has the
/// perspective shape), or fixed at +1.
enum class SignFrom { clip, camera, camera_on_perspective_shape, fixed };
/// What the solves take for a pair of entries of M (M13, M23 or M14, M24): the entries, 0, their
/// magnitudes or their negatives.
enum class Entries { kept, dropped, magnitude, negated };

/// The modification's choices, each set to one of the alternatives real code takes; the default
/// is the correct method. A mistake (mistakes.h) sets the knobs of its choices (choices_changed()).
struct Knobs {
  bool camera_guard = true, corner_guard = true, skips_head_on = false, sign_by_division = false;
  SignFrom x = SignFrom::clip, y = SignFrom::clip;
  bool face_fixed = false, face_opposite = false;
  Entries off_axis = Entries::kept, shift = Entries::kept;
  ClosedForm closed_form = ClosedForm::never;
  bool assumes_m43_minus_one = false, left_handed_qw = false;
  bool zero_one_on_gl = false, gl_on_zero_one = false, note_flip = false;
  /// The factor's numerator or row 3's form of the other convention: a = 1 / (C . Q) on a gl
  /// matrix, a = 2 / (C . Q) on a [0, 1] or reversed-Z one; row 3 = a C on a gl matrix,
  /// a C - M_4 on a [0, 1] one.
  bool zero_one_factor_on_gl = false, gl_factor_on_zero_one = false;
  bool zero_one_form_on_gl = false, gl_form_on_zero_one = false;
  /// Row 3's M_4 taken as the perspective shape's (0, 0, -1, 0), as Listing 5.1 prints it (row 3
  /// = a C + (0, 0, 1, 0) on a gl matrix), whatever M_4 is.
  bool m4_assumed = false;
  /// A route through another convention (route_back()): the matrix taken to `via`'s depth range,
  /// modified there by `via`'s formula (with the other knobs' mistakes) and brought back.
  std::optional<Convention> via;

  bool operator==(const Knobs& o) const;
  bool operator!=(const Knobs& o) const { return !(*this == o); }
};

Knobs knobs_of(Mistake mistake);
/// The knobs of several mistakes made together.
Knobs knobs_of(const std::vector<Mistake>& mistakes);

/// The choices a variant made on one input: two variants whose choices agree give the same
/// answer when nothing rounds.
struct Choices {
  bool refused_camera = false, head_on_skipped = false;
  bool closed_form = false, nan_sign = false, refused_corner = false, unguarded_corner = false;
  bool note_flip = false;
  /// What the solves take for M13, M23, M14, M24: 1 the entry, 0 zero, -1 its negative (an
  /// entry that is 0 is always 1).
  std::array<int, 4> solved{1, 1, 1, 1};
  /// Whether the solves take another matrix than M.
  bool solve_changed() const { return solved != std::array<int, 4>{1, 1, 1, 1}; }
  bool q_z_assumed = false, left_handed_qw = false;  ///< the closed form's Q_z = -1, Q_w
  int sx = 0, sy = 0;                                ///< the corner's x and y signs
  int z_twice = 0;  ///< twice the corner's z (a face or, for a zero sign, the middle)
  Convention formula = Convention::gl;  ///< whose formula: range, a's numerator, row 3's form
  int numerator = 2;                    ///< a = numerator / (C . Q)
  int r3 = 1, t3 = -1;                  ///< row 3 = (r3 a C + t3 M_4) / den
  int den = 1;                          ///< 2 where a route's way back halves the row
  bool m4_assumed = false;              ///< M_4 in row 3 taken as (0, 0, -1, 0)
  bool routed = false;                  ///< the formula ran in another convention (Knobs::via)

  bool operator==(const Choices& o) const {
    return refused_camera == o.refused_camera && head_on_skipped == o.head_on_skipped &&
           closed_form == o.closed_form && nan_sign == o.nan_sign &&
           refused_corner == o.refused_corner && unguarded_corner == o.unguarded_corner &&
           note_flip == o.note_flip && solved == o.solved && q_z_assumed == o.q_z_assumed &&
           left_handed_qw == o.left_handed_qw && sx == o.sx && sy == o.sy && z_twice == o.z_twice &&
           formula == o.formula && numerator == o.numerator && r3 == o.r3 && t3 == o.t3 &&
           den == o.den && m4_assumed == o.m4_assumed && routed == o.routed;
  }
  bool operator!=(const Choices& o) const { return !(*this == o); }
};

template <class S>
using Vec = std::array<S, 4>;
template <class S>
using Mat = std::array<Vec<S>, 4>;

/// A variant's answer: a refusal, M unchanged, a non-finite matrix (a division by zero or a NaN
/// sign), or M with row 3 = r3 (a C) + t3 M_4 and, for note_flip, row 4 = a C + M_4.
template <class S>
struct Evaluation {
  Status status = Status::ok;
  bool unchanged = false, non_finite = false, solve_failed = false;
  bool nan_sign_of_computed = false;       ///< a NaN sign of a component of C' (computed), not of C
  std::array<bool, 3> sign_of_computed{};  ///< the corner's x, y, z signs read from C', not C
  bool perspective_shape = false;          ///< M has the perspective shape
  Choices choices;
  S a{}, d{};
  Vec<S> c{}, c_clip{}, q_clip{}, q{},
      q_magnitude{};   ///< q_magnitude: |Q| as the closed form sums it
  Mat<S> solved{};     ///< the matrix solved with (M with the dropped entries zero)
  int r3 = 1, t3 = 0;  ///< row 3 = (r3 a C + t3 M_4) / den
  int den = 1;
  bool m4_assumed = false;  ///< M_4 in row 3 taken as (0, 0, -1, 0) (row_m4())
  bool routed = false;      ///< Choices::routed
  bool row4_changed = false;
};

/// The M_4 a variant's row 3 takes: M's own, or the perspective shape's (0, 0, -1, 0).
template <class S>
Vec<S> row_m4(const Mat<S>& m, bool assumed) {
  return assumed ? Vec<S>{S(0), S(0), S(-1), S(0)} : m[3];
}

template <class S>
S magnitude(const S& x) {
  return x < 0 ? S(-x) : x;
}

template <class S, class T>
S convert(T x) {
  if constexpr (std::is_same_v<S, oracle::exact::Rational>) {
    return oracle::exact::to_rational(x);
  } else {
    return static_cast<S>(x);
  }
}

/// Solves A x = b (or A^T x = b) by Gaussian elimination with partial pivoting, and in floating
/// point one step of iterative refinement (componentwise backward stable, Skeel 1980); false when
/// a pivot is zero.
template <class S>
bool solve(const Mat<S>& a, bool transpose, const Vec<S>& b, Vec<S>& x) {
  auto eliminate = [&a, transpose](const Vec<S>& rhs, Vec<S>& out) {
    std::array<std::array<S, 5>, 4> m;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) m[i][j] = transpose ? a[j][i] : a[i][j];
      m[i][4] = rhs[i];
    }
    for (int k = 0; k < 4; ++k) {
      int p = k;
      for (int i = k + 1; i < 4; ++i) {
        if (magnitude(m[i][k]) > magnitude(m[p][k])) p = i;
      }
      if (m[p][k] == 0) return false;
      std::swap(m[k], m[p]);
      for (int i = k + 1; i < 4; ++i) {
        const S f = m[i][k] / m[k][k];
        for (int j = k; j < 5; ++j) m[i][j] -= f * m[k][j];
      }
    }
    for (int i = 3; i >= 0; --i) {
      S s = m[i][4];
      for (int j = i + 1; j < 4; ++j) s -= m[i][j] * out[j];
      out[i] = s / m[i][i];
    }
    return true;
  };
  if (!eliminate(b, x)) return false;
  if constexpr (std::is_floating_point_v<S>) {
    Vec<S> r, dx;
    for (int i = 0; i < 4; ++i) {
      S ax = 0;
      for (int j = 0; j < 4; ++j) ax += (transpose ? a[j][i] : a[i][j]) * x[j];
      r[i] = b[i] - ax;
    }
    if (!eliminate(r, dx)) return false;
    for (int i = 0; i < 4; ++i) x[i] += dx[i];
  }
  return true;
}

/// x / y; false (in exact arithmetic) where y = 0: the answer is then not finite.
template <class S>
bool divide(const S& x, const S& y, S& out) {
  if constexpr (std::is_floating_point_v<S>) {
    out = x / y;
    return true;
  } else {
    if (y == 0) return false;
    out = x / y;
    return true;
  }
}

/// Each convention's row 3 is alpha times [0, 1]'s plus beta times M_4 (z_gl = 2 z - w, z_rev =
/// w - z): the way back from a route through `via` to `own` multiplies via's row 3 less its
/// beta_via M_4 by alpha_own / alpha_via = num / den and adds beta_own M_4.
struct RouteBack {
  int num = 1, den = 1, beta_via = 0, beta_own = 0;
};
constexpr RouteBack route_back(Convention via, Convention own) {
  auto alpha = [](Convention c) {
    return c == Convention::gl ? 2 : c == Convention::zero_one ? 1 : -1;
  };
  auto beta = [](Convention c) {
    return c == Convention::gl ? -1 : c == Convention::zero_one ? 0 : 1;
  };
  RouteBack b;
  b.beta_via = beta(via);
  b.beta_own = beta(own);
  const int a_own = alpha(own), a_via = alpha(via);
  // num / den = a_own / a_via, den positive and 1 or 2
  if (a_own % a_via == 0) {
    b.num = a_own / a_via;
    b.den = 1;
  } else {
    b.num = a_own * (a_via < 0 ? -1 : 1);
    b.den = a_via < 0 ? -a_via : a_via;
  }
  return b;
}

/// What a variant decides on one input before it computes anything but C's clip-space signs:
/// its choices (but the corner guard's outcome, which needs C . Q) and what follows from them.
/// Two variants whose decisions are equal give the same answer when nothing rounds.
struct Decision {
  Choices choices;             ///< refused_corner and unguarded_corner are left false
  bool corner_guard = true;    ///< whether C . Q <= 0 is refused
  Status status = Status::ok;  ///< camera_not_behind_plane or singular_projection: no answer
  bool unchanged = false, solve_failed = false, perspective_shape = false;
  bool nan_sign_of_computed = false;       ///< Evaluation::nan_sign_of_computed
  std::array<bool, 3> sign_of_computed{};  ///< Evaluation::sign_of_computed

  bool operator==(const Decision& o) const {
    return choices == o.choices && corner_guard == o.corner_guard;
  }
};

/// The decision of the variant with `knobs` on an input in `convention`, from the signs of C,
/// of M13, M23, M14, M24, and `clip_signs(solved)`: the signs of C' = S^-T C for the matrix S
/// the solves take (Choices::solved), or none where S is singular.
template <class ClipSigns>
Decision decide(const Knobs& knobs, Convention convention, bool perspective,
                const std::array<int, 4>& c_sign, const std::array<int, 4>& entry_sign,
                ClipSigns&& clip_signs) {
  Decision d;
  d.corner_guard = knobs.corner_guard;
  d.perspective_shape = perspective;
  Choices& ch = d.choices;
  // The convention the formula runs in: the matrix's own, or a route's (Knobs::via).
  const Convention own = knobs.via.value_or(convention);
  ch.routed = own != convention;
  ch.formula = own;
  if (knobs.zero_one_on_gl && own == Convention::gl) ch.formula = Convention::zero_one;
  if (knobs.gl_on_zero_one && own == Convention::zero_one) ch.formula = Convention::gl;
  ch.note_flip = knobs.note_flip && own == Convention::reversed_z && !ch.routed;
  const DepthRange range = clip_depth_range(ch.formula);
  ch.numerator = range.z_high - range.z_low;
  if (knobs.zero_one_factor_on_gl && own == Convention::gl) ch.numerator = 1;
  if (knobs.gl_factor_on_zero_one && own != Convention::gl) ch.numerator = 2;
  const RowCombination near = near_rows(ch.formula);
  ch.r3 = near.m3;
  ch.t3 = -near.m3 * near.m4;
  if (knobs.zero_one_form_on_gl && own == Convention::gl) ch.t3 = 0;
  if (knobs.gl_form_on_zero_one && own == Convention::zero_one) ch.t3 = -1;
  ch.m4_assumed = knobs.m4_assumed && ch.t3 != 0;
  // The way back (route_back()): row 3 in the matrix's own convention, exactly.
  const RouteBack back = route_back(own, convention);
  if (ch.routed) {
    ch.r3 *= back.num;
    ch.t3 = back.num * (ch.t3 - back.beta_via) + back.beta_own * back.den;
    ch.den = back.den;
  }
  if (!(c_sign[3] < 0) && knobs.camera_guard) {
    ch.refused_camera = true;
    d.status = Status::camera_not_behind_plane;
    return d;
  }
  if (knobs.skips_head_on && c_sign[0] == 0 && c_sign[1] == 0 && c_sign[2] < 0) {
    ch.head_on_skipped = true;
    d.unchanged = true;
    return d;
  }
  auto take = [](Entries how, int sign) {
    if (sign == 0) return 1;
    return how == Entries::dropped     ? 0
           : how == Entries::negated   ? -1
           : how == Entries::magnitude ? sign
                                       : 1;
  };
  for (int i = 0; i < 4; ++i)
    ch.solved[i] = take(i < 2 ? knobs.off_axis : knobs.shift, entry_sign[i]);
  const std::optional<std::array<int, 3>> clip = clip_signs(ch.solved);
  if (!clip) {
    d.solve_failed = true;
    d.status = Status::singular_projection;
    return d;
  }
  auto sign = [&](int v, bool computed) {
    if (knobs.sign_by_division && v == 0) {
      ch.nan_sign = true;
      d.nan_sign_of_computed = d.nan_sign_of_computed || computed;
    }
    return v;
  };
  auto read = [&](SignFrom from, int i) {
    const bool camera =
        from == SignFrom::camera || (from == SignFrom::camera_on_perspective_shape && perspective);
    d.sign_of_computed[i] = !camera && from != SignFrom::fixed;
    if (from == SignFrom::fixed) return 1;
    return camera ? sign(c_sign[i], false) : sign((*clip)[i], true);
  };
  d.sign_of_computed[2] = true;
  ch.sx = read(knobs.x, 0);
  ch.sy = read(knobs.y, 1);
  // On a route, C'_z in the route's convention: its sign flips where the depth runs the other way.
  const int sz = sign((*clip)[2], true) * (back.num < 0 ? -1 : 1);
  const int face = knobs.face_opposite ? -sz : sz;
  ch.z_twice = knobs.face_fixed ? 2
               : face > 0       ? 2 * range.z_high
               : face < 0       ? 2 * range.z_low
                                : range.z_low + range.z_high;
  // The route's corner in the matrix's own clip space: z_own = (z_via - beta_via) num / den +
  // beta_own (every route's corner lands on a quarter-integer: twice it is an integer).
  if (ch.routed)
    ch.z_twice = back.num * (ch.z_twice - 2 * back.beta_via) / back.den + 2 * back.beta_own;
  if (ch.nan_sign) return d;
  ch.closed_form = knobs.closed_form == ClosedForm::always ||
                   (knobs.closed_form == ClosedForm::perspective_shape && perspective);
  if (ch.closed_form) {
    ch.q_z_assumed = knobs.assumes_m43_minus_one;
    ch.left_handed_qw = knobs.left_handed_qw;
  }
  return d;
}

/// The solves one case needs, kept across the variants evaluated on it (diagnosis tries thousands
/// of knob settings on one case, and they solve with few matrices and corners): M and C in S, and
/// each solve by the entries it changed and its right side.
template <class S>
struct SolveMemo {
  struct Solved {
    std::array<int, 4> entries;  ///< Choices::solved
    bool transpose;
    std::array<int, 3> corner;  ///< the corner's sx, sy, z_twice (0 for the transposed solve)
    bool ok;
    Vec<S> x;
  };
  bool filled = false;
  Mat<S> m;
  Vec<S> c;
  /// What decide() reads of the case: the signs of C and of M13, M23, M14, M24, the shape.
  std::array<int, 4> c_sign{}, entry_sign{};
  bool perspective = false;
  std::vector<Solved> solves;
  /// The signs of C' for each matrix the solves take (Choices::solved), none where singular.
  std::vector<std::pair<std::array<int, 4>, std::optional<std::array<int, 3>>>> clip_signs;
};

/// -1, 0 or 1.
template <class S>
int sign_of(const S& v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

/// The matrix the solves take: M with M13, M23, M14, M24 as `solved` (Choices::solved) says.
template <class S>
Mat<S> solved_matrix(const Mat<S>& m, const std::array<int, 4>& solved) {
  Mat<S> out = m;
  for (int i = 0; i < 4; ++i) {
    S& v = out[i % 2][2 + i / 2];
    if (solved[i] == 0) v = 0;
    if (solved[i] == -1) v = -v;
  }
  return out;
}

/// S x = rhs (or S^T x = rhs) for S = solved_matrix(memo.m, solved), solved once per memo: the
/// corner (sx, sy, z_twice) names rhs = Q' (0, 0, 0 for the transposed solve, whose rhs is C).
template <class S>
bool memo_solve(SolveMemo<S>& memo, const std::array<int, 4>& solved, bool transpose,
                const std::array<int, 3>& corner, const Vec<S>& rhs, Vec<S>& x) {
  for (const auto& s : memo.solves) {
    if (s.entries == solved && s.transpose == transpose && s.corner == corner) {
      x = s.x;
      return s.ok;
    }
  }
  const bool ok = solve(solved_matrix(memo.m, solved), transpose, rhs, x);
  memo.solves.push_back({solved, transpose, corner, ok, x});
  return ok;
}

/// The signs of C' = S^-T C for the matrix S the solves take (`solved`), solved once per memo;
/// none where S is singular. (clip_signs() needs a filled memo: evaluate() fills it.)
template <class S>
std::optional<std::array<int, 3>> clip_signs(SolveMemo<S>& memo, const std::array<int, 4>& solved) {
  for (const auto& [entries, signs] : memo.clip_signs) {
    if (entries == solved) return signs;
  }
  std::optional<std::array<int, 3>> out;
  Vec<S> c_clip;
  if (memo_solve(memo, solved, true, {0, 0, 0}, memo.c, c_clip))
    out = {sign_of(c_clip[0]), sign_of(c_clip[1]), sign_of(c_clip[2])};
  memo.clip_signs.emplace_back(solved, out);
  return out;
}

/// The modification of (M, C) in `convention` with `knobs`, in S. Precondition: M and C finite.
/// `memo`: one case's solves, kept for the next call on the same case (exact arithmetic).
template <class S, class T>
Evaluation<S> evaluate(const Matrix4<T>& matrix, const Vector4<T>& plane, Convention convention,
                       const Knobs& knobs, SolveMemo<S>* memo = nullptr) {
  Evaluation<S> e;
  Mat<S> m;
  if (memo && memo->filled) {
    m = memo->m;
    e.c = memo->c;
  } else {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) m[i][j] = convert<S>(matrix(i, j));
      e.c[i] = convert<S>(plane(i));
    }
    if constexpr (std::is_floating_point_v<S>) {
      // a C does not change when C is scaled: a very tiny or huge C is brought near magnitude 1
      // by a power of two (exact) first, as careful code does, so that C . Q neither under- nor
      // overflows (an ordinary C is left alone: scaling it down would lose a subnormal's bits).
      S largest = 0;
      for (const S& v : e.c) largest = std::max(largest, std::abs(v));
      const int exponent = largest > 0 && std::isfinite(largest) ? std::ilogb(largest) : 0;
      if (std::abs(exponent) > std::numeric_limits<S>::max_exponent / 4) {
        for (S& v : e.c) v = std::ldexp(v, -exponent);
      }
    }
    if (memo) {
      memo->m = m;
      memo->c = e.c;
      memo->filled = true;
    }
  }
  const Vec<S>& c = e.c;
  std::array<int, 4> c_sign, entry_sign;
  for (int i = 0; i < 4; ++i) {
    c_sign[i] = sign_of(c[i]);
    entry_sign[i] = sign_of(m[i % 2][2 + i / 2]);  // M13, M23, M14, M24
  }
  const bool perspective = has_perspective_shape(matrix);
  if (memo) {
    memo->c_sign = c_sign;
    memo->entry_sign = entry_sign;
    memo->perspective = perspective;
  }
  auto solve_memo = [&](const std::array<int, 4>& solved, bool transpose,
                        const std::array<int, 3>& corner, const Vec<S>& rhs, Vec<S>& x) {
    if (memo) return memo_solve(*memo, solved, transpose, corner, rhs, x);
    return solve(solved_matrix(m, solved), transpose, rhs, x);
  };
  const Decision d = decide(
      knobs, convention, perspective, c_sign, entry_sign, [&](const std::array<int, 4>& solved) {
        std::optional<std::array<int, 3>> out;
        if (!solve_memo(solved, true, {0, 0, 0}, c, e.c_clip)) return out;
        out = {sign_of(e.c_clip[0]), sign_of(e.c_clip[1]), sign_of(e.c_clip[2])};
        return out;
      });
  Choices& ch = e.choices;
  ch = d.choices;
  e.status = d.status;
  e.unchanged = d.unchanged;
  e.solve_failed = d.solve_failed;
  e.nan_sign_of_computed = d.nan_sign_of_computed;
  e.sign_of_computed = d.sign_of_computed;
  e.perspective_shape = d.perspective_shape;
  e.r3 = ch.r3;
  e.t3 = ch.t3;
  e.den = ch.den;
  e.routed = ch.routed;
  e.m4_assumed = ch.m4_assumed;
  e.row4_changed = ch.note_flip;
  if (d.status != Status::ok || d.unchanged) return e;
  e.solved = solved_matrix(m, ch.solved);
  if (ch.nan_sign) {  // x / |x| at 0: a NaN in Q, C . Q and every entry of row 3
    e.non_finite = true;
    return e;
  }
  e.q_clip = {S(ch.sx), S(ch.sy), S(ch.z_twice) / S(2), S(1)};
  const Mat<S>& s = e.solved;
  if (ch.closed_form) {
    // Q = M^-1 Q' for the perspective shape: Q_z = 1 / M43, Q_w = (z - M33 Q_z) / M34,
    // Q_x = (s_x - M13 Q_z) / M11, Q_y = (s_y - M23 Q_z) / M22.
    S qz = S(-1);
    if (!ch.q_z_assumed && !divide(S(1), s[3][2], qz)) {
      e.non_finite = true;
      return e;
    }
    const S qz_in_w = ch.left_handed_qw ? S(1) : qz;
    // Q_k = (Q'_j - M_j3 z) / M_jl for (k, j, z, l) = (x, 1, Q_z, 1), (y, 2, Q_z, 2), (w, 3, Q_z
    // or, left-handed, 1, 4); q_magnitude sums the same terms' magnitudes.
    const struct {
      int k, j, l;
      const S& z;
    } parts[3] = {{0, 0, 0, qz}, {1, 1, 1, qz}, {3, 2, 3, qz_in_w}};
    for (const auto& p : parts) {
      if (!divide(S(e.q_clip[p.j] - s[p.j][2] * p.z), s[p.j][p.l], e.q[p.k])) {
        e.non_finite = true;
        return e;
      }
      e.q_magnitude[p.k] = (magnitude(e.q_clip[p.j]) + magnitude(s[p.j][2]) * magnitude(p.z)) /
                           magnitude(s[p.j][p.l]);
    }
    e.q[2] = qz;
    e.q_magnitude[2] = magnitude(qz);
  } else if (!solve_memo(ch.solved, false, {ch.sx, ch.sy, ch.z_twice}, e.q_clip, e.q)) {
    e.solve_failed = true;
    e.status = Status::singular_projection;
    return e;
  }
  e.d = c[0] * e.q[0] + c[1] * e.q[1] + c[2] * e.q[2] + c[3] * e.q[3];
  if constexpr (std::is_floating_point_v<S>) {
    if (!std::isfinite(e.d)) {  // where exact arithmetic divides by zero: the answer is NaN
      e.non_finite = true;
      return e;
    }
  }
  if (!(e.d > 0)) {
    if (knobs.corner_guard) {
      ch.refused_corner = true;
      e.status = Status::plane_misses_view_volume;
      return e;
    }
    ch.unguarded_corner = true;
  }
  if (!divide(S(ch.numerator), e.d, e.a)) {
    e.non_finite = true;
    return e;
  }
  return e;
}

/// The answer of an evaluation in T (as an engine writes it): row 3 = s (a C - t M_4).
template <class T>
Matrix4<T> answer_matrix(const Matrix4<T>& m, const Evaluation<T>& e) {
  Matrix4<T> out = m;
  if (e.unchanged) return out;
  if (e.non_finite) {
    out.row(2).setConstant(std::numeric_limits<T>::quiet_NaN());
    return out;
  }
  for (int i = 0; i < 4; ++i) {
    const T m4 = e.m4_assumed ? (i == 2 ? T(-1) : T(0)) : m(3, i);
    out(2, i) = (T(e.r3) * (e.a * e.c[i]) + T(e.t3) * m4) / T(e.den);
    if (e.row4_changed) out(3, i) = e.a * e.c[i] + m(3, i);
  }
  return out;
}

}  // namespace oblique::mistakes::variant
