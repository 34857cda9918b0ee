// The six camera-space planes of any projection matrix, as sums and differences of its rows
// (Gribb-Hartmann; paper Table 1 for gl). Each plane keeps the points p with plane.dot(p) >= 0.
#pragma once

#include "oblique/depth_convention.h"
#include "oblique/plane.h"

namespace oblique {

template <class T>
struct FrustumPlanes {
  Vector4<T> left, right, bottom, top, near_plane, far_plane;
};

/// rows.m3 * M_3 + rows.m4 * M_4 as a column vector.
template <class T>
Vector4<T> combine_rows(const Matrix4<T>& m, RowCombination rows) {
  return (T(rows.m3) * m.row(2) + T(rows.m4) * m.row(3)).transpose();
}

/// The near plane: M_4 + M_3 (gl), M_3 (zero_one), M_4 - M_3 (reversed_z).
template <class T>
Vector4<T> near_plane(const Matrix4<T>& m, Convention convention) {
  return combine_rows(m, near_rows(convention));
}

/// The far plane: M_4 - M_3 (gl, zero_one), M_3 (reversed_z).
template <class T>
Vector4<T> far_plane(const Matrix4<T>& m, Convention convention) {
  return combine_rows(m, far_rows(convention));
}

template <class T>
FrustumPlanes<T> frustum_planes(const Matrix4<T>& m, Convention convention) {
  FrustumPlanes<T> planes;
  planes.left = (m.row(3) + m.row(0)).transpose();
  planes.right = (m.row(3) - m.row(0)).transpose();
  planes.bottom = (m.row(3) + m.row(1)).transpose();
  planes.top = (m.row(3) - m.row(1)).transpose();
  planes.near_plane = near_plane(m, convention);
  planes.far_plane = far_plane(m, convention);
  return planes;
}

}  // namespace oblique
