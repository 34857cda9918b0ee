// The oblique near-plane modification (Lengyel): replace the near plane of a projection matrix M
// by a camera-space clip plane C, keep the four side planes, and tilt the far plane as little as
// possible by making it pass through Q, the view-volume corner farthest on C's positive side.
#pragma once

#include <limits>

#include "oblique/accurate/accurate.h"
#include "oblique/depth_convention.h"
#include "oblique/detail/finish.h"
#include "oblique/equilibrated_solver.h"
#include "oblique/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/plane_scaling.h"
#include "oblique/projection.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique {

namespace detail {

// The methods apply() chooses between, defined below (the accurate method in accurate/accurate.h).
template <class T>
ObliqueResult<T> closed_form(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention);
template <class T, class CornerRule = TrustedCornerSigns>
ObliqueResult<T> general(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention,
                         const CornerRule& rule = CornerRule{});

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

namespace detail {

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

/// The largest componentwise backward error the general method accepts from its refined solves
/// (the refinement stops at eps; beyond this it has stalled, and the answer goes to the accurate
/// method).
template <class T>
constexpr T general_backward_error_limit() noexcept {
  return T(8) * std::numeric_limits<T>::epsilon();
}

/// General method for any invertible M, through EquilibratedSolver (equilibration by powers of
/// two, one LU factorisation for both solves):
///   C' = M^-T C   has the signs of   R^-1 C',
///   Q  = M^-1 Q',
/// with the signs of Q' from `rule` (TrustedCornerSigns: the trusted signs of C').
template <class T, class CornerRule>
ObliqueResult<T> general(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention,
                         const CornerRule& rule) {
  const EquilibratedSolver<T> solver(m);
  if (auto refusal = solver_refusal(m, solver, Method::general)) return *refusal;
  if (rule.checks_camera() && !(plane.w() < T(0))) {
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
  const Vector4<T> signs = rule.corner_signs(plane, c_clip, solver.transposed_error_bound(c_clip));
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

}  // namespace detail
}  // namespace oblique

// With OBLIQUE_EXTERN_TEMPLATES (set by linking oblique::core_instances), apply() for float,
// double and long double is compiled once, in that library, instead of in every file that calls
// it: a file calling apply<float> then compiles in well under a second instead of ~12 s.
#ifdef OBLIQUE_EXTERN_TEMPLATES
namespace oblique {
extern template ObliqueResult<float> apply<float>(const Matrix4<float>&, const Vector4<float>&,
                                                  Convention, Method);
extern template ObliqueResult<double> apply<double>(const Matrix4<double>&, const Vector4<double>&,
                                                    Convention, Method);
extern template ObliqueResult<long double> apply<long double>(const Matrix4<long double>&,
                                                              const Vector4<long double>&,
                                                              Convention, Method);
}  // namespace oblique
#endif
