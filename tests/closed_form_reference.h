// TEST-ONLY REFERENCE ORACLE: the closed form's path through apply() as it was before issue 17
// made it fast (commit 3359b37): every check one by one, Eigen's allFinite(), and libm's frexp,
// ldexp and ilogb where the core now reads and writes exponent bits. Not for use outside tests:
// closed_form_same_bits_test compares the core with it, bit for bit. The pieces issue 17 left
// unchanged (has_perspective_shape, magnitude_spread_exceeds, clip_corner, sign, the accurate
// method the closed form hands stiff planes to, and dot_lost_to_underflow(), the hand-off that
// issue 23 added to finish() for a C . Q lost to underflow) are the core's own.
#pragma once

#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

#include "oblique/oblique.h"

namespace oblique::reference {

template <class Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}

template <class Derived>
int magnitude_exponent(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  const T largest = v.cwiseAbs().maxCoeff();
  if (!(largest > T(0))) return 0;
  int exponent = 0;
  std::frexp(largest, &exponent);
  return exponent;
}

template <class Derived>
typename Derived::PlainObject scaled_by_power_of_two(const Eigen::MatrixBase<Derived>& v, int k) {
  using T = typename Derived::Scalar;
  typename Derived::PlainObject out = v;
  if (k >= std::numeric_limits<T>::min_exponent - 1 && k < std::numeric_limits<T>::max_exponent) {
    const T factor = std::ldexp(T(1), k);
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] *= factor;
  } else {
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = std::ldexp(out.data()[i], k);
  }
  return out;
}

struct PlaneScale {
  int shift = 0;
  bool below_normal = false;
};

template <class T>
PlaneScale plane_scale(const Vector4<T>& v) {
  const int e = magnitude_exponent(v);
  T low = std::numeric_limits<T>::infinity();
  for (int i = 0; i < 4; ++i) {
    if (v(i) != T(0)) low = std::min(low, T(std::abs(v(i))));
  }
  if (!(low < std::numeric_limits<T>::infinity())) return {-e, false};
  int low_exponent = 0;
  std::frexp(low, &low_exponent);
  const int keep_normal = std::numeric_limits<T>::min_exponent - low_exponent;
  if (-e < keep_normal && e + keep_normal <= std::numeric_limits<T>::max_exponent / 2)
    return {keep_normal, false};
  return {-e, -e < keep_normal};
}

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
ObliqueResult<T> finish(const Matrix4<T>& m, const Vector4<T>& plane, const Vector4<T>& q,
                        Convention convention, int k, const Vector4<T>& c_hat) {
  ObliqueResult<T> r = detail::refuse(m, Method::closed_form, Status::ok);
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
  if (detail::dot_lost_to_underflow(d, c_hat, q))  // since issue 23's fix, the core's own test
    return detail::handed_to_accurate(m, plane, convention);
  if (!(d > T(0))) {
    r.status = Status::plane_misses_view_volume;
    return r;
  }
  const DepthRange range = clip_depth_range(convention);
  const T a_hat = T(range.z_high - range.z_low) / d;
  const T a = std::ldexp(a_hat, k);
  const Vector4<T> ac = (std::isfinite(a) && std::abs(a) >= std::numeric_limits<T>::min())
                            ? Vector4<T>(a * plane)
                            : Vector4<T>(a_hat * c_hat);
  const RowCombination near_combination = near_rows(convention);
  const Vector4<T> t_m4 = T(near_combination.m4) * m.row(3).transpose();
  const Vector4<T> row3 = near_combination.m3 > 0 ? Vector4<T>(ac - t_m4) : Vector4<T>(t_m4 - ac);
  return accept_row3(std::move(r), row3, c_hat, convention);
}

template <class T>
ObliqueResult<T> closed_form(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention) {
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  if (A == T(0) || D == T(0) || H == T(0)) {
    return detail::refuse(m, Method::closed_form, Status::singular_projection,
                          "the projection is singular: M11, M22 or M34 is zero");
  }
  if (!(plane.w() < T(0))) {
    return detail::refuse(m, Method::closed_form, Status::camera_not_behind_plane);
  }
  const PlaneScale scale = plane_scale(plane);
  const Vector4<T> c_hat = scaled_by_power_of_two(plane, scale.shift);
  bool lossy = false;
  if (scale.below_normal) {
    for (int i = 0; i < 4; ++i) {
      if (plane(i) != T(0) && !(std::abs(c_hat(i)) >= std::numeric_limits<T>::min()))
        lossy |= std::ldexp(c_hat(i), -scale.shift) != plane(i);
    }
  }
  if (lossy) return detail::handed_to_accurate(m, plane, convention);
  const Vector4<T> corner = detail::clip_corner(
      detail::sign(plane.x()) * detail::sign(A), detail::sign(plane.y()) * detail::sign(D),
      detail::sign(plane.w()) * detail::sign(H), convention);
  const Vector4<T> q((corner.x() - B / K) / A, (corner.y() - E / K) / D, T(1) / K,
                     (corner.z() - G / K) / H);
  return finish(m, plane, q, convention, scale.shift, c_hat);
}

/// apply(projection, plane, convention, method) for method closed_form, and for automatic
/// wherever it chose the closed form (every input but a finite, not too widely spread matrix
/// without the perspective shape, which went to the general method), as it was.
template <class T>
ObliqueResult<T> apply_closed_form(const Matrix4<T>& projection, const Vector4<T>& plane,
                                   Convention convention, Method method) {
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
  if (!has_perspective_shape(projection)) {
    return detail::refuse(projection, Method::closed_form, Status::invalid_input,
                          "closed_form needs the standard perspective shape (zeros outside "
                          "M11, M13, M22, M23, M33, M34, M43; M43 != 0); use auto or general");
  }
  return closed_form(projection, plane, convention);
}

}  // namespace oblique::reference
