// Planes and matrices on Eigen types. Column-vector convention: clip = M * p.
// (Magnitudes and finiteness: magnitudes.h; the core's scaling of a plane: plane_scaling.h.)
#pragma once

#include <Eigen/Core>

#include "oblique/numeric/magnitudes.h"

namespace oblique {

template <class T>
using Matrix4 = Eigen::Matrix<T, 4, 4>;

/// A homogeneous point (w = 1), direction (w = 0), or plane <N, -N.P>; a plane keeps the points
/// p with plane.dot(p) >= 0 (paper Eq. 1).
template <class T>
using Vector4 = Eigen::Matrix<T, 4, 1>;

/// The plane through `point` whose positive (kept) side is the one `normal` points to.
template <class T>
Vector4<T> plane_from_normal_and_point(const Eigen::Matrix<T, 3, 1>& normal,
                                       const Eigen::Matrix<T, 3, 1>& point) {
  Vector4<T> plane;
  plane << normal, -normal.dot(point);
  return plane;
}

}  // namespace oblique
