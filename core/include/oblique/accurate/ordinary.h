// The accurate method's path for the common request (issue 17): an input that passed apply()'s
// checks in one pass (detail/input_checks.h) and that the perspective fast path certifies, answered
// inside apply() without accurate()'s general set-up (plane_scale(), an ObliqueResult built,
// passed by value and copied). Everything else goes to accurate(), which gives the same answer
// for these requests: the same scaling, corner, fast path and acceptance, step for step.
#pragma once

#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

#include "oblique/accurate/accurate.h"
#include "oblique/accurate/perspective_fast_path.h"
#include "oblique/depth_convention.h"
#include "oblique/detail/config.h"
#include "oblique/detail/finish.h"
#include "oblique/detail/input_checks.h"
#include "oblique/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/plane_scaling.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique::detail {

/// accurate_ordinary()'s answer, always ok: row 3 of M' and the far corner Q.
template <class T>
struct AccurateAnswer {
  Vector4<T> row3;
  Vector4<T> far_corner;

  /// The ObliqueResult accurate() gives for projection m.
  ObliqueResult<T> result(const Matrix4<T>& m) const {
    ObliqueResult<T> r;
    r.status = Status::ok;
    std::memcpy(r.projection.data(), m.data(), sizeof(T) * 16);
    for (int j = 0; j < 4; ++j) r.projection(2, j) = row3(j);
    r.far_corner = far_corner;
    r.method = Method::accurate;
    return r;
  }
};

/// accurate(m, plane, convention, true) where its perspective fast path answers and the answer
/// is accepted at once: returns true with that answer in `out`, or false (then accurate() must
/// answer; `out` is unspecified). False for a zero A, D or H, C_w >= 0, a plane that is stiff
/// (stiff_plane()) or that plane_scale() scales otherwise than by 2^-e (e the frexp exponent of
/// its largest component), an input outside the fast path's range, an entry the fast path does
/// not certify, a far corner beyond T's range, and a near plane accept_row3() would have to test
/// (double, long double: near_z against C_z by sign, as accurate() decides first; float: that
/// test fails, as accurate() then refuses). accurate() finds the same for each of these, so where
/// this returns true it gives the same status, matrix and far corner.
///
/// Preconditions: ordinary_input(m, plane).ordinary (the entries of m and C finite, each zero or
/// normal; the perspective shape).
template <class T>
OBLIQUE_ALWAYS_INLINE bool accurate_ordinary(const Matrix4<T>& m, const Vector4<T>& plane,
                                             Convention convention, const OrdinaryInput& input,
                                             AccurateAnswer<T>& out) {
  using W = typename AccurateWorkingType<T>::type;
  const W A = W(m(0, 0)), D = W(m(1, 1)), H = W(m(2, 3));
  if (A == W(0) || D == W(0) || H == W(0) || !(plane.w() < T(0))) return false;
  // plane_scale(C), as closed_form_ordinary() reads it from the exponent fields: shift = -e and
  // nothing scaled below the normal range (so scale_plane() is not lossy), and the spread
  // e - low_exponent within max_magnitude_spread<W>() (so the plane is not stiff).
  const int e = static_cast<int>(input.plane_high) - (ExponentBits<T>::bias - 1);
  const int low_exponent = static_cast<int>(input.plane_low) - (ExponentBits<T>::bias - 1);
  const int shift = -e;
  if (shift < std::numeric_limits<T>::min_exponent - low_exponent ||
      !normal_power_of_two<T>(shift) || e - low_exponent > max_magnitude_spread<W>())
    return false;
  // scale_plane(C in W, shift): 2^shift is normal in T, so in W, and the products are exact.
  ScaledPlane<W> scaled;
  const W factor = power_of_two<W>(shift);
  for (int i = 0; i < 4; ++i) scaled.c_hat(i) = W(plane(i)) * factor;
  scaled.shift = shift;
  scaled.lossy = false;
  // clip_corner(), with z from the convention's table by the sign of C'_z (no branch).
  const PerspectiveConstants<W>& constants = perspective_constants<W>(convention);
  const W sign_z = W(sign(plane.w())) * sign(H);
  const Vector4<W> corner(W(sign(plane.x())) * sign(A), W(sign(plane.y())) * sign(D),
                          constants.corner_z[(sign_z > W(0)) - (sign_z < W(0)) + 1], W(1));
  if constexpr (std::is_same_v<T, float>) {
    // accurate()'s first step for float (plain double, perspective_row3_plain()), inline; the
    // double-word pass after it is left to accurate().
    // in_fast_range(in) holds for every ordinary float request, so it is not tested: K, A_i and
    // B_i are zero (B_i only) or normal floats, within [2^-126, 2^128), and C scaled by 2^-e is
    // zero or within [2^-(spread + 1), 1) with spread <= max_magnitude_spread<double>() = 106;
    // all inside double's 2^+-128 there.
    static_assert(
        std::numeric_limits<T>::min_exponent - 1 >= -std::numeric_limits<W>::max_exponent / 8 &&
        std::numeric_limits<T>::max_exponent <= std::numeric_limits<W>::max_exponent / 8 &&
        max_magnitude_spread<W>() + 1 <= std::numeric_limits<W>::max_exponent / 8);
    const PerspectiveInput<W> in = perspective_input<W>(scaled.c_hat, m, corner, convention);
    if (in.t != W(0) && in.t != W(1)) return false;
    const std::optional<PerspectiveAnswer<T, W>> fast = perspective_row3_plain<T>(in);
    if (!fast) return false;
    const Vector4<T>* const row3 = &fast->row3;
    out.far_corner = fast->far_corner.template cast<T>();
    // accurate() ends in accept_row3(): a row that is not finite or loses the near plane is
    // refused there. The near plane's test by signs where it decides (near_plane_kept_by_signs():
    // its x, y and w components are s M'_3i = the correctly rounded a C_i, a > 0), in full
    // otherwise.
    if (!all_finite(out.far_corner) || !all_finite(*row3)) return false;
    T near[4];
    for (int i = 0; i < 4; ++i) near[i] = T(constants.s) * (*row3)(i) + T(constants.t) * m(3, i);
    if (!near_plane_kept_by_signs(plane, near, near[2], e) &&
        !near_plane_kept(*row3, m.row(3), Vector4<T>(scaled.c_hat.template cast<T>()), convention))
      return false;
    out.row3 = *row3;
    return true;
  } else {
    const std::optional<PerspectiveAnswer<T, W>> fast =
        perspective_row3_dispatched<T>(scaled, m, corner, convention);
    if (!fast) return false;
    out.far_corner = fast->far_corner.template cast<T>();
    if (!all_finite(out.far_corner)) return false;
    // accurate()'s test by signs of the extracted near plane; where it does not decide,
    // accept_row3() does, in accurate().
    const T near_z = T(constants.s) * fast->row3(2) + T(constants.t) * m(3, 2);
    if (near_z * T(sign(plane.z())) < T(0)) return false;
    out.row3 = fast->row3;
    return true;
  }
}

}  // namespace oblique::detail
