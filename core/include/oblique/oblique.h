// The oblique near-plane modification (Lengyel): replace the near plane of a projection matrix M
// by a camera-space clip plane C, keep the four side planes, and tilt the far plane as little as
// possible by making it pass through Q, the view-volume corner farthest on C's positive side.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>

#include "oblique/accurate/accurate.h"
#include "oblique/accurate/ordinary.h"
#include "oblique/depth_convention.h"
#include "oblique/detail/batch.h"
#include "oblique/detail/finish.h"
#include "oblique/detail/input_checks.h"
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
template <class T>
struct ClosedFormAnswer;
template <class T>
OBLIQUE_ALWAYS_INLINE bool closed_form_ordinary(const Matrix4<T>& m, const Vector4<T>& plane,
                                                Convention convention, const OrdinaryInput& input,
                                                ClosedFormAnswer<T>& out);
template <class T>
ObliqueResult<T> apply_checked(const Matrix4<T>& projection, const Vector4<T>& plane,
                               Convention convention, Method method, bool ordinary);
template <class T>
ObliqueResult<T> general(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention);
template <class T>
struct ConventionTable;
template <class T>
const ConventionTable<T>& convention_table(Convention convention);

/// apply_batch()'s answer to request i, one request at a time.
template <class T>
OBLIQUE_ALWAYS_INLINE void batch_answer(const Matrix4<T>& m, const Vector4<T>& plane,
                                        Convention convention, Method method, Matrix4<T>& out,
                                        Status& status) {
  const detail::OrdinaryInput input = detail::ordinary_input(m, plane);
  detail::ClosedFormAnswer<T> answer;
  if (input.ordinary && (method == Method::automatic || method == Method::closed_form) &&
      detail::closed_form_ordinary(m, plane, convention, input, answer)) {
    if (&out != &m) out = m;
    if (answer.status == Status::ok) {
      for (int j = 0; j < 4; ++j) out(2, j) = answer.row3(j);
    }
    status = answer.status;
  } else {
    const ObliqueResult<T> r = detail::apply_checked(m, plane, convention, method, input.ordinary);
    out = r.projection;
    status = r.status;
  }
}

/// batch_answer() kept out of its caller: the requests a block of closed_form_lanes() leaves.
template <class T>
OBLIQUE_NOINLINE void batch_answer_apart(const Matrix4<T>& m, const Vector4<T>& plane,
                                         Convention convention, Method method, Matrix4<T>& out,
                                         Status& status) {
  batch_answer(m, plane, convention, method, out, status);
}

/// apply_batch()'s blocks: W closed-form requests at a time through closed_form_lanes()
/// (detail/batch.h), each block read before it is answered; `answered(j, lanes, k)` for request
/// j answered by lane k, `apart(j)` for a request the block leaves. Returns how many requests the
/// blocks covered (a multiple of W, 0 without a block path or for another method); the rest go
/// one by one.
template <class T, bool FarCorner, class Answered, class Apart>
OBLIQUE_ALWAYS_INLINE std::size_t closed_form_blocks(const Matrix4<T>* projections,
                                                     const Vector4<T>* planes, std::size_t count,
                                                     Convention convention, Method method,
                                                     Answered&& answered, Apart&& apart) {
  std::size_t i = 0;
  if constexpr (closed_form_lanes_available<T>()) {
    if (method == Method::automatic || method == Method::closed_form) {
      constexpr int W = closed_form_lane_count<T>;
      const ConventionTable<T>& table = convention_table<T>(convention);
      ClosedFormLanes<T, W> lanes;
      const bool avx2 = closed_form_block_avx2_supported();
      for (; count - i >= std::size_t(W); i += W) {
        closed_form_block_on<T, W, FarCorner>(avx2, projections + i, planes + i, table, lanes);
        for (int k = 0; k < W; ++k) {
          const std::size_t j = i + std::size_t(k);
          if (lanes.fast[k] != T(0)) {
            answered(j, lanes, k);
          } else {
            apart(j);
          }
        }
      }
    }
  }
  return i;
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
  // The common request passes the first four checks at once (detail/input_checks.h); the closed
  // form then answers it here, and every other request goes through detail::apply_checked().
  // The accurate method's common request likewise (accurate/ordinary.h).
  const detail::OrdinaryInput input = detail::ordinary_input(projection, plane);
  if (input.ordinary && (method == Method::automatic || method == Method::closed_form)) {
    detail::ClosedFormAnswer<T> answer;
    if (detail::closed_form_ordinary(projection, plane, convention, input, answer))
      return answer.result(projection);
  } else if (input.ordinary && method == Method::accurate) {
    detail::AccurateAnswer<T> answer;
    if (detail::accurate_ordinary(projection, plane, convention, input, answer))
      return answer.result(projection);
  }
  return detail::apply_checked(projection, plane, convention, method, input.ordinary);
}

/// apply() over `count` requests in one convention: for each i, out[i] and statuses[i] are the
/// projection and status of apply(projections[i], planes[i], convention, method) (M' when ok,
/// the input matrix otherwise), bit for bit. The closed form's ordinary requests are answered
/// without building an ObliqueResult. `out` may be `projections` (in place); the arrays must
/// otherwise not overlap.
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, Matrix4<T>* out, Status* statuses) {
  std::size_t i = detail::closed_form_blocks<T, false>(
      projections, planes, count, convention, method,
      [&](std::size_t j, const auto& lanes, int k) {
        if (&out[j] != &projections[j])
          std::memcpy(out[j].data(), projections[j].data(), sizeof(T) * 16);
        for (int e = 0; e < 4; ++e) out[j](2, e) = lanes.row3[e][k];
        statuses[j] = Status::ok;
      },
      [&](std::size_t j) {
        detail::batch_answer_apart(projections[j], planes[j], convention, method, out[j],
                                   statuses[j]);
      });
  for (; i < count; ++i)
    detail::batch_answer(projections[i], planes[i], convention, method, out[i], statuses[i]);
}

/// apply() over `count` requests in one convention: results[i] = apply(projections[i], planes[i],
/// convention, method).
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, ObliqueResult<T>* results) {
  std::size_t i = detail::closed_form_blocks<T, true>(
      projections, planes, count, convention, method,
      [&](std::size_t j, const auto& lanes, int k) {
        ObliqueResult<T>& r = results[j];
        r.status = Status::ok;
        r.detail = {};
        std::memcpy(r.projection.data(), projections[j].data(), sizeof(T) * 16);
        for (int e = 0; e < 4; ++e) {
          r.projection(2, e) = lanes.row3[e][k];
          r.far_corner(e) = lanes.q[e][k];
        }
        r.method = Method::closed_form;
      },
      [&](std::size_t j) { results[j] = apply(projections[j], planes[j], convention, method); });
  for (; i < count; ++i) results[i] = apply(projections[i], planes[i], convention, method);
}

namespace detail {

/// apply()'s checks one by one, in the documented order, and the method; `ordinary`: the
/// request passed ordinary_input() (so the first four checks pass).
template <class T>
OBLIQUE_NOINLINE ObliqueResult<T> apply_checked(const Matrix4<T>& projection,
                                                const Vector4<T>& plane, Convention convention,
                                                Method method, bool ordinary) {
  if (ordinary) {
    if (method == Method::automatic || method == Method::closed_form)
      return detail::closed_form(projection, plane, convention);
    if (method == Method::accurate) return detail::accurate(projection, plane, convention, true);
    return detail::general(projection, plane, convention);
  }
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

}  // namespace detail

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

/// A convention's constants as closed_form_ordinary() reads them, in T: corner_z = {z_low,
/// (z_low + z_high) / 2, z_high} (clip_corner() for sgn C'_z = -1, 0, 1), depth_span =
/// z_high - z_low, and the near plane s M_3 + t M_4 (near_rows()), with first = 0 for s = 1 and
/// 1 for s = -1 (M'_3 = a C - t M_4, or t M_4 - a C).
template <class T>
struct ConventionTable {
  T corner_z[3];
  T depth_span;
  T s, t;
  int first;
};

template <class T>
constexpr ConventionTable<T> make_convention_table(Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const RowCombination near_combination = near_rows(convention);
  return {{T(range.z_low), T(range.z_low + range.z_high) / T(2), T(range.z_high)},
          T(range.z_high - range.z_low),
          T(near_combination.m3),
          T(near_combination.m4),
          near_combination.m3 > 0 ? 0 : 1};
}

/// The table for `convention` (gl, zero_one, reversed_z: the enumerators' order).
template <class T>
const ConventionTable<T>& convention_table(Convention convention) {
  static constexpr ConventionTable<T> tables[] = {make_convention_table<T>(Convention::gl),
                                                  make_convention_table<T>(Convention::zero_one),
                                                  make_convention_table<T>(Convention::reversed_z)};
  return tables[static_cast<int>(convention)];
}

/// closed_form()'s answer, without the matrix it modifies: the status (and message), row 3 of
/// M' when ok, and Q when the computation got that far.
template <class T>
struct ClosedFormAnswer {
  Status status = Status::ok;
  std::string_view detail;
  Vector4<T> row3 = Vector4<T>::Zero();
  Vector4<T> far_corner = Vector4<T>::Zero();

  /// The ObliqueResult closed_form() gives for projection m.
  ObliqueResult<T> result(const Matrix4<T>& m) const {
    ObliqueResult<T> r;
    r.status = status;
    r.detail = detail;
    std::memcpy(r.projection.data(), m.data(), sizeof(T) * 16);
    if (status == Status::ok) {
      for (int j = 0; j < 4; ++j) r.projection(2, j) = row3(j);
    }
    r.far_corner = far_corner;
    r.method = Method::closed_form;
    return r;
  }
};

/// closed_form() for an input that passed ordinary_input(), in one function and
/// without libm calls: the same statuses, messages and bits, step for step (scale_plane(),
/// finish() and accept_row3() with C's exponents read from its bits). Returns false (`out` then
/// means nothing) where closed_form() would scale C otherwise than by 2^-e (e the exponent of its
/// largest component: a plane whose nonzero components span about min_exponent binades, or a
/// largest component at or above 2^(max_exponent - 2)), or where C . Q was lost to underflow
/// (dot_lost_to_underflow()); closed_form() then answers (and hands a lossy scaling, or such a
/// C . Q, to the accurate method).
///
/// Preconditions: ordinary_input(m, plane).ordinary, so the entries of m and C are finite and
/// each is zero or normal.
template <class T>
OBLIQUE_ALWAYS_INLINE bool closed_form_ordinary(const Matrix4<T>& m, const Vector4<T>& plane,
                                                Convention convention, const OrdinaryInput& input,
                                                ClosedFormAnswer<T>& out) {
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  if (A == T(0) || D == T(0) || H == T(0)) {
    out.status = Status::singular_projection;
    out.detail = "the projection is singular: M11, M22 or M34 is zero";
    return true;
  }
  if (!(plane.w() < T(0))) {
    out.status = Status::camera_not_behind_plane;
    return true;
  }
  // plane_scale(C): e = frexp exponent of max |C_i| (C_w != 0), low_exponent that of the
  // smallest nonzero |C_i|, both (every component zero or normal) biased field - (bias - 1).
  const unsigned high = input.plane_high, low = input.plane_low;
  const int e = static_cast<int>(high) - (ExponentBits<T>::bias - 1);
  const int low_exponent = static_cast<int>(low) - (ExponentBits<T>::bias - 1);
  const int keep_normal = std::numeric_limits<T>::min_exponent - low_exponent;
  // plane_scale() gives shift = -e, nothing below the normal range, exactly when -e >= keep_normal;
  // scale_plane() then multiplies by 2^-e where that is normal (and so does finish()'s ldexp).
  const int shift = -e;
  if (shift < keep_normal || !normal_power_of_two<T>(shift)) return false;
  const T factor = power_of_two<T>(shift);
  Vector4<T> c_hat;  // plane * factor, in a loop: Eigen's assignment is a call for long double
  for (int i = 0; i < 4; ++i) c_hat(i) = plane(i) * factor;
  // clip_corner(): z from a table by the sign of C'_z, not by a branch (the convention, and so
  // the sign of H, changes from one request to the next).
  const ConventionTable<T>& table = convention_table<T>(convention);
  const T sign_z = sign(plane.w()) * sign(H);
  const T corner_z = table.corner_z[(sign_z > T(0)) - (sign_z < T(0)) + 1];
  const Vector4<T> q((sign(plane.x()) * sign(A) - B / K) / A,
                     (sign(plane.y()) * sign(D) - E / K) / D, T(1) / K, (corner_z - G / K) / H);
  // finish():
  out.far_corner = q;
  if (!all_finite(q)) {
    out.status = Status::out_of_range;
    out.detail = "the far corner Q = M^-1 Q' is beyond the range of the scalar type";
    return true;
  }
  const T d = c_hat.dot(q);
  if (!std::isfinite(d)) {
    out.status = Status::out_of_range;
    out.detail = "C . Q is beyond the range of the scalar type";
    return true;
  }
  if (dot_lost_to_underflow(d, c_hat, q)) return false;  // finish() hands it on
  if (!(d > T(0))) {
    out.status = Status::plane_misses_view_volume;
    return true;
  }
  const T a_hat = table.depth_span / d;
  const T a = a_hat * factor;  // std::ldexp(a_hat, shift): 2^shift is normal
  // a C (or a_hat c_hat where a is not normal) and t M_4; M'_3 = a C - t M_4 for s = 1 and
  // t M_4 - a C for s = -1, the operands chosen by pointer (a zero entry stays +0 either way).
  const bool a_normal = std::isfinite(a) && std::abs(a) >= std::numeric_limits<T>::min();
  T ac[4], t_m4[4];
  for (int i = 0; i < 4; ++i) {
    ac[i] = a_normal ? a * plane(i) : a_hat * c_hat(i);
    t_m4[i] = table.t * m(3, i);
  }
  const T* const minuend = table.first == 0 ? ac : t_m4;
  const T* const subtrahend = table.first == 0 ? t_m4 : ac;
  Vector4<T> row3;
  bool finite = true;
  for (int i = 0; i < 4; ++i) {
    row3(i) = minuend[i] - subtrahend[i];
    finite &= std::abs(row3(i)) <= std::numeric_limits<T>::max();
  }
  // accept_row3():
  if (!finite) {
    out.status = Status::out_of_range;
    out.detail = accept_row3_messages::not_finite;
    return true;
  }
  if (!near_plane_kept_by_signs(plane, ac, table.s * row3(2) + t_m4[2], e)) {
    // near_hat = scaled_by_power_of_two(near, -magnitude_exponent(near)), near = s M'_3 + t M_4.
    Vector4<T> near_hat;
    T largest = T(0);
    for (int i = 0; i < 4; ++i) {
      near_hat(i) = table.s * row3(i) + t_m4[i];
      largest = std::max(largest, T(std::abs(near_hat(i))));
    }
    const int near_shift = largest > T(0) ? -frexp_exponent(largest) : 0;
    if (normal_power_of_two<T>(near_shift)) {
      const T near_factor = power_of_two<T>(near_shift);
      for (int i = 0; i < 4; ++i) near_hat(i) *= near_factor;
    } else {
      for (int i = 0; i < 4; ++i) near_hat(i) = std::ldexp(near_hat(i), near_shift);
    }
    if (!(near_hat.dot(c_hat) > T(0))) {
      out.status = Status::out_of_range;
      out.detail = accept_row3_messages::near_plane_lost;
      return true;
    }
  }
  out.status = Status::ok;
  out.row3 = row3;
  return true;
}

/// General method for any invertible M, through EquilibratedSolver (equilibration by powers of
/// two, one LU factorisation for both solves):
///   C' = M^-T C   has the signs of   R^-1 C',
///   Q  = M^-1 Q',
/// with the signs of Q' those of C' (each one outside C'_k's error bound, or C'_k exactly 0).
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
  // A nonzero C'_k within its error bound goes to the accurate method, which settles its sign
  // exactly. The bound comes from a computed inverse and can be far above the error on matrices
  // whose entries differ greatly in size: fuzz_oblique found C'_z = 12.5 (first-order error
  // 1.4e-4) under a bound of 147 in float, and the middle corner the trusted signs take there
  // moved C . Q by 3.6%. A C'_k that came out 0 is within its first-order error of 0 (the solve
  // is componentwise backward stable, checked below), so the middle is as good as either corner
  // (the checker allows that much), and it avoids a corner that may be far out.
  const Vector4<T> bound = solver.transposed_error_bound(c_clip);
  for (int i = 0; i < 3; ++i) {
    if (c_clip(i) != T(0) && std::abs(c_clip(i)) <= bound(i))
      return handed_to_accurate(m, plane, convention);
  }
  const Vector4<T> corner =
      clip_corner(sign(c_clip.x()), sign(c_clip.y()), sign(c_clip.z()), convention);
  T corner_error = T(0);
  const Vector4<T> q = solver.solve(corner, &corner_error);
  // A refinement that stalled short of a small componentwise backward error: the error bounds
  // (the signs' and the checker's) assume one.
  if (all_finite(q) &&
      (transposed_error > backward_error_limit<T>() || corner_error > backward_error_limit<T>()))
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
