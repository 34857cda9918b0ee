// The camera of an oblique pass and its clip plane in that camera's space (the references of
// `oblique::testing`'s pass-camera properties, and what `oblique check` builds its passes from):
//
//   mirror:  view' = view R(P), R the reflection through the world plane P (det R = -1: the
//            pass flips the winding of every triangle, so front faces become back faces);
//   portal:  view' = view T, T = frame turn linked^-1 (world -> world: what is in front of the
//            linked portal is seen behind this one);
//   clip:    view' = view;
//   plane:   C = view'^-T P_kept (planes go by the inverse transpose), P_kept the world plane
//            whose positive side the pass draws: the mirror's or clip plane's front, or the
//            linked portal's front (T^T (-P) for this portal's plane P).
//
// A camera that sees the surface's front (the eye on its positive side) has the pass camera on
// C's negative side: C_w < 0, as the oblique modification requires.
#pragma once

#include <cmath>

#include "oblique/plane.h"

namespace oblique {

/// The plane, in the space `to_camera` maps world points into: to_camera^-T plane. A world point
/// x lies on the world plane exactly when to_camera x lies on the result, on the same side.
template <class T>
Vector4<T> plane_in_camera(const Matrix4<T>& to_camera, const Vector4<T>& world_plane) {
  return to_camera.inverse().transpose() * world_plane;
}

/// The reflection through a world plane (n, d): x -> x - 2 (n . x + d) n / |n|^2 (the plane's
/// scale does not matter; it is scaled by a power of two first, exactly, so |n|^2 is in range).
template <class T>
Matrix4<T> reflection(const Vector4<T>& plane_in) {
  using std::ilogb;
  using std::isfinite;
  using std::ldexp;
  const T largest = plane_in.template head<3>().cwiseAbs().maxCoeff();
  const Vector4<T> plane = largest > 0 && isfinite(largest)
                               ? Vector4<T>(ldexp(T(1), -ilogb(largest)) * plane_in)
                               : plane_in;
  const Eigen::Matrix<T, 3, 1> n = plane.template head<3>();
  const T nn = n.squaredNorm();
  Matrix4<T> r = Matrix4<T>::Identity();
  r.template block<3, 3>(0, 0) -= T(2) * n * n.transpose() / nn;
  r.template block<3, 1>(0, 3) = T(-2) * plane.w() * n / nn;
  return r;
}

/// A mirror pass's view: world -> the reflected camera.
template <class T>
Matrix4<T> mirror_view(const Matrix4<T>& view, const Vector4<T>& world_plane) {
  return view * reflection(world_plane);
}

/// The world -> world map of a portal at `frame` linked to `linked` (frames: columns right, up,
/// normal, center, orthonormal): a point in front of the linked portal goes to where it is seen
/// behind this one (x and z turned around: a half turn about up).
template <class T>
Matrix4<T> portal_map(const Matrix4<T>& frame, const Matrix4<T>& linked) {
  const Matrix4<T> turn = Vector4<T>(-1, 1, -1, 1).asDiagonal();
  return frame * turn * linked.inverse();
}

/// A portal pass's view: world (around the linked portal) -> the camera seeing it through this
/// portal.
template <class T>
Matrix4<T> portal_view(const Matrix4<T>& view, const Matrix4<T>& frame, const Matrix4<T>& linked) {
  return view * portal_map(frame, linked);
}

/// The world plane a portal pass keeps: the front of the linked portal, as `portal_map` carries
/// this portal's plane (its front turned around).
template <class T>
Vector4<T> portal_kept_plane(const Matrix4<T>& portal_transform, const Vector4<T>& world_plane) {
  return portal_transform.transpose() * (-world_plane);
}

}  // namespace oblique
