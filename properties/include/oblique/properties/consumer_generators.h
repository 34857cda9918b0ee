// RapidCheck generators of the inputs the code around the matrix gets (consumers.h): points of
// the kept region and the depth they leave in a 24-bit fixed or 32-bit float buffer; main views,
// surface planes and the pass cameras of mirrors, clip planes and portals.
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <vector>

#include "oblique/kept_region.h"
#include "oblique/pass_camera.h"
#include "oblique/properties/consumers.h"
#include "oblique/properties/generators.h"

namespace oblique::generators {

/// A point of the kept region of (m, c): a weighted mean of one to all of its finite vertices
/// (one vertex: the corner itself; two: a point of an edge, ...), moved along a direction at
/// infinity when the region has one, computed in long double and rounded to T. Rounding may put
/// it just outside; the properties judge it where it is.
template <class T>
rc::Gen<Vector4<T>> kept_point(const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
  using Wide = long double;
  const std::vector<Vector4<Wide>> vertices =
      kept_region_vertices<Wide>(m.template cast<Wide>(), c.template cast<Wide>(), convention);
  std::vector<Vector4<Wide>> finite, directions;
  for (const auto& v : vertices) (v.w() != 0 ? finite : directions).push_back(v);
  if (finite.empty()) return rc::gen::just(Vector4<T>(Vector4<T>::Zero()));
  const int n = static_cast<int>(finite.size());
  return rc::gen::exec([=] {
    const int count = *rc::gen::inRange(1, n + 1);
    Vector4<Wide> sum = Vector4<Wide>::Zero();
    Wide total = 0;
    for (int k = 0; k < count; ++k) {
      const auto index = static_cast<std::size_t>(*rc::gen::inRange(0, n));
      const Wide weight = Wide(*rc::gen::inRange(1, 1001));
      sum += weight * finite[index];
      total += weight;
    }
    Vector4<Wide> p = sum / total;
    if (!directions.empty() && *rc::gen::arbitrary<bool>()) {
      const auto index =
          static_cast<std::size_t>(*rc::gen::inRange(0, static_cast<int>(directions.size())));
      const Wide scale = std::ldexp(Wide(1), *rc::gen::inRange(-4, 20));
      const Vector4<Wide> d = directions[index];
      p += scale * d / d.template head<3>().norm() * p.template head<3>().norm();
    }
    return Vector4<T>(p.template cast<T>());
  });
}

/// A rotation by angles picked in sixteenths of pi about x, then y, then z.
template <class T>
rc::Gen<Matrix4<T>> rigid_view() {
  return rc::gen::exec([] {
    Matrix4<T> r = detail::rotation_about<T>(1, 0, 0, *rc::gen::inRange(0, 32)) *
                   detail::rotation_about<T>(0, 1, 0, *rc::gen::inRange(0, 32)) *
                   detail::rotation_about<T>(0, 0, 1, *rc::gen::inRange(0, 32));
    for (int i = 0; i < 3; ++i) r(i, 3) = T(*rc::gen::inRange(-1000, 1001)) / T(16);
    return r;
  });
}

/// A world plane through a point within 64 units of the origin, its normal of small integers.
template <class T>
rc::Gen<Vector4<T>> world_plane() {
  return rc::gen::exec([] {
    Eigen::Matrix<T, 3, 1> n;
    do {
      for (int i = 0; i < 3; ++i) n(i) = T(*rc::gen::inRange(-8, 9));
    } while (n.squaredNorm() == 0);
    Eigen::Matrix<T, 3, 1> p;
    for (int i = 0; i < 3; ++i) p(i) = T(*rc::gen::inRange(-512, 513)) / T(8);
    return plane_from_normal_and_point<T>(n, p);
  });
}

/// An orthonormal frame (columns right, up, normal, centre) at a point within 64 units.
template <class T>
rc::Gen<Matrix4<T>> portal_frame() {
  return rc::gen::map(rigid_view<T>(), [](Matrix4<T> f) {
    for (int i = 0; i < 3; ++i) f(i, 3) *= T(1) / T(4);
    return f;
  });
}

/// The passes whose camera and plane are checked.
enum class PassKind { mirror, clip, portal };

inline const char* pass_kind_name(PassKind kind) {
  return kind == PassKind::mirror ? "mirror" : kind == PassKind::clip ? "clip" : "portal";
}

/// What a pass camera's plane is asked for: the pass's view, the world plane it keeps the front
/// of, three points of it and one in front.
template <class T>
struct PassPlaneCase {
  PassKind kind = PassKind::mirror;
  Matrix4<T> main_view, pass_view;
  Vector4<T> kept_plane;
  std::vector<Vector4<T>> surface_points;
  Vector4<T> front_point;
};

/// A mirror (eye in front), a clip plane (eye behind: the water's refraction pass) or a portal
/// (eye in front of it, the plane the linked portal's front).
template <class T>
rc::Gen<PassPlaneCase<T>> pass_plane_case() {
  return rc::gen::exec([] {
    PassPlaneCase<T> out;
    out.kind = *detail::category({PassKind::mirror, PassKind::clip, PassKind::portal});
    out.main_view = *rigid_view<T>();
    const Vector4<T> eye = out.main_view.inverse().col(3);
    Vector4<T> plane;
    if (out.kind == PassKind::portal) {
      Matrix4<T> frame = *portal_frame<T>();
      const Matrix4<T> linked = *portal_frame<T>();
      plane = plane_from_normal_and_point<T>(frame.template block<3, 1>(0, 2),
                                             frame.template block<3, 1>(0, 3));
      if (plane.dot(eye) < 0) {  // the portal turned about its up axis, to face the eye
        frame = frame * Matrix4<T>(Vector4<T>(-1, 1, -1, 1).asDiagonal());
        plane = -plane;
      }
      out.pass_view = portal_view(out.main_view, frame, linked);
      out.kept_plane = portal_kept_plane(portal_map(frame, linked), plane);
    } else {
      plane = *world_plane<T>();
      const bool eye_in_front = out.kind == PassKind::mirror;
      if (plane.dot(eye) == T(0)) plane.w() += T(1);
      if ((plane.dot(eye) > 0) != eye_in_front) plane = -plane;
      out.pass_view =
          out.kind == PassKind::mirror ? mirror_view(out.main_view, plane) : out.main_view;
      out.kept_plane = plane;
    }
    // Points of the kept plane (computed in long double and rounded; the properties project
    // them onto it exactly) and one in front of it.
    using Wide = long double;
    const Eigen::Matrix<Wide, 3, 1> n = out.kept_plane.template head<3>().template cast<Wide>();
    const Wide nn = n.squaredNorm();
    const Eigen::Matrix<Wide, 3, 1> base = -Wide(out.kept_plane.w()) * n / nn;
    const Eigen::Matrix<Wide, 3, 1> t1 = n.unitOrthogonal(), t2 = n.cross(t1).normalized();
    for (int k = 0; k < 3; ++k) {
      const Wide s = Wide(*rc::gen::inRange(-64, 65)), t = Wide(*rc::gen::inRange(-64, 65));
      const Eigen::Matrix<Wide, 3, 1> x = base + s * t1 + t * t2;
      out.surface_points.push_back(Vector4<T>(T(x(0)), T(x(1)), T(x(2)), T(1)));
    }
    const Eigen::Matrix<Wide, 3, 1> front =
        base + Wide(*rc::gen::inRange(1, 65)) * n / std::sqrt(nn);
    out.front_point = Vector4<T>(T(front(0)), T(front(1)), T(front(2)), T(1));
    return out;
  });
}

}  // namespace oblique::generators
