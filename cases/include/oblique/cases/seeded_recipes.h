// The formulas as printed in the source documents (shared/seeds), transcribed faithfully so the
// properties can judge them. None of them returns a status; they are not for production use.
#pragma once

#include <Eigen/LU>

#include "oblique/plane.h"

namespace oblique::cases {

template <class T>
T sgn(T x) {
  return x > T(0) ? T(1) : (x < T(0) ? T(-1) : T(0));
}

/// Lengyel's book, Listing 5.1 (gl perspective fast path): the corner signs are taken from the
/// camera-space C, and M_4 = (0, 0, -1, 0) is assumed.
template <class T>
Matrix4<T> listing_5_1(Matrix4<T> m, const Vector4<T>& c) {
  Vector4<T> q;
  q.x() = (sgn(c.x()) + m(0, 2)) / m(0, 0);
  q.y() = (sgn(c.y()) + m(1, 2)) / m(1, 1);
  q.z() = T(-1);
  q.w() = (T(1) + m(2, 2)) / m(2, 3);
  const Vector4<T> scaled = c * (T(2) / c.dot(q));
  m(2, 0) = scaled.x();
  m(2, 1) = scaled.y();
  m(2, 2) = scaled.z() + T(1);
  m(2, 3) = scaled.w();
  return m;
}

/// Q = M^-1 Q' with the paper's Eq. 7, Q' = (sgn C'_x, sgn C'_y, 1, 1), C' = M^-T C (explicit
/// inverse).
template <class T>
Vector4<T> corner_by_eq_7(const Matrix4<T>& m, const Vector4<T>& c) {
  const Matrix4<T> inverse = m.inverse();
  const Vector4<T> c_clip = inverse.transpose() * c;
  return inverse * Vector4<T>(sgn(c_clip.x()), sgn(c_clip.y()), T(1), T(1));
}

/// The paper's Eq. 20 with Q' from Eq. 7 (z fixed at 1) and Q = M^-1 Q' (gl).
template <class T>
Matrix4<T> paper_eq_20(Matrix4<T> m, const Vector4<T>& c) {
  const Vector4<T> q = corner_by_eq_7(m, c);
  const Vector4<T> m4 = m.row(3).transpose();
  const T a = T(2) * m4.dot(q) / c.dot(q);
  m.row(2) = (a * c - m4).transpose();
  return m;
}

/// The [0, 1]-depth note's TL;DR: M_3 = (M_4 . Q) / (C . Q) C with Q = M^-1 (sgn C'_x, sgn C'_y, 1,
/// 1).
template <class T>
Matrix4<T> note_zero_one(Matrix4<T> m, const Vector4<T>& c) {
  const Vector4<T> q = corner_by_eq_7(m, c);
  const Vector4<T> m4 = m.row(3).transpose();
  m.row(2) = (m4.dot(q) / c.dot(q) * c).transpose();
  return m;
}

/// The note's Z-flip matrix for reversed Z, as printed (its fourth row is (0, 0, 1, 1)).
template <class T>
Matrix4<T> note_flip_as_printed() {
  Matrix4<T> f;
  f << 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 1, 0, 0, 1, 1;
  return f;
}

/// The flip that maps [0, 1] depth to reversed [0, 1] depth and leaves w alone: z' = w - z.
template <class T>
Matrix4<T> depth_flip() {
  Matrix4<T> f;
  f << 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 1, 0, 0, 0, 1;
  return f;
}

/// The note's reversed-Z route: oblique on the [0, 1] matrix, then flip. `forward` is the
/// (non-reversed) [0, 1] matrix; the result is meant as the oblique form of flip * forward.
template <class T>
Matrix4<T> note_reversed(const Matrix4<T>& forward, const Vector4<T>& c, const Matrix4<T>& flip) {
  return flip * note_zero_one(forward, c);
}

}  // namespace oblique::cases
