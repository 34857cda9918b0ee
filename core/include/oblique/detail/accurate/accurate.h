// The accurate method: the same answer as closed_form / general, with every entry of M'_3 close
// to the exactly rounded value of the exact answer (aim: correct rounding; measured by
// `oblique report accuracy` against the GMP oracle, checked by the property suite at 2 ulp).
//
// Where the plain methods lose accuracy, and what this one does instead:
//  - Q = M^-1 Q' rounds in every component: here Q is refined to two words (one for float's
//    closed form, up to five where needed), each correction solved from a residual
//    Q' - M (q_0 + ...) summed as in K-fold precision;
//  - C . Q cancels when C passes close to the far corner: distilled to its exact value from
//    exact products;
//  - a = range / (C . Q) rounds: kept as a double-word quotient;
//  - a C_i - t M4_i cancels when C is close to the standard near plane (the a C_z + 1 of the
//    paper's GL formula): formed as (k C_i - t M4_i (C . Q)) / (C . Q) from exact products,
//    rounded once;
//  - stiff planes (components spanning more binades than the type holds, or pushed below the
//    range by the power-of-two scaling), signs of C' within their error bound of zero, and what
//    five words of Q do not resolve: the exact answer (exact_cramer.h).
// float runs in double (float products are exact there and nothing under- or overflows); double
// and long double run in their own type with double-word arithmetic.
#pragma once
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "oblique/depth_convention.h"
#include "oblique/detail/accurate/exact_cramer.h"
#include "oblique/detail/accurate/perspective_fast_path.h"
#include "oblique/detail/accurate/refined_corner.h"
#include "oblique/detail/closed_form_steps.h"
#include "oblique/detail/config.h"
#include "oblique/detail/equilibrated_solver.h"
#include "oblique/detail/general_method.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/error_free.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/projection.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique::detail {

/// The type the accurate method computes in for a given scalar type.
template <class T>
struct AccurateWorkingType {
  using type = T;
};
template <>
struct AccurateWorkingType<float> {
  using type = double;
};

/// The accurate method's answer in exact integer arithmetic (exact_cramer.h), for stiff planes,
/// signs of C' that floating point cannot settle, and C . Q or row-3 entries the refined far
/// corner does not resolve. Out of line: it is rarely taken, and costs microseconds.
/// `plane` is C in W (any power-of-two multiple of it gives the same answer); `c_hat` is C
/// scaled by 2^plane_scale_shift(C) in T, for accept_row3.
template <class T, class W>
OBLIQUE_NOINLINE ObliqueResult<T> accurate_exact(const Matrix4<T>& m, const Matrix4<W>& mw,
                                                 const Vector4<W>& plane, const Vector4<T>& c_hat,
                                                 Convention convention) {
  using Outcome = typename ExactOblique<T, W>::Outcome;
  const ExactOblique<T, W> exact = exact_oblique<T, W>(mw, plane, convention);
  if (exact.outcome == Outcome::singular) {
    return refuse(m, Method::accurate, Status::singular_projection,
                  "the projection is singular: its determinant, computed exactly, is zero");
  }
  ObliqueResult<T> r = refuse(m, Method::accurate, Status::ok);
  r.far_corner = exact.far_corner.template cast<T>();
  if (exact.outcome == Outcome::plane_misses_view_volume) {
    r.status = Status::plane_misses_view_volume;
    return r;
  }
  if (!all_finite(r.far_corner)) {
    r.status = Status::out_of_range;
    r.detail = "the far corner Q = M^-1 Q' is beyond the range of the scalar type";
    return r;
  }
  return accept_row3(std::move(r), exact.row3, c_hat, convention);
}

/// Whether the far corner's first word comes with a bound of its error (the closed form's explicit
/// solve: a few roundings) or only with an estimate (an LU solve, through rcond).
enum class FirstWord : bool { estimated = false, bounded = true };

/// The accurate method's last steps, once the far corner's first word is solved: refine Q to
/// two words (more where C . Q or a row-3 entry cancels beyond them), C . Q and row 3; where
/// five words do not resolve them, the exact answer.
/// `contraction_floor` bounds below how much each refinement step shrinks Q's error: a few eps
/// for the closed form's explicit solve, 16 eps / rcond for the equilibrated LU.
/// Precondition: scaling C lost nothing (not scaled.lossy).
template <class T, class W, class Corner>
ObliqueResult<T> accurate_finish(const Matrix4<T>& m, const Matrix4<W>& mw,
                                 const ScaledPlane<W>& scaled, Convention convention, Corner q,
                                 W contraction_floor, FirstWord first_word) {
  ObliqueResult<T> r = refuse(m, Method::accurate, Status::ok);
  // c_hat is C scaled by 2^k in W; its rounding to T is C scaled by 2^k in T (each is the
  // exact C_i 2^k rounded once), so plane_scale_shift need not run again.
  const Vector4<T> c_hat(scaled.c_hat.template cast<T>());
  // In its own type the answer needs a second word of Q. float (run in double) rarely does when
  // the first word comes from the closed form, whose few roundings contraction_floor bounds;
  // an LU solve's error is only estimated by rcond, so it always gets a second word.
  if ((std::is_same_v<T, W> || first_word == FirstWord::estimated) && q.finite()) q.add_word();
  r.far_corner = q.value().template cast<T>();
  if (!q.finite() || !all_finite(r.far_corner)) {
    r.status = Status::out_of_range;
    r.detail = "the far corner Q = M^-1 Q' is beyond the range of the scalar type";
    return r;
  }
  const Vector4<W> m4 = mw.row(3).transpose();
  for (;;) {
    const DotTerms<W> terms = dot_terms(scaled.c_hat, q);
    const W q_part = W(2) * q.remaining_error(scaled.c_hat, contraction_floor);
    const AccurateRow3<T, W> row3 = accurate_row3<T>(scaled, terms, q_part, m4, convention);
    if (!terms.all_finite() || !std::isfinite(row3.corner_dot)) {
      r.status = Status::out_of_range;
      r.detail = "C . Q is beyond the range of the scalar type";
      return r;
    }
    if (row3.resolved && !(row3.corner_dot > W(0))) {
      r.status = Status::plane_misses_view_volume;
      return r;
    }
    if (row3.resolved) return accept_row3(std::move(r), row3.row3, c_hat, convention);
    if (!q.add_word()) {
      // Out of words (five, or a correction that is not finite): C . Q's sign or the row is
      // still within Q's error, which rcond may underestimate on a nearly singular M.
      return accurate_exact(m, mw, scaled.c_hat, c_hat, convention);
    }
  }
}

/// The accurate method: the general method's refusals and far corner, with C',
/// Q, C . Q and a carried to about twice the working precision and each entry rounded once.
/// For the perspective shape the solves are the closed form's, and C' has exact signs. Stiff
/// planes (stiff_plane()), and signs of C' within their error bound of zero, are settled in
/// exact arithmetic (exact_cramer.h). `scale`: plane_scale(plane); `entries`: whether every entry
/// of M and C is zero or normal (ordinary_input(); the near plane's test may then be decided by
/// signs).
template <class T>
ObliqueResult<T> accurate(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention,
                          Shape shape, const PlaneScale& scale, Entries entries) {
  using W = typename AccurateWorkingType<T>::type;
  const Vector4<W> plane_w = plane.template cast<W>();
  const ScaledPlane<W> scaled = scale_plane(plane_w, scale);
  const Vector4<W>& c_hat = scaled.c_hat;
  // C' and C . Q may rest on components below the others' rounding, or lost to the scaling.
  const bool stiff = stiff_plane(scale, scaled);
  const auto exact_answer = [&] {
    return accurate_exact(m, Matrix4<W>(m.template cast<W>()), plane_w,
                          Vector4<T>(c_hat.template cast<T>()), convention);
  };
  if (shape == Shape::perspective) {
    const W A = W(m(0, 0)), B = W(m(0, 2)), D = W(m(1, 1)), E = W(m(1, 2)), G = W(m(2, 2)),
            H = W(m(2, 3)), K = W(m(3, 2));
    if (A == W(0) || D == W(0) || H == W(0)) {
      return refuse(m, Method::accurate, Status::singular_projection,
                    "the projection is singular: M11, M22 or M34 is zero");
    }
    if (!(plane.w() < T(0))) return refuse(m, Method::accurate, Status::camera_not_behind_plane);
    if (stiff) return exact_answer();
    // Signs from C itself, exact; Q'_z from the convention's table by the sign of C'_z.
    const ConventionTable<W>& constants = convention_table<W>(convention);
    const W sign_z = W(sign(plane.w())) * sign(H);
    const Vector4<W> corner(W(sign(plane.x())) * sign(A), W(sign(plane.y())) * sign(D),
                            constants.corner_z[(sign_z > W(0)) - (sign_z < W(0)) + 1], W(1));
    std::optional<PerspectiveAnswer<T, W>> fast;
    if constexpr (std::numeric_limits<W>::digits > std::numeric_limits<T>::digits) {
      // float: plain double first, here (not in perspective_row3()'s FMA clone); scaled is not
      // lossy here (not stiff).
      const PerspectiveInput<W> in = perspective_input<W>(c_hat, m, corner, convention);
      if ((in.t == W(0) || in.t == W(1)) && in_fast_range(in)) fast = perspective_row3_plain<T>(in);
    }
    if (!fast) fast = perspective_row3_dispatched<T>(scaled, m, corner, convention);
    if (fast) {
      Answer<T> answer;
      answer.far_corner = fast->far_corner.template cast<T>();
      if (all_finite(answer.far_corner)) {
        // accept_row3's test that the extracted near plane keeps C's side, decided by signs
        // where that is provable. Its x, y and w components are the correctly rounded a C_i
        // (M_4 = (0, 0, K, 0)), so their terms of the dot product with C are >= 0. In double
        // and long double the w term is > 0 (C_w < 0, and in the fast path's range a C_w and its
        // scaled product stay normal), and a z term >= 0 makes the sum positive. float's values
        // can underflow in float: near_plane_kept_by_signs() decides where its proof applies,
        // the full test elsewhere.
        const ConventionTable<T>& table = convention_table<T>(convention);
        T near[4];
        for (int i = 0; i < 4; ++i) near[i] = table.s * fast->row3(i) + table.t * m(3, i);
        NearPlane near_plane;
        if constexpr (std::is_same_v<T, float>) {
          near_plane = near_plane_proved_kept(plane, near, near[2], scale, entries);
        } else {
          near_plane = NearPlane(!(near[2] * T(sign(plane.z())) < T(0)));
        }
        accept_row3(fast->row3, m, Vector4<T>(c_hat.template cast<T>()), table, near_plane, answer);
        return answer.result(m, Method::accurate);
      }
    }
    const Matrix4<W> mw = m.template cast<W>();
    return accurate_finish(m, mw, scaled, convention,
                           RefinedCorner(mw, corner,
                                         [A, B, D, E, G, H, K](const Vector4<W>& v) {
                                           const W z = v.w() / K;
                                           return Vector4<W>((v.x() - B * z) / A,
                                                             (v.y() - E * z) / D, z,
                                                             (v.z() - G * z) / H);
                                         }),
                           W(8) * std::numeric_limits<W>::epsilon(), FirstWord::bounded);
  }
  const Matrix4<W> mw = m.template cast<W>();
  const EquilibratedSolver<W> solver(mw);
  Answer<T> refusal;
  if (solver_refused(solver, refusal)) return refusal.result(m, Method::accurate);
  if (!(plane.w() < T(0))) return refuse(m, Method::accurate, Status::camera_not_behind_plane);
  if (stiff) return exact_answer();
  W transposed_error = W(0);
  const Vector4<W> c_clip = solver.solve_transposed_unscaled(c_hat, &transposed_error);
  if (!all_finite(c_clip)) {
    return refuse(m, Method::accurate, Status::out_of_range,
                  "C' = M^-T C is beyond the range of the scalar type");
  }
  // The bound below assumes a componentwise backward stable solve; where the refinement stalled
  // short of one, the exact signs settle it (fuzz_oblique: a backward error of 0.27 in long double
  // with C' spanning 2^112 gave C'_y = 0.58 the wrong sign, and row 3 was 20% off).
  if (transposed_error > backward_error_limit<W>()) return exact_answer();
  const Vector4<W> correction = solver.transposed_correction_unscaled(c_hat, c_clip);
  const bool refined = all_finite(correction);
  const Vector4<W> estimate = refined ? Vector4<W>(c_clip + correction) : c_clip;
  const Vector4<W> bound =
      refined
          ? Vector4<W>(solver.transposed_error_bound(correction) +
                       std::numeric_limits<W>::epsilon() * solver.transposed_error_bound(c_clip))
          : solver.transposed_error_bound(c_clip);
  const Vector4<W> signs = trusted_signs(estimate, bound);
  // A sign within its error bound of zero: the middle of the edge is within rounding as far,
  // but not within an ulp of the answer where C . Q is small; the exact signs settle it.
  if (signs.x() == W(0) || signs.y() == W(0) || signs.z() == W(0)) return exact_answer();
  // The bounds of C' and of Q's refinement hold where the refinement's residual, summed in twice
  // the working precision, is accurate. Where M's entries span more binades than W holds, its
  // terms can cancel beyond that: a component of C' below eps of the largest may have the wrong
  // sign with its bound (fuzz_oblique: in long double, M spanning 2^100, a C'_y 3e-30 of the
  // others came out positive, the far corner was the wrong one, and row 3 was 40 ulps off), and
  // Q's words stop gaining while its estimated error still shrinks (fuzz_oblique: in double, M
  // spanning 2^71, a known to 64 bits, a row-3 entry cancelling to 2^-65 of its terms came out
  // 10 times too small). Such an input is answered exactly.
  if (magnitude_spread_exceeds<std::numeric_limits<W>::digits>(mw)) return exact_answer();
  const Vector4<W> corner = clip_corner(signs.x(), signs.y(), signs.z(), convention);
  return accurate_finish(
      m, mw, scaled, convention,
      RefinedCorner(mw, corner, [&solver](const Vector4<W>& v) { return solver.solve(v); }),
      W(16) * std::numeric_limits<W>::epsilon() / solver.rcond(), FirstWord::estimated);
}

/// The hand-off of the closed form and the general method to the accurate method, for the
/// inputs they cannot settle in T (stiff planes, stalled solves). Out of line, so that their own
/// path does not grow.
template <class T>
OBLIQUE_NOINLINE ObliqueResult<T> handed_to_accurate(const Matrix4<T>& m, const Vector4<T>& plane,
                                                     Convention convention) {
  return accurate(m, plane, convention, Shape(has_perspective_shape(m)), plane_scale(plane),
                  Entries::unchecked);
}

}  // namespace oblique::detail
