// The oblique near-plane modification (Lengyel): replace the near plane of a projection matrix M
// by a camera-space clip plane C, keep the four side planes, and tilt the far plane as little as
// possible by making it pass through Q, the view-volume corner farthest on C's positive side.
#pragma once

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>

#include "oblique/accurate.h"
#include "oblique/depth_convention.h"
#include "oblique/equilibrated_solver.h"
#include "oblique/exact_cramer.h"
#include "oblique/plane.h"
#include "oblique/projection.h"
#include "oblique/status.h"

namespace oblique {

/// How the far corner Q is found.
enum class Method {
  automatic,    ///< closed_form when the matrix has the standard perspective shape, else general
  closed_form,  ///< Q from the matrix entries, no solve; standard perspective shape only
  general,      ///< C' = M^-T C and Q = M^-1 Q' by one LU factorisation; any invertible M
  accurate,     ///< any invertible M, each entry of M'_3 within an ulp or two of the exact answer
                ///< (accurate.h); closed-form solves for the perspective shape
};

inline constexpr Method all_methods[] = {Method::automatic, Method::closed_form, Method::general,
                                         Method::accurate};

constexpr std::string_view method_name(Method m) noexcept {
  switch (m) {
    case Method::automatic: return "auto";
    case Method::closed_form: return "closed_form";
    case Method::general: return "general";
    case Method::accurate: return "accurate";
  }
  return "unknown";
}

constexpr std::optional<Method> parse_method(std::string_view name) noexcept {
  for (Method m : all_methods) {
    if (method_name(m) == name) return m;
  }
  return std::nullopt;
}

/// The general method refuses a matrix whose equilibrated reciprocal condition number is at or
/// below this: its solve for Q could not be trusted to even two significant digits.
template <class T>
constexpr T singular_rcond_threshold() noexcept {
  return T(16) * std::numeric_limits<T>::epsilon();
}

template <class T>
struct ObliqueResult {
  Status status = Status::ok;
  /// A more specific reason than status_message(status); empty when there is none.
  std::string_view detail;
  /// M' when ok; otherwise the input matrix, unchanged.
  Matrix4<T> projection;
  /// Q = M^-1 Q' in camera space (a direction, w = 0, for infinite projections); set when the
  /// computation got that far (ok, plane_misses_view_volume, out_of_range), else zero.
  Vector4<T> far_corner = Vector4<T>::Zero();
  /// The method that ran: closed_form or general (automatic resolved), accurate where one of them
  /// handed a stiff input to it, or what was asked for if the request was refused before one
  /// ran.
  Method method = Method::automatic;

  bool ok() const noexcept { return status == Status::ok; }
  std::string_view message() const noexcept {
    return detail.empty() ? status_message(status) : detail;
  }
};

namespace detail {

template <class T>
T sign(T x) noexcept {
  return x > T(0) ? T(1) : (x < T(0) ? T(-1) : T(0));
}

template <class T>
ObliqueResult<T> refuse(const Matrix4<T>& m, Method method, Status status,
                        std::string_view why = {}) {
  ObliqueResult<T> r;
  r.status = status;
  r.detail = why;
  r.projection = m;
  r.method = method;
  return r;
}

/// The clip-space corner Q' (paper Eq. 7, every convention): x, y = sgn(C'_x), sgn(C'_y) and z on
/// the depth face C' leans toward (the far face whenever the camera is behind C in a perspective
/// projection). A zero sign gives the middle of the edge, which is an equally far point.
template <class T>
Vector4<T> clip_corner(T sign_x, T sign_y, T sign_z, Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const T z = sign_z > T(0)   ? T(range.z_high)
              : sign_z < T(0) ? T(range.z_low)
                              : T(range.z_low + range.z_high) / T(2);
  return Vector4<T>(sign_x, sign_y, z, T(1));
}

/// r with row 3 of its projection set to row3, or out_of_range where row3 is not finite or the
/// near plane a consumer extracts from it no longer keeps C's side (c_hat: C scaled by 2^k).
template <class T>
ObliqueResult<T> accept_row3(ObliqueResult<T> r, const Vector4<T>& row3, const Vector4<T>& c_hat,
                             Convention convention) {
  const RowCombination near_combination = near_rows(convention);
  const Vector4<T> t_m4 = T(near_combination.m4) * r.projection.row(3).transpose();
  if (!all_finite(row3)) {
    r.status = Status::out_of_range;
    r.detail =
        "the oblique matrix exceeds the range of the scalar type: C passes within rounding "
        "distance of the far corner Q";
    return r;
  }
  // The near plane as a consumer extracts it from the rounded matrix must still keep C's side:
  // when a C is below the precision of M_4's entries, a C - M_4 rounds to -M_4 and it vanishes.
  const Vector4<T> near_extracted = T(near_combination.m3) * row3 + t_m4;
  const Vector4<T> near_hat =
      scaled_by_power_of_two(near_extracted, -magnitude_exponent(near_extracted));
  if (!(near_hat.dot(c_hat) > T(0))) {
    r.status = Status::out_of_range;
    r.detail =
        "the oblique near plane a C is lost to rounding against M_4 (|a C| is below the precision "
        "of M_4's entries): the plane is too far from the view volume for this scalar type";
    return r;
  }
  r.projection.row(2) = row3.transpose();
  return r;
}

template <class T>
ObliqueResult<T> accurate(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention,
                          bool perspective_shape);

/// The hand-off of the closed form and the general method to the accurate method, for the
/// inputs they cannot settle in T (stiff planes, stalled solves). Out of line, so that their own
/// path does not grow.
template <class T>
OBLIQUE_NOINLINE ObliqueResult<T> handed_to_accurate(const Matrix4<T>& m, const Vector4<T>& plane,
                                                     Convention convention) {
  return accurate(m, plane, convention, has_perspective_shape(m));
}

/// Given Q with M_4 . Q = 1, builds M' with M'_3 chosen so that the near plane is a C, a > 0,
/// and the far plane contains Q (paper Eqs. 9, 10 and 20, for every convention):
///   near' = s M'_3 + t M_4 = a C,   far' . Q = 0,   so   a = (z_high - z_low) / (C . Q).
/// `c_hat` is C scaled by 2^k (plane_scale_shift()) so that C . Q neither overflows nor
/// underflows; a C is unchanged by it. The core's callers hand a plane whose scaling loses bits
/// to the accurate method instead.
template <class T>
ObliqueResult<T> finish(const Matrix4<T>& m, const Vector4<T>& plane, const Vector4<T>& q,
                        Convention convention, Method method, int k, const Vector4<T>& c_hat) {
  ObliqueResult<T> r = refuse(m, method, Status::ok);
  r.far_corner = q;
  if (!all_finite(q)) {
    r.status = Status::out_of_range;
    r.detail = "the far corner Q = M^-1 Q' is beyond the range of the scalar type";
    return r;
  }
  const T d = c_hat.dot(q);
  if (!std::isfinite(d)) {
    r.status = Status::out_of_range;
    r.detail = "C . Q is beyond the range of the scalar type";
    return r;
  }
  if (!(d > T(0))) {
    r.status = Status::plane_misses_view_volume;
    return r;
  }
  const DepthRange range = clip_depth_range(convention);
  const T a_hat = T(range.z_high - range.z_low) / d;  // a * 2^-k
  const T a = std::ldexp(a_hat, k);
  // a * C_i rounds once; fall back to a_hat * c_hat_i (the same value) when a itself is not normal.
  const Vector4<T> ac = (std::isfinite(a) && std::abs(a) >= std::numeric_limits<T>::min())
                            ? Vector4<T>(a * plane)
                            : Vector4<T>(a_hat * c_hat);
  const RowCombination near_combination = near_rows(convention);
  // s = +-1: written as a difference either way so that a zero entry stays +0.
  const Vector4<T> t_m4 = T(near_combination.m4) * m.row(3).transpose();
  const Vector4<T> row3 = near_combination.m3 > 0 ? Vector4<T>(ac - t_m4) : Vector4<T>(t_m4 - ac);
  return accept_row3(std::move(r), row3, c_hat, convention);
}

/// Closed form for the standard perspective shape (see has_perspective_shape()):
/// M^T C' = C gives C'_x = C_x / A, C'_y = C_y / D, C'_z = C_w / H (only their signs are needed),
/// and M Q = Q' gives Q = ((Q'_x - B/K) / A, (Q'_y - E/K) / D, 1 / K, (Q'_z - G/K) / H)
/// (the paper's Eq. 15 and Listing 5.1 for gl, K = -1, A > 0, D > 0).
template <class T>
ObliqueResult<T> closed_form(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention) {
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  if (A == T(0) || D == T(0) || H == T(0)) {
    return refuse(m, Method::closed_form, Status::singular_projection,
                  "the projection is singular: M11, M22 or M34 is zero");
  }
  if (!(plane.w() < T(0))) {
    return refuse(m, Method::closed_form, Status::camera_not_behind_plane);
  }
  const ScaledPlane<T> scaled = scale_plane(plane, plane_scale(plane));
  // A component lost to the scaling may carry C . Q (a DBL_MIN beside a -DBL_MAX).
  if (scaled.lossy) return handed_to_accurate(m, plane, convention);
  const Vector4<T> corner = clip_corner(sign(plane.x()) * sign(A), sign(plane.y()) * sign(D),
                                        sign(plane.w()) * sign(H), convention);
  const Vector4<T> q((corner.x() - B / K) / A, (corner.y() - E / K) / D, T(1) / K,
                     (corner.z() - G / K) / H);
  return finish(m, plane, q, convention, Method::closed_form, scaled.shift, scaled.c_hat);
}

/// The signs of C' for the far corner, with 0 for a component within its error bound of zero:
/// a rounded zero's sign would send Q' to a face whose corner may lie arbitrarily far out (a
/// matrix entry of 2^-52 puts it at 2^52), and C . Q, computed there, cancels to nothing. Where
/// the component is really that small, every point of the edge is within rounding as far, and
/// the middle of the edge is the safe choice.
template <class T>
Vector4<T> trusted_signs(const Vector4<T>& c_clip, const Vector4<T>& error_bound) {
  Vector4<T> signs;
  for (int i = 0; i < 4; ++i)
    signs(i) = std::abs(c_clip(i)) <= error_bound(i) ? T(0) : sign(c_clip(i));
  return signs;
}

/// General method for any invertible M, through EquilibratedSolver (equilibration by powers of
/// two, one LU factorisation for both solves):
///   C' = M^-T C   has the signs of   R^-1 C',
///   Q  = M^-1 Q'.
/// The refusal for a matrix the equilibrated solver cannot be trusted with, if any.
template <class T, class W>
std::optional<ObliqueResult<T>> solver_refusal(const Matrix4<T>& m,
                                               const EquilibratedSolver<W>& solver, Method method) {
  switch (solver.failure()) {
    case EquilibratedSolver<W>::Failure::zero_row:
      return refuse(m, method, Status::singular_projection,
                    "the projection is singular: a row is zero");
    case EquilibratedSolver<W>::Failure::zero_column:
      return refuse(m, method, Status::singular_projection,
                    "the projection is singular: a column is zero");
    case EquilibratedSolver<W>::Failure::none: break;
  }
  if (!(solver.rcond() > singular_rcond_threshold<W>())) {
    return refuse(m, method, Status::singular_projection,
                  "the projection is singular or numerically singular (reciprocal condition "
                  "number after equilibration at most 16 epsilon)");
  }
  return std::nullopt;
}

/// The largest componentwise backward error the general method accepts from its refined solves
/// (the refinement stops at eps; beyond this it has stalled, and the answer goes to the accurate
/// method).
template <class T>
constexpr T general_backward_error_limit() noexcept {
  return T(8) * std::numeric_limits<T>::epsilon();
}

template <class T>
ObliqueResult<T> general(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention) {
  const EquilibratedSolver<T> solver(m);
  if (auto refusal = solver_refusal(m, solver, Method::general)) return *refusal;
  if (!(plane.w() < T(0))) {
    return refuse(m, Method::general, Status::camera_not_behind_plane);
  }
  const PlaneScale scale = plane_scale(plane);
  const ScaledPlane<T> scaled = scale_plane(plane, scale);
  // Stiff planes: C' and C . Q may rest on components below the others' rounding.
  if (stiff_plane(scale, scaled)) return handed_to_accurate(m, plane, convention);
  T transposed_error = T(0);
  const Vector4<T> c_clip = solver.solve_transposed_unscaled(scaled.c_hat, &transposed_error);
  if (!all_finite(c_clip)) {
    return refuse(m, Method::general, Status::out_of_range,
                  "C' = M^-T C is beyond the range of the scalar type");
  }
  const Vector4<T> signs = trusted_signs(c_clip, solver.transposed_error_bound(c_clip));
  const Vector4<T> corner = clip_corner(signs.x(), signs.y(), signs.z(), convention);
  T corner_error = T(0);
  const Vector4<T> q = solver.solve(corner, &corner_error);
  // A refinement that stalled short of a small componentwise backward error: the error bounds
  // (the signs' and the checker's) assume one.
  if (all_finite(q) && (transposed_error > general_backward_error_limit<T>() ||
                        corner_error > general_backward_error_limit<T>()))
    return handed_to_accurate(m, plane, convention);
  return finish(m, plane, q, convention, Method::general, scaled.shift, scaled.c_hat);
}

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

/// The accurate method's last steps, once the far corner's first word is solved: refine Q to
/// two words (more where C . Q or a row-3 entry cancels beyond them), C . Q and row 3; where
/// five words do not resolve them, the exact answer.
/// `contraction_floor` bounds below how much each refinement step shrinks Q's error: a few eps
/// for the closed form's explicit solve, 16 eps / rcond for the equilibrated LU.
/// Precondition: scaling C lost nothing (not scaled.lossy).
template <class T, class W, class Corner>
ObliqueResult<T> accurate_finish(const Matrix4<T>& m, const Matrix4<W>& mw,
                                 const ScaledPlane<W>& scaled, Convention convention, Corner q,
                                 W contraction_floor, bool first_word_bounded) {
  ObliqueResult<T> r = refuse(m, Method::accurate, Status::ok);
  // c_hat is C scaled by 2^k in W; its rounding to T is C scaled by 2^k in T (each is the
  // exact C_i 2^k rounded once), so plane_scale_shift need not run again.
  const Vector4<T> c_hat(scaled.c_hat.template cast<T>());
  // In its own type the answer needs a second word of Q. float (run in double) rarely does when
  // the first word comes from the closed form, whose few roundings contraction_floor bounds;
  // an LU solve's error is only estimated by rcond, so it always gets a second word.
  if ((std::is_same_v<T, W> || !first_word_bounded) && q.finite()) q.add_word();
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

/// The accurate method (accurate.h): the general method's refusals and far corner, with C',
/// Q, C . Q and a carried to about twice the working precision and each entry rounded once.
/// For the perspective shape the solves are the closed form's, and C' has exact signs. Stiff
/// planes (stiff_plane()), and signs of C' within their error bound of zero, are settled in
/// exact arithmetic (exact_cramer.h).
template <class T>
ObliqueResult<T> accurate(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention,
                          bool perspective_shape) {
  using W = typename AccurateWorkingType<T>::type;
  const Vector4<W> plane_w = plane.template cast<W>();
  const PlaneScale scale = plane_scale(plane);
  const ScaledPlane<W> scaled = scale_plane(plane_w, scale);
  const Vector4<W>& c_hat = scaled.c_hat;
  // C' and C . Q may rest on components below the others' rounding, or lost to the scaling.
  const bool stiff = stiff_plane(scale, scaled);
  const auto exact_answer = [&] {
    return accurate_exact(m, Matrix4<W>(m.template cast<W>()), plane_w,
                          Vector4<T>(c_hat.template cast<T>()), convention);
  };
  if (perspective_shape) {
    const W A = W(m(0, 0)), B = W(m(0, 2)), D = W(m(1, 1)), E = W(m(1, 2)), G = W(m(2, 2)),
            H = W(m(2, 3)), K = W(m(3, 2));
    if (A == W(0) || D == W(0) || H == W(0)) {
      return refuse(m, Method::accurate, Status::singular_projection,
                    "the projection is singular: M11, M22 or M34 is zero");
    }
    if (!(plane.w() < T(0))) return refuse(m, Method::accurate, Status::camera_not_behind_plane);
    if (stiff) return exact_answer();
    // Signs from C itself, exact.
    const Vector4<W> corner =
        clip_corner(W(sign(plane.x())) * sign(A), W(sign(plane.y())) * sign(D),
                    W(sign(plane.w())) * sign(H), convention);
    if (const auto fast = perspective_row3_dispatched<T>(scaled, m, corner, convention)) {
      ObliqueResult<T> r = refuse(m, Method::accurate, Status::ok);
      r.far_corner = fast->far_corner.template cast<T>();
      if (all_finite(r.far_corner)) {
        // accept_row3's test that the extracted near plane keeps C's side, decided by signs:
        // its x, y and w components are the correctly rounded a C_i (M_4 = (0, 0, K, 0)), so
        // their terms of the dot product with C are >= 0, and the w term > 0 (C_w < 0, and in
        // the fast path's range a C_w and its scaled product stay normal in double and long
        // double); a z term >= 0 then makes the sum positive, as accept_row3 would find.
        // (float's fast-path values can underflow in float: accept_row3 decides.)
        if constexpr (!std::is_same_v<T, float>) {
          const RowCombination near_combination = near_rows(convention);
          const T near_z =
              T(near_combination.m3) * fast->row3(2) + T(near_combination.m4) * m(3, 2);
          if (!(near_z * T(sign(plane.z())) < T(0))) {
            r.projection.row(2) = fast->row3.transpose();
            return r;
          }
        }
        return accept_row3(std::move(r), fast->row3, Vector4<T>(c_hat.template cast<T>()),
                           convention);
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
                           W(8) * std::numeric_limits<W>::epsilon(), true);
  }
  const Matrix4<W> mw = m.template cast<W>();
  const EquilibratedSolver<W> solver(mw);
  if (auto refusal = solver_refusal(m, solver, Method::accurate)) return *refusal;
  if (!(plane.w() < T(0))) return refuse(m, Method::accurate, Status::camera_not_behind_plane);
  if (stiff) return exact_answer();
  const Vector4<W> c_clip = solver.solve_transposed_unscaled(c_hat);
  if (!all_finite(c_clip)) {
    return refuse(m, Method::accurate, Status::out_of_range,
                  "C' = M^-T C is beyond the range of the scalar type");
  }
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
  const Vector4<W> corner = clip_corner(signs.x(), signs.y(), signs.z(), convention);
  return accurate_finish(
      m, mw, scaled, convention,
      RefinedCorner(mw, corner, [&solver](const Vector4<W>& v) { return solver.solve(v); }),
      W(16) * std::numeric_limits<W>::epsilon() / solver.rcond(), false);
}

}  // namespace detail

/// Makes the near plane of `projection` the camera-space plane `plane` (kept side positive),
/// in the given depth convention (paper Eq. 20 generalised):
///   M'_1 = M_1, M'_2 = M_2, M'_4 = M_4, near(M') = a C, far(M') . Q = 0,
/// with Q = M^-1 Q' the corner of the original view volume farthest on C's positive side.
/// Preconditions are checked, in this order, and reported as statuses: finite input
/// (invalid_input), an invertible matrix (singular_projection), C_w < 0 (camera_not_behind_plane),
/// C . Q > 0 (plane_misses_view_volume), a representable answer (out_of_range). A matrix whose
/// nonzero entries span more than max_magnitude_spread<T>() binades is refused as out_of_range
/// right after the finiteness check.
template <class T>
ObliqueResult<T> apply(const Matrix4<T>& projection, const Vector4<T>& plane, Convention convention,
                       Method method = Method::automatic) {
  if (!all_finite(projection)) {
    return detail::refuse(projection, method, Status::invalid_input,
                          "the projection matrix has a NaN or infinite entry");
  }
  if (!all_finite(plane)) {
    return detail::refuse(projection, method, Status::invalid_input,
                          "the clip plane has a NaN or infinite component");
  }
  if (magnitude_spread_exceeds<max_magnitude_spread<T>()>(projection)) {
    return detail::refuse(projection, method, Status::out_of_range,
                          "the projection's nonzero entries span more binades than twice the "
                          "precision of the scalar type (max_magnitude_spread)");
  }
  const bool perspective_shape = has_perspective_shape(projection);
  if (method == Method::automatic) {
    method = perspective_shape ? Method::closed_form : Method::general;
  }
  if (method == Method::closed_form) {
    if (!perspective_shape) {
      return detail::refuse(projection, method, Status::invalid_input,
                            "closed_form needs the standard perspective shape (zeros outside "
                            "M11, M13, M22, M23, M33, M34, M43; M43 != 0); use auto or general");
    }
    return detail::closed_form(projection, plane, convention);
  }
  if (method == Method::accurate) {
    return detail::accurate(projection, plane, convention, perspective_shape);
  }
  return detail::general(projection, plane, convention);
}

}  // namespace oblique
