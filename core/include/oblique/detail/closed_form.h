// The closed form (paper Eqs. 15, 20) and the finish it shares with the general method: the
// core's answer for the common request. oblique.h shows the formula; apply() (definitions.h)
// calls these.
#pragma once

#include <cmath>
#include <limits>

#include "oblique/depth_convention.h"
#include "oblique/detail/closed_form_steps.h"  // Answer, ConventionTable, accept_row3(), ...
#include "oblique/detail/plane_scaling.h"      // PlaneScale, scale_plane()
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique {
namespace detail {

/// The closed form, for the standard perspective shape (has_perspective_shape(): A = M11,
/// B = M13, D = M22, E = M23, G = M33, H = M34, K = M43, zeros elsewhere); paper Eqs. 15, 20:
///   C'   = M^-T C has the signs of (C_x / A, C_y / D, C_w / H); Q' the clip-space corner by them,
///   Q    = M^-1 Q' = ((Q'_x - B/K) / A, (Q'_y - E/K) / D, 1/K, (Q'_z - G/K) / H),
///   a    = (z_high - z_low) / (C . Q),
///   M'_3 = a C - t M_4      (near = s M_3 + t M_4: s = 1; t M_4 - a C where s = -1).
/// Fills `out` (answered or refused), or hands on a plane whose scaling lost bits or a C . Q
/// lost to underflow: the accurate method answers those. `scale`: plane_scale(C); `entries`:
/// whether ordinary_input() found every entry of M and C zero or normal.
template <class T>
OBLIQUE_ALWAYS_INLINE Step closed_form(const Matrix4<T>& m, const Vector4<T>& plane,
                                       Convention convention, const PlaneScale& scale,
                                       Entries entries, Answer<T>& out) {
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  if (A == T(0) || D == T(0) || H == T(0))
    return out.refuse(Status::singular_projection,
                      "the projection is singular: M11, M22 or M34 is zero");
  if (!(plane.w() < T(0))) return out.refuse(Status::camera_not_behind_plane);
  const ScaledPlane<T> scaled = scale_plane(plane, scale);  // c_hat = C 2^k, for C . Q
  if (scaled.lossy) return Step::handed_on;
  // Q'_z from the table by the sign of C'_z, not by a branch (it changes from request to request).
  const ConventionTable<T>& table = convention_table<T>(convention);
  const T sign_z = sign(plane.w()) * sign(H);
  const T corner_z = table.corner_z[(sign_z > T(0)) - (sign_z < T(0)) + 1];
  const Vector4<T> q((sign(plane.x()) * sign(A) - B / K) / A,
                     (sign(plane.y()) * sign(D) - E / K) / D, T(1) / K, (corner_z - G / K) / H);
  return finish(m, plane, q, table, scale, scaled, entries, out);
}

/// From a far corner Q (M_4 . Q = 1) to M'_3 (paper Eqs. 9, 10, 20, every convention):
///   near' = s M'_3 + t M_4 = a C,   far' . Q = 0,   so   a = (z_high - z_low) / (C . Q).
/// C . Q is taken with c_hat = C 2^k, so that it neither overflows nor underflows, and a = a_hat
/// 2^k. Hands on a C . Q lost to underflow or overflowed (the accurate method answers). Shared with
/// the general method. `entries`: ordinary only where M also has the perspective shape (the near
/// plane's test may then be decided by signs); the general method passes Entries::unchecked.
template <class T>
OBLIQUE_ALWAYS_INLINE Step finish(const Matrix4<T>& m, const Vector4<T>& plane, const Vector4<T>& q,
                                  const ConventionTable<T>& table, const PlaneScale& scale,
                                  const ScaledPlane<T>& scaled, Entries entries, Answer<T>& out) {
  out.far_corner = q;
  if (!all_finite(q))
    return out.refuse(Status::out_of_range,
                      "the far corner Q = M^-1 Q' is beyond the range of the scalar type");
  const Vector4<T>& c_hat = scaled.c_hat;
  const T d = c_hat.dot(q);
  // The scaling keeps C in range, not its products with Q: C . Q can overflow here while the
  // answer is in range (fuzz_oblique: a C spanning 1,077 binades scaled up to keep C_w = 5e-324
  // normal, c_hat_z Q_z = 2.8e306 x 1.4e303). The accurate method decides, out_of_range included.
  if (!std::isfinite(d)) return Step::handed_on;
  if (dot_lost_to_underflow(d, c_hat, q)) return Step::handed_on;
  if (!(d > T(0))) return out.refuse(Status::plane_misses_view_volume);
  const T a_hat = table.depth_span / d;
  const T a = times_power_of_two(a_hat, scale.shift);
  // a C rounds once per entry (a_hat c_hat, the same value, where a itself is not normal); the
  // difference is written either way round so that a zero entry stays +0.
  const bool a_normal = std::isfinite(a) && std::abs(a) >= std::numeric_limits<T>::min();
  T ac[4], t_m4[4];
  for (int i = 0; i < 4; ++i) {
    ac[i] = a_normal ? a * plane(i) : a_hat * c_hat(i);
    t_m4[i] = table.t * m(3, i);
  }
  const T* const minuend = table.first == 0 ? ac : t_m4;
  const T* const subtrahend = table.first == 0 ? t_m4 : ac;
  Vector4<T> row3;
  for (int i = 0; i < 4; ++i) row3(i) = minuend[i] - subtrahend[i];  // M'_3 = a C - t M_4
  const NearPlane near_plane =
      near_plane_proved_kept(plane, ac, table.s * row3(2) + t_m4[2], scale, entries);
  return accept_row3(row3, m, c_hat, table, near_plane, out);
}

}  // namespace detail
}  // namespace oblique
