// The kept region of an oblique pass and the corners of a view volume (the references of
// `oblique::testing`'s corner properties: what cascade fitting, light lists and bounding volumes
// start from).
//
// The kept region is what the pass must draw: the original view volume of M on C's positive
// side, the polytope {x : P . x >= 0} of M's six planes and C. Its vertices are the points where
// three of the planes meet and no plane is violated (at infinity, as directions with w = 0, when M
// is infinite).
//
// The eight corners M^-1 (+-1, +-1, z, 1) of a view volume bound it only when all eight lie in
// front of the eye (w > 0 before the divide). An oblique M' often has corners behind the eye or at
// infinity (C cuts an edge of the original volume behind the camera, or parallel to it): their
// convex hull then misses part of what M' draws, and the kept region's own vertices are the
// answer.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/frustum_planes.h"
#include "oblique/plane.h"

namespace oblique {

/// The corners of M's view volume, homogeneous (M^-1 (x, y, z, 1) not divided by w), in the
/// order x, then y, then z from low to high: index 4 z_index + 2 y_index + x_index (z_index 0 is
/// z_low, -1 for gl and 0 otherwise, which is the far face for reversed_z).
template <class T>
std::array<Vector4<T>, 8> view_volume_corners(const Matrix4<T>& m, Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const auto lu = m.partialPivLu();
  std::array<Vector4<T>, 8> out;
  for (int i = 0; i < 8; ++i) {
    const Vector4<T> clip(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? range.z_high : range.z_low, 1);
    out[static_cast<std::size_t>(i)] = lu.solve(clip);
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

/// The point where planes a, b and c meet, homogeneous (zero when they meet in a line or not
/// at all): the cofactors of the 3 x 4 matrix of the planes.
template <class S>
Vec<S> meet(const Vec<S>& a, const Vec<S>& b, const Vec<S>& c) {
  auto minor = [&](int i, int j, int k) -> S {
    return a[i] * (b[j] * c[k] - b[k] * c[j]) - a[j] * (b[i] * c[k] - b[k] * c[i]) +
           a[k] * (b[i] * c[j] - b[j] * c[i]);
  };
  return {minor(1, 2, 3), -minor(0, 2, 3), minor(0, 1, 3), -minor(0, 1, 2)};
}

/// The vertices of {x : P . x >= 0 for every P of `planes`}: points with w = 1, directions at
/// infinity with w = 0. A candidate counts as on the kept side of P where P . x >= -slack |P| . |x|
/// (slack 0 in exact arithmetic; a few epsilon in floating point, where a vertex on four or more
/// planes rounds to either side). A vertex where more than three planes meet appears once per
/// triple of them.
template <class S>
std::vector<Vec<S>> vertices(const std::vector<Vec<S>>& planes, const S& slack) {
  auto magnitude = [](const S& x) { return x < 0 ? S(-x) : x; };
  auto kept = [&](const Vec<S>& x) {
    for (const Vec<S>& p : planes) {
      S scale = 0;
      for (int i = 0; i < 4; ++i) scale += magnitude(p[i]) * magnitude(x[i]);
      if (dot(p, x) < -slack * scale) return false;
    }
    return true;
  };
  std::vector<Vec<S>> out;
  const std::size_t n = planes.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Vec<S> x = meet(planes[i], planes[j], planes[k]);
        if (x[3] != 0) {
          const S w = x[3];
          for (S& v : x) v = v / w;
          if (kept(x)) out.push_back(x);
        } else if (x[0] != 0 || x[1] != 0 || x[2] != 0) {
          if (kept(x)) {
            out.push_back(x);
          } else {
            for (S& v : x) v = -v;
            if (kept(x)) out.push_back(x);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace polytope

/// The six planes of M's view volume and C, as polytope::vertices() takes them.
template <class T>
std::vector<polytope::Vec<T>> kept_region_planes(const Matrix4<T>& m, const Vector4<T>& c,
                                                 Convention convention) {
  const FrustumPlanes<T> f = frustum_planes(m, convention);
  std::vector<polytope::Vec<T>> out;
  for (const Vector4<T>& p : {f.left, f.right, f.bottom, f.top, f.near_plane, f.far_plane, c})
    out.push_back({p(0), p(1), p(2), p(3)});
  return out;
}

/// The vertices of the kept region of (M, C) in camera space (w = 1; w = 0 for directions of an
/// infinite M), computed in T with a slack of 64 epsilon.
template <class T>
std::vector<Vector4<T>> kept_region_vertices(const Matrix4<T>& m, const Vector4<T>& c,
                                             Convention convention) {
  std::vector<Vector4<T>> out;
  for (const auto& v : polytope::vertices(kept_region_planes(m, c, convention),
                                          T(64) * std::numeric_limits<T>::epsilon()))
    out.emplace_back(v[0], v[1], v[2], v[3]);
  return out;
}

}  // namespace oblique
