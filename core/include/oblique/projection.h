// Projection builders for every depth convention: finite and infinite perspective, orthographic.
// Right-handed camera space: the camera sits at the origin and looks down -z (paper Figure 1).
#pragma once

#include <cassert>
#include <cmath>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"

namespace oblique {

namespace detail {

/// Rows 1, 2 and 4 of glFrustum, shared by finite and infinite perspective (row 3 left zero).
template <class T>
Matrix4<T> perspective_sides(T left, T right, T bottom, T top, T near_distance) {
  Matrix4<T> m = Matrix4<T>::Zero();
  m(0, 0) = T(2) * near_distance / (right - left);
  m(0, 2) = (right + left) / (right - left);
  m(1, 1) = T(2) * near_distance / (top - bottom);
  m(1, 2) = (top + bottom) / (top - bottom);
  m(3, 2) = T(-1);
  return m;
}

}  // namespace detail

/// glFrustum generalised to every convention: the side planes pass through the rectangle
/// [left, right] x [bottom, top] at distance `near_distance`; the far plane is at `far_distance`.
/// gl is the paper's Eq. 11. Preconditions: left != right, bottom != top,
/// 0 < near_distance < far_distance.
template <class T>
Matrix4<T> frustum(T left, T right, T bottom, T top, T near_distance, T far_distance,
                   Convention convention) {
  assert(left != right && bottom != top && near_distance > T(0) && far_distance > near_distance);
  const T n = near_distance, f = far_distance;
  Matrix4<T> m = detail::perspective_sides(left, right, bottom, top, n);
  switch (convention) {
    case Convention::gl:  // z = -n -> -w, z = -f -> w
      m(2, 2) = -(f + n) / (f - n);
      m(2, 3) = T(-2) * f * n / (f - n);
      break;
    case Convention::zero_one:  // z = -n -> 0, z = -f -> w
      m(2, 2) = -f / (f - n);
      m(2, 3) = -f * n / (f - n);
      break;
    case Convention::reversed_z:  // z = -n -> w, z = -f -> 0
      m(2, 2) = n / (f - n);
      m(2, 3) = f * n / (f - n);
      break;
  }
  return m;
}

/// gluPerspective generalised: vertical field of view `fovy_radians`, `aspect` = width / height.
/// Preconditions: 0 < fovy_radians < pi, aspect > 0, 0 < near_distance < far_distance.
template <class T>
Matrix4<T> perspective(T fovy_radians, T aspect, T near_distance, T far_distance,
                       Convention convention) {
  assert(fovy_radians > T(0) && aspect > T(0));
  const T top = near_distance * std::tan(fovy_radians / T(2));
  const T right = top * aspect;
  return frustum(-right, right, -top, top, near_distance, far_distance, convention);
}

/// The limit of frustum() as far_distance -> infinity (Lengyel's M_infinite for gl).
/// Preconditions: left != right, bottom != top, near_distance > 0.
template <class T>
Matrix4<T> infinite_frustum(T left, T right, T bottom, T top, T near_distance,
                            Convention convention) {
  assert(left != right && bottom != top && near_distance > T(0));
  const T n = near_distance;
  Matrix4<T> m = detail::perspective_sides(left, right, bottom, top, n);
  switch (convention) {
    case Convention::gl:
      m(2, 2) = T(-1);
      m(2, 3) = T(-2) * n;
      break;
    case Convention::zero_one:
      m(2, 2) = T(-1);
      m(2, 3) = -n;
      break;
    case Convention::reversed_z:
      m(2, 2) = T(0);
      m(2, 3) = n;
      break;
  }
  return m;
}

/// infinite_frustum() from a vertical field of view and aspect ratio.
template <class T>
Matrix4<T> infinite_perspective(T fovy_radians, T aspect, T near_distance, Convention convention) {
  assert(fovy_radians > T(0) && aspect > T(0));
  const T top = near_distance * std::tan(fovy_radians / T(2));
  const T right = top * aspect;
  return infinite_frustum(-right, right, -top, top, near_distance, convention);
}

/// glOrtho generalised: the box [left, right] x [bottom, top] x [-far_distance, -near_distance].
/// Preconditions: left != right, bottom != top, near_distance != far_distance (near may be <= 0).
template <class T>
Matrix4<T> orthographic(T left, T right, T bottom, T top, T near_distance, T far_distance,
                        Convention convention) {
  assert(left != right && bottom != top && near_distance != far_distance);
  const T n = near_distance, f = far_distance;
  Matrix4<T> m = Matrix4<T>::Zero();
  m(0, 0) = T(2) / (right - left);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 1) = T(2) / (top - bottom);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(3, 3) = T(1);
  switch (convention) {
    case Convention::gl:
      m(2, 2) = T(-2) / (f - n);
      m(2, 3) = -(f + n) / (f - n);
      break;
    case Convention::zero_one:
      m(2, 2) = T(-1) / (f - n);
      m(2, 3) = -n / (f - n);
      break;
    case Convention::reversed_z:
      m(2, 2) = T(1) / (f - n);
      m(2, 3) = f / (f - n);
      break;
  }
  return m;
}

/// True when M has the standard perspective shape the closed form handles:
///   [A 0 B 0]
///   [0 D E 0]
///   [0 0 G H]
///   [0 0 K 0]   with exact zeros elsewhere and K != 0.
/// This covers frustum(), infinite_frustum(), y-flipped (D < 0), jittered (B, E) and
/// left-handed (K > 0) perspective matrices in every convention.
template <class T>
bool has_perspective_shape(const Matrix4<T>& m) {
  return m(0, 1) == T(0) && m(0, 3) == T(0) && m(1, 0) == T(0) && m(1, 3) == T(0) &&
         m(2, 0) == T(0) && m(2, 1) == T(0) && m(3, 0) == T(0) && m(3, 1) == T(0) &&
         m(3, 3) == T(0) && m(3, 2) != T(0);
}

}  // namespace oblique
