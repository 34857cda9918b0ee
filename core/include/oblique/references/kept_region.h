// The kept region of an oblique pass and the corners of a view volume (the references of
// `oblique::testing`'s corner properties: what cascade fitting, light lists and bounding volumes
// start from).
//
// The kept region is what the pass must draw: the original view volume of M on C's positive
// side. Its vertices are M's corners on that side and the points where C crosses the volume's
// edges (at infinity, as directions with w = 0, when M is infinite).
//
// The eight corners M^-1 (+-1, +-1, z, 1) of a view volume bound it only when all eight lie in
// front of the eye (w > 0 before the divide). An oblique M' often has corners behind the eye or at
// infinity (C cuts an edge of the original volume behind the camera, or parallel to it): their
// convex hull then misses part of what M' draws, and the kept region's own vertices are the
// answer.
#pragma once

#include <Eigen/LU>
#include <array>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"

namespace oblique {

/// The clip-space corner i (0..7) of the view volume at w = 1: x = -1 or 1 (bit 0), y (bit 1),
/// z = z_low or z_high (bit 2).
inline std::array<int, 4> clip_corner(int i, Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  return {i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? range.z_high : range.z_low, 1};
}

/// The corners of M's view volume, homogeneous (M^-1 (x, y, z, 1) not divided by w), in the
/// order x, then y, then z from low to high: index 4 z_index + 2 y_index + x_index (z_index 0 is
/// z_low, -1 for gl and 0 otherwise, which is the far face for reversed_z).
template <class T>
std::array<Vector4<T>, 8> view_volume_corners(const Matrix4<T>& m, Convention convention) {
  const auto lu = m.partialPivLu();
  std::array<Vector4<T>, 8> out;
  for (int i = 0; i < 8; ++i) {
    const std::array<int, 4> q = clip_corner(i, convention);
    out[static_cast<std::size_t>(i)] = lu.solve(Vector4<T>(T(q[0]), T(q[1]), T(q[2]), T(q[3])));
  }
  return out;
}

namespace polytope {

template <class S>
using Vec = std::array<S, 4>;

template <class S>
S dot(const Vec<S>& a, const Vec<S>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/// The vertices of a view volume (its eight corners, homogeneous, indexed as
/// view_volume_corners() gives them, in front of the eye: w >= 0) on the positive side of the
/// plane c: the corners with c . x >= 0, and where an edge (corners whose indices differ in one
/// bit) crosses c, the crossing (c . a) b - (c . b) a, positive in both. Finite vertices are
/// divided to w = 1; directions at infinity keep w = 0. Written once for any scalar with
/// + - * / and comparisons: the core's T, the checker's rationals.
template <class S>
std::vector<Vec<S>> clip_volume(const std::array<Vec<S>, 8>& corners, const Vec<S>& c) {
  std::array<S, 8> side;
  for (std::size_t i = 0; i < 8; ++i) side[i] = dot(c, corners[i]);
  std::vector<Vec<S>> out;
  auto add = [&out](Vec<S> x) {
    if (x[3] != 0) {
      const S w = x[3];
      for (S& v : x) v = v / w;
    }
    out.push_back(x);
  };
  for (std::size_t i = 0; i < 8; ++i) {
    if (!(side[i] < 0)) add(corners[i]);
  }
  for (std::size_t i = 0; i < 8; ++i) {
    for (std::size_t bit = 1; bit < 8; bit <<= 1) {
      const std::size_t j = i | bit;
      if (j == i) continue;
      const bool crosses = (side[i] > 0 && side[j] < 0) || (side[i] < 0 && side[j] > 0);
      if (!crosses) continue;
      const std::size_t in = side[i] > 0 ? i : j, out_index = side[i] > 0 ? j : i;
      Vec<S> x;
      for (std::size_t k = 0; k < 4; ++k)
        x[k] = side[in] * corners[out_index][k] - side[out_index] * corners[in][k];
      add(x);
    }
  }
  return out;
}

}  // namespace polytope

/// The vertices of the kept region of (M, C) in camera space: points with w = 1, directions at
/// infinity (an infinite M) with w = 0. Computed in T from M's corners; a corner within rounding
/// of C may be kept or replaced by the crossings next to it, which lie within rounding of it.
template <class T>
std::vector<Vector4<T>> kept_region_vertices(const Matrix4<T>& m, const Vector4<T>& c,
                                             Convention convention) {
  std::array<polytope::Vec<T>, 8> corners;
  const std::array<Vector4<T>, 8> homogeneous = view_volume_corners(m, convention);
  for (std::size_t i = 0; i < 8; ++i) {
    const T sign = homogeneous[i].w() < 0 ? T(-1) : T(1);
    for (int k = 0; k < 4; ++k) corners[i][static_cast<std::size_t>(k)] = sign * homogeneous[i](k);
  }
  std::vector<Vector4<T>> out;
  for (const auto& v : polytope::clip_volume(corners, {c(0), c(1), c(2), c(3)}))
    out.emplace_back(v[0], v[1], v[2], v[3]);
  return out;
}

}  // namespace oblique
