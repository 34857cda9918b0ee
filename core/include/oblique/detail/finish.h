// What the closed form, the general method and the accurate method share: the refusal, the
// clip-space far corner Q' from the signs of C', the refusal of a solver that cannot be trusted,
// and the finish from a far corner Q to the oblique matrix M'.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>

#include "oblique/depth_convention.h"
#include "oblique/detail/config.h"
#include "oblique/equilibrated_solver.h"
#include "oblique/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique {

/// The general method refuses a matrix whose equilibrated reciprocal condition number is at or
/// below this: its solve for Q could not be trusted to even two significant digits.
template <class T>
constexpr T singular_rcond_threshold() noexcept {
  return T(16) * std::numeric_limits<T>::epsilon();
}

namespace detail {

/// The smallest |C . Q| the core's dot product of c_hat (C scaled so that its largest component
/// is about 1) and Q settles whatever its products lost to underflow: min / epsilon =
/// 2^(min_exponent - 2 + digits) (2^-970 in double). A product c_hat_i Q_i below the normal range
/// loses up to half a subnormal ulp; at this size four such losses are below 2^-100 of the sum,
/// but a smaller C . Q may rest on them, or be 0 because of them (fuzz_oblique: C = (-0.25, 3.25,
/// 0, -1.8e308) on an infinite reversed-Z matrix, C . Q = 5.7e-30 of which c_hat . Q kept
/// nothing).
template <class T>
constexpr T min_settled_dot() noexcept {
  return std::numeric_limits<T>::min() / std::numeric_limits<T>::epsilon();
}

/// Whether the rounded c_hat . q = d cannot be trusted for underflow: |d| below
/// min_settled_dot() and a product of nonzero factors below the normal range. The closed form
/// and the general method hand such a C . Q to the accurate method. (A d that small from normal
/// products alone is cancellation, which the rounding bounds cover.)
template <class T>
bool dot_lost_to_underflow(T d, const Vector4<T>& c_hat, const Vector4<T>& q) noexcept {
  if (!(std::abs(d) < min_settled_dot<T>())) return false;
  for (int i = 0; i < 4; ++i) {
    if (c_hat(i) != T(0) && q(i) != T(0) &&
        std::abs(c_hat(i) * q(i)) < std::numeric_limits<T>::min())
      return true;
  }
  return false;
}

/// The accurate method on an input the closed form or the general method cannot settle in T
/// (accurate/accurate.h).
template <class T>
ObliqueResult<T> handed_to_accurate(const Matrix4<T>& m, const Vector4<T>& plane,
                                    Convention convention);

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

/// accept_row3()'s refusals (closed_form_ordinary() gives the same ones).
namespace accept_row3_messages {
inline constexpr std::string_view not_finite =
    "the oblique matrix exceeds the range of the scalar type: C passes within rounding "
    "distance of the far corner Q";
inline constexpr std::string_view near_plane_lost =
    "the oblique near plane a C is lost to rounding against M_4 (|a C| is below the precision "
    "of M_4's entries): the plane is too far from the view volume for this scalar type";
}  // namespace accept_row3_messages

/// accept_row3()'s test that the near plane a consumer extracts from the rounded matrix,
/// s row3 + t M_4 (m4: row 4 of M), still keeps C's side (c_hat: C scaled by 2^k): when a C is
/// below the precision of M_4's entries, a C - M_4 rounds to -M_4 and it vanishes. Shared with
/// the accurate method's ordinary path (accurate/ordinary.h), so both decide alike.
template <class T, class Row>
bool near_plane_kept(const Vector4<T>& row3, const Row& m4, const Vector4<T>& c_hat,
                     Convention convention) {
  const RowCombination near_combination = near_rows(convention);
  const Vector4<T> t_m4 = T(near_combination.m4) * m4.transpose();
  const Vector4<T> near_extracted = T(near_combination.m3) * row3 + t_m4;
  const Vector4<T> near_hat =
      scaled_by_power_of_two(near_extracted, -magnitude_exponent(near_extracted));
  return near_hat.dot(c_hat) > T(0);
}

/// accept_row3()'s test that the near plane a consumer extracts, near = s M'_3 + t M_4, keeps
/// C's side (near_hat . c_hat > 0, near_hat = near 2^-E with 2^(E-1) <= max |near_i| < 2^E),
/// decided by signs where that is provable; false where it is not (the caller then runs the
/// test). For the perspective shape M_4 = (0, 0, K, 0), so near_i = a C_i in value for
/// i = x, y, w (ac: those products, with a > 0), and each of those terms of the dot product
/// is >= 0; if near_z and C_z do not have opposite signs, the z term is >= 0 too, and a
/// rounded sum of terms >= 0 is > 0 exactly when one term is (terms < 1: no overflow). The w
/// term is: with L(x) the frexp exponent (2^(L - 1) <= |x| < 2^L), |near_hat_w| >=
/// 2^(L(a C_w) - 1 - E) and |c_hat_w| = |C_w| 2^-e >= 2^(L(C_w) - 1 - e), so where
/// L(a C_w) + L(C_w) - E - e - 2 >= min_exponent - 1 both and their product are normal, the
/// scaling is exact, and the product of two negatives rounds to a positive number.
/// Preconditions: as closed_form_ordinary() at accept_row3() (the accurate method's ordinary path
/// meets them too: accurate/ordinary.h); e the frexp exponent of max |C_i|, near_z the z
/// component of near.
template <class T>
OBLIQUE_ALWAYS_INLINE bool near_plane_kept_by_signs(const Vector4<T>& plane, const T (&ac)[4],
                                                    T near_z, int e) {
  if (sign(near_z) * sign(plane.z()) < T(0)) return false;
  const T largest = std::max(std::max(std::abs(ac[0]), std::abs(ac[1])),
                             std::max(std::abs(ac[3]), std::abs(near_z)));
  constexpr unsigned all_ones = ExponentBits<T>::all_ones;
  constexpr int offset = ExponentBits<T>::bias - 1;  // L(x) = field - offset for normal x
  const unsigned f_largest = biased_exponent(largest), f_ac_w = biased_exponent(ac[3]);
  // Normal (so L is read from the field), finite, nonzero: largest, a C_w, and C_w (ordinary).
  if (f_largest - 1u >= all_ones - 1u || f_ac_w - 1u >= all_ones - 1u) return false;
  const int l_ac_w = static_cast<int>(f_ac_w) - offset;
  const int l_c_w = static_cast<int>(biased_exponent(plane.w())) - offset;
  const int l_largest = static_cast<int>(f_largest) - offset;
  return l_ac_w + l_c_w - l_largest - e - 2 >= std::numeric_limits<T>::min_exponent - 1;
}

/// r with row 3 of its projection set to row3, or out_of_range where row3 is not finite or the
/// near plane a consumer extracts from it no longer keeps C's side (c_hat: C scaled by 2^k).
template <class T>
ObliqueResult<T> accept_row3(ObliqueResult<T> r, const Vector4<T>& row3, const Vector4<T>& c_hat,
                             Convention convention) {
  if (!all_finite(row3)) {
    r.status = Status::out_of_range;
    r.detail = accept_row3_messages::not_finite;
    return r;
  }
  if (!near_plane_kept(row3, r.projection.row(3), c_hat, convention)) {
    r.status = Status::out_of_range;
    r.detail = accept_row3_messages::near_plane_lost;
    return r;
  }
  r.projection.row(2) = row3.transpose();
  return r;
}

/// Given Q with M_4 . Q = 1, builds M' with M'_3 chosen so that the near plane is a C, a > 0,
/// and the far plane contains Q (paper Eqs. 9, 10 and 20, for every convention):
///   near' = s M'_3 + t M_4 = a C,   far' . Q = 0,   so   a = (z_high - z_low) / (C . Q).
/// `c_hat` is C scaled by 2^k (plane_scale_shift()) so that C . Q neither overflows nor
/// underflows; a C is unchanged by it. The core's callers hand a plane whose scaling loses bits
/// to the accurate method instead; a C . Q lost to underflow (dot_lost_to_underflow()) goes there
/// from here.
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
  if (dot_lost_to_underflow(d, c_hat, q)) return handed_to_accurate(m, plane, convention);
  if (!(d > T(0))) {
    r.status = Status::plane_misses_view_volume;
    return r;
  }
  const DepthRange range = clip_depth_range(convention);
  const T a_hat = T(range.z_high - range.z_low) / d;  // a * 2^-k
  const T a = times_power_of_two(a_hat, k);           // std::ldexp(a_hat, k)
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

}  // namespace detail
}  // namespace oblique
