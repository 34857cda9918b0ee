// Fixed projection matrices, one per family, for the unit tests.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "oblique/projection.h"

namespace oblique::testing {

template <class T>
struct NamedProjection {
  std::string family;
  Matrix4<T> matrix;
  Vector4<T> plane;  ///< a plane with C_w < 0 that cuts the view volume obliquely
};

/// One matrix of every family in `convention`, each with an oblique plane through its volume.
template <class T>
std::vector<NamedProjection<T>> fixed_families(Convention convention) {
  std::vector<NamedProjection<T>> out;
  const Vector4<T> tilted(T(0.25), T(-0.375), T(-1), T(-3));  // z = -3 tilted, camera behind
  out.push_back({"perspective",
                 perspective<T>(T(1.0471975511965976), T(1.75), T(0.5), T(400), convention),
                 tilted});
  out.push_back(
      {"off_axis", frustum<T>(T(-0.1), T(0.7), T(-0.2), T(0.3), T(1), T(100), convention), tilted});
  out.push_back({"infinite", infinite_perspective<T>(T(1.2), T(1.5), T(0.1), convention), tilted});
  Matrix4<T> flipped = frustum<T>(T(-1), T(1), T(-0.75), T(0.75), T(1), T(50), convention);
  flipped.row(1) *= T(-1);  // Vulkan's y-down clip space
  out.push_back({"y_flipped", flipped, tilted});
  Matrix4<T> jittered = frustum<T>(T(-1), T(1), T(-0.75), T(0.75), T(1), T(50), convention);
  jittered(0, 2) += T(0.3) / T(1920);  // a sub-pixel offset in NDC x, as TAA does: M_1 += j M_4
  jittered(1, 2) -= T(0.7) / T(1080);
  out.push_back({"jittered", jittered, tilted});
  // A mirror camera: clip x negated (M11 < 0), alone and on a y-flipped projection.
  Matrix4<T> mirrored = frustum<T>(T(-1), T(1), T(-0.75), T(0.75), T(1), T(50), convention);
  mirrored.row(0) *= T(-1);
  out.push_back({"x_flipped", mirrored, tilted});
  mirrored.row(1) *= T(-1);
  out.push_back({"xy_flipped", mirrored, tilted});
  // A left-handed camera looking down +z (M43 = +1), off-axis; the plane mirrored in z with it.
  Matrix4<T> left_handed = frustum<T>(T(-0.1), T(0.7), T(-0.2), T(0.3), T(1), T(100), convention);
  left_handed.col(2) *= T(-1);
  out.push_back({"left_handed", left_handed, Vector4<T>(T(0.25), T(-0.375), T(1), T(-3))});
  const Matrix4<T> p = frustum<T>(T(-1), T(1), T(-0.75), T(0.75), T(1), T(50), convention);
  Matrix4<T> r = Matrix4<T>::Identity();
  r.template topLeftCorner<3, 3>() =
      Eigen::AngleAxis<T>(T(0.3), Eigen::Matrix<T, 3, 1>(T(1), T(2), T(2)).normalized())
          .toRotationMatrix();
  out.push_back({"rotated", Matrix4<T>(p * r), Vector4<T>(T(0.1), T(-0.2), T(-1), T(-4))});
  out.push_back({"orthographic", orthographic<T>(T(-4), T(5), T(-3), T(2), T(1), T(20), convention),
                 Vector4<T>(T(0.125), T(0.25), T(-1), T(-6))});
  Matrix4<T> general;
  general << T(1.25), T(0.125), T(0.25), T(0.5), T(-0.25), T(1.5), T(0.125), T(-0.25), T(0.0625),
      T(-0.125), T(-1.125), T(-2.5), T(0.03125), T(0.0625), T(-1), T(0.25);
  out.push_back({"general", general, Vector4<T>(T(0.05), T(0.1), T(-1), T(-0.75))});
  return out;
}

}  // namespace oblique::testing
