// The code around the oblique matrix as engines write it, right and wrong: depth reconstruction,
// culling planes, the pass camera and its plane, the view volume's corners. The right ones pass
// oblique::testing::check_consumers(); each wrong one is a mistake found in engines' trackers
// (docs/consumers.md) and is caught by the property named beside it.
#pragma once

#include <oblique/oracle/consumers.h>
#include <oblique/references/kept_region.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <vector>

namespace engine_consumers {

using oblique::Convention;
using oblique::Matrix4;
using oblique::Vector3;
using oblique::Vector4;

// ---- right ----

/// The pixel's camera-space point: the inverse of the matrix the depth was rendered with.
template <class T>
Vector3<T> view_position(const oblique::oracle::DepthSample<T>& s) {
  const T z = s.convention == Convention::gl ? T(2) * s.depth - T(1) : s.depth;
  const Vector4<T> v = s.projection.inverse() * Vector4<T>(s.ndc_x, s.ndc_y, z, T(1));
  return v.template head<3>() / v.w();
}

/// Its distance along the view axis (the camera looks down -z unless the projection is
/// left-handed).
template <class T>
T linear_depth(const oblique::oracle::DepthSample<T>& s) {
  const int axis = oblique::view_axis_sign(s.original, s.convention);
  return T(axis) * view_position(s).z();
}

/// The pixel's world point: its view position carried back by the inverse of the pass camera's
/// view (camera to world). (Inverting the view-projection M' V in float instead loses every digit
/// a few thousand units from the origin.)
template <class T>
Vector3<T> world_position(const oblique::oracle::DepthSample<T>& s) {
  const Vector3<T> v = view_position(s);
  return (s.view.inverse() * Vector4<T>(v.x(), v.y(), v.z(), T(1))).template head<3>();
}

/// Gribb-Hartmann, with the depth rows of the matrix's own convention.
template <class T>
oblique::FrustumPlanes<T> culling_planes(const Matrix4<T>& m, Convention convention) {
  return oblique::frustum_planes(m, convention);
}

/// The world plane through the pass camera's view: the inverse transpose.
template <class T>
Vector4<T> camera_plane(const Matrix4<T>& pass_view, const Vector4<T>& world_plane) {
  return pass_view.inverse().transpose() * world_plane;
}

/// The main view times the reflection through the mirror's plane.
template <class T>
Matrix4<T> mirror_view(const Matrix4<T>& view, const Vector4<T>& plane) {
  const Vector3<T> n = plane.template head<3>();
  const T nn = n.squaredNorm();
  Matrix4<T> r = Matrix4<T>::Identity();
  r.template topLeftCorner<3, 3>() -= T(2) * n * n.transpose() / nn;
  r.template topRightCorner<3, 1>() = T(-2) * plane.w() * n / nn;
  return view * r;
}

/// The main view times this portal's frame, a half turn about up, and the linked frame's inverse
/// (a rigid inverse: transpose and translate).
template <class T>
Matrix4<T> portal_view(const Matrix4<T>& view, const Matrix4<T>& frame, const Matrix4<T>& linked) {
  Matrix4<T> linked_inverse = Matrix4<T>::Identity();
  linked_inverse.template topLeftCorner<3, 3>() = linked.template topLeftCorner<3, 3>().transpose();
  linked_inverse.template topRightCorner<3, 1>() =
      -linked_inverse.template topLeftCorner<3, 3>() * linked.template topRightCorner<3, 1>();
  const Matrix4<T> turn = Vector4<T>(-1, 1, -1, 1).asDiagonal();
  return view * frame * turn * linked_inverse;
}

/// The kept region's vertices: the original volume on the near plane's kept side (the oblique
/// volume's own eight corners do not bound it where some lie behind the eye).
template <class T>
std::vector<Vector3<T>> corners(const Matrix4<T>& m, const Matrix4<T>& original,
                                Convention convention) {
  std::vector<Vector3<T>> out;
  for (const Vector4<T>& v :
       oblique::kept_region_vertices(original, oblique::near_plane(m, convention), convention))
    out.push_back(v.template head<3>());
  return out;
}

// ---- wrong ----

/// view_position: the depth decompressed with the camera's unmodified matrix (Unity
/// Graphics#3919, three.js#21403, ioq3#641). Caught by view_position.
template <class T>
Vector3<T> reconstructs_with_original(const oblique::oracle::DepthSample<T>& s) {
  oblique::oracle::DepthSample<T> wrong = s;
  wrong.projection = s.original;
  return view_position(wrong);
}

/// world_position: the inverse view-projection the camera keeps for its main view, M V, on a
/// depth the pass wrote through M' V. Caught by world_position.
template <class T>
Vector3<T> world_with_original(const oblique::oracle::DepthSample<T>& s) {
  oblique::oracle::DepthSample<T> wrong = s;
  wrong.projection = s.original;
  return world_position(wrong);
}

/// linear_depth: the textbook n f / (f - d (f - n)) with n and f read off the unmodified
/// perspective matrix in its convention (right-handed; reversed depth turned forward, as
/// _ZBufferParams do). Caught by linear_depth.
template <class T>
T linearises_with_near_far(const oblique::oracle::DepthSample<T>& s) {
  // As _ZBufferParams hold it: 1 / n and 1 / f, so that an infinite far plane gives 1 / f = 0.
  const T a = s.original(2, 2), b = s.original(2, 3);
  T near_inverse = a / b, far_inverse = (a + T(1)) / b, d = s.depth;  // [0, 1] depth
  if (s.convention == Convention::gl) {
    near_inverse = (a - T(1)) / b;
  } else if (s.convention == Convention::reversed_z) {
    near_inverse = (a + T(1)) / b;
    far_inverse = a / b;
    d = T(1) - d;  // _ZBufferParams turn reversed depth forward
  }
  return T(1) / ((far_inverse - near_inverse) * d + near_inverse);
}

/// culling_planes: OpenGL's rows on a [0, 1] matrix (near = M_4 + M_3). Caught by
/// culling_near_is_c.
template <class T>
oblique::FrustumPlanes<T> gl_planes_on_any_matrix(const Matrix4<T>& m, Convention) {
  return oblique::frustum_planes(m, Convention::gl);
}

/// culling_planes: the planes of the transposed matrix (a row-major array read as column-major).
/// Caught by culling_keeps_visible.
template <class T>
oblique::FrustumPlanes<T> planes_of_transpose(const Matrix4<T>& m, Convention convention) {
  return oblique::frustum_planes(Matrix4<T>(m.transpose()), convention);
}

/// camera_plane: the normal rotated into camera space, the distance kept from world space
/// (three.js#16013, drei#721). Caught by plane_on_surface.
template <class T>
Vector4<T> plane_without_translation(const Matrix4<T>& pass_view, const Vector4<T>& world_plane) {
  const oblique::Vector3<T> normal =
      pass_view.template topLeftCorner<3, 3>() * world_plane.template head<3>();
  return Vector4<T>(normal.x(), normal.y(), normal.z(), world_plane.w());
}

/// camera_plane: flipped again where the pass view mirrors ("the reflection turns the plane
/// around"; it already has, through the inverse transpose). Caught by plane_kept_side.
template <class T>
Vector4<T> plane_flipped_for_mirrors(const Matrix4<T>& pass_view, const Vector4<T>& world_plane) {
  const Vector4<T> plane = camera_plane(pass_view, world_plane);
  return pass_view.template topLeftCorner<3, 3>().determinant() < 0 ? Vector4<T>(-plane) : plane;
}

/// mirror_view: the eye, target and up reflected, and a look-at view of them: a proper rotation
/// that does not mirror the image (the winding is not flipped either). Caught by mirror_view.
template <class T>
Matrix4<T> mirror_by_reflected_look_at(const Matrix4<T>& view, const Vector4<T>& plane) {
  const Matrix4<T> to_world = view.inverse();
  const Vector3<T> n = plane.template head<3>() / plane.template head<3>().norm();
  const T d = plane.w() / plane.template head<3>().norm();
  auto reflect_point = [&](const Vector3<T>& p) -> Vector3<T> {
    return p - T(2) * (n.dot(p) + d) * n;
  };
  auto reflect_direction = [&](const Vector3<T>& v) -> Vector3<T> {
    return v - T(2) * n.dot(v) * n;
  };
  const Vector3<T> eye = reflect_point(to_world.template topRightCorner<3, 1>());
  const Vector3<T> forward = reflect_direction(-to_world.template block<3, 1>(0, 2)).normalized();
  const Vector3<T> up = reflect_direction(to_world.template block<3, 1>(0, 1));
  const Vector3<T> side = forward.cross(up).normalized();
  const Vector3<T> true_up = side.cross(forward);
  Matrix4<T> out = Matrix4<T>::Identity();
  out.template block<1, 3>(0, 0) = side.transpose();
  out.template block<1, 3>(1, 0) = true_up.transpose();
  out.template block<1, 3>(2, 0) = -forward.transpose();
  out(0, 3) = -side.dot(eye);
  out(1, 3) = -true_up.dot(eye);
  out(2, 3) = forward.dot(eye);
  return out;
}

/// portal_view: without the half turn (what is in front of the linked portal is then seen in
/// front of this one, mirrored through the wall). Caught by portal_view.
template <class T>
Matrix4<T> portal_without_turn(const Matrix4<T>& view, const Matrix4<T>& frame,
                               const Matrix4<T>& linked) {
  return view * frame * linked.inverse();
}

/// corners: the oblique matrix's eight corners, M'^-1 (+-1, +-1, z, 1) divided by w, as for an
/// ordinary camera (cascade fitting from the oblique camera: Godot #89140, Ogre #1337). Where C
/// cuts an edge of the volume behind the eye, a corner lands behind the camera and their hull
/// misses part of the kept region. Caught by corners_contain_kept.
template <class T>
std::vector<Vector3<T>> corners_of_oblique_matrix(const Matrix4<T>& m, const Matrix4<T>&,
                                                  Convention convention) {
  std::vector<Vector3<T>> out;
  for (const Vector4<T>& v : oblique::view_volume_corners(m, convention))
    out.push_back(v.template head<3>() / v.w());
  return out;
}

}  // namespace engine_consumers
