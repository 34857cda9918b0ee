// The inputs the code around the matrix gets (consumers.h), built from integer picks: points of
// the kept region, main views, surface planes and the pass cameras of mirrors, clip planes and
// portals. `pick(lo, hi)` returns an integer in [lo, hi): RapidCheck's choices
// (oblique::cases::rc_pick, generators.h) or a fuzz input's bytes
// (oblique::fuzzing::test_consumers).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

#include "oblique/oracle/consumers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"
#include "oblique/util/enum_names.h"

namespace oblique::oracle::consumer_cases {

/// A point of the kept region of (m, c): a weighted mean of one to all of its finite vertices
/// (one vertex: the corner itself; two: a point of an edge, ...), moved along a direction at
/// infinity when the region has one, computed in long double and rounded to T. Rounding may put
/// it just outside (toward_centre() brings it back).
template <class T, class Pick>
Vector4<T> kept_point(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                      Pick&& pick) {
  using Wide = long double;
  const std::vector<Vector4<Wide>> vertices =
      kept_region_vertices<Wide>(m.template cast<Wide>(), c.template cast<Wide>(), convention);
  std::vector<Vector4<Wide>> finite, directions;
  for (const auto& v : vertices) (v.w() != 0 ? finite : directions).push_back(v);
  if (finite.empty()) return Vector4<T>::Zero();
  const int n = static_cast<int>(finite.size());
  {
    const int count = pick(1, n + 1);
    Vector4<Wide> sum = Vector4<Wide>::Zero();
    Wide total = 0;
    for (int k = 0; k < count; ++k) {
      const auto index = static_cast<std::size_t>(pick(0, n));
      const Wide weight = Wide(pick(1, 1001));
      sum += weight * finite[index];
      total += weight;
    }
    Vector4<Wide> p = sum / total;
    if (!directions.empty() && pick(0, 2) == 1) {
      const auto index = static_cast<std::size_t>(pick(0, static_cast<int>(directions.size())));
      const Wide scale = std::ldexp(Wide(1), pick(-4, 20));
      const Vector4<Wide> d = directions[index];
      p += scale * d / d.template head<3>().norm() * p.template head<3>().norm();
    }
    return Vector4<T>(p.template cast<T>());
  }
}

/// `point` moved `fraction` of the way to a centre of the kept region (computed in long double,
/// rounded to T): the mean of its finite vertices, moved along the mean of its directions at
/// infinity where it has some (an infinite frustum's finite vertices all lie on C). What brings a
/// point rounding left just outside the region, or one pushed behind the eye, back to a point
/// that leaves a depth sample.
template <class T>
Vector4<T> toward_centre(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                         const Vector4<T>& point, long double fraction) {
  using Wide = long double;
  const std::vector<Vector4<Wide>> vertices =
      kept_region_vertices<Wide>(m.template cast<Wide>(), c.template cast<Wide>(), convention);
  Vector4<Wide> centre = Vector4<Wide>::Zero(), away = Vector4<Wide>::Zero();
  int n = 0;
  for (const auto& v : vertices) {
    if (v.w() == 0) {
      if (v.template head<3>().norm() > 0) away += v / v.template head<3>().norm();
      continue;
    }
    centre += v;
    ++n;
  }
  if (n == 0) return point;
  centre /= Wide(n);
  if (away.template head<3>().norm() > 0)
    centre +=
        away / away.template head<3>().norm() * std::max(Wide(1), centre.template head<3>().norm());
  const Vector4<Wide> p = point.template cast<Wide>();
  return Vector4<T>((p + fraction * (centre - p)).template cast<T>());
}

/// A render target of a size engines render at: the common screens, a quarter-size buffer,
/// odd and prime sizes, 1 x 1, and the widest and tallest a GPU allows (16384).
template <class Pick>
oracle::Pixel render_target(Pick&& pick) {
  static constexpr int kSizes[][2] = {{1920, 1080}, {1280, 720}, {3840, 2160}, {2560, 1440},
                                      {960, 540},   {1, 1},      {7, 3},       {641, 479},
                                      {1023, 767},  {16384, 9},  {5, 16384},   {2, 2}};
  const auto& size = kSizes[pick(0, static_cast<int>(std::size(kSizes)))];
  oracle::Pixel target;
  target.width = size[0];
  target.height = size[1];
  return target;
}

/// A rotation by angles picked in sixteenths of pi about x, then y, then z.
template <class T, class Pick>
Matrix4<T> rigid_view(Pick&& pick) {
  using Wide = long double;
  const Wide sixteenth = Wide(3.14159265358979323846264338327950288L) / 16;
  Eigen::Matrix<Wide, 3, 3> rotation = Eigen::Matrix<Wide, 3, 3>::Identity();
  for (int axis = 0; axis < 3; ++axis) {
    rotation = rotation * Eigen::AngleAxis<Wide>(sixteenth * Wide(pick(0, 32)),
                                                 Eigen::Matrix<Wide, 3, 1>::Unit(axis))
                              .toRotationMatrix();
  }
  Matrix4<T> r = Matrix4<T>::Identity();
  r.template topLeftCorner<3, 3>() = rotation.template cast<T>();
  for (int i = 0; i < 3; ++i) r(i, 3) = T(pick(-1000, 1001)) / T(16);
  return r;
}

/// A pass camera's view for a world-position consumer: rigid_view()'s rotation and translation,
/// the translation scaled by a power of two up to 128 (a camera up to 8,000 units from the
/// origin, where float world positions have lost digits), and half the time mirrored (times
/// diag(-1, 1, 1, 1): a mirror pass's reflected view, det < 0).
template <class T, class Pick>
Matrix4<T> pass_view(Pick&& pick) {
  Matrix4<T> v = rigid_view<T>(pick);
  const T scale = std::ldexp(T(1), pick(0, 8));
  for (int i = 0; i < 3; ++i) v(i, 3) *= scale;
  if (pick(0, 2)) v.col(0) = -v.col(0);
  return v;
}

/// A world plane through a point within 64 units of the origin, its normal of small integers.
template <class T, class Pick>
Vector4<T> world_plane(Pick&& pick) {
  {
    Eigen::Matrix<T, 3, 1> n;
    do {
      for (int i = 0; i < 3; ++i) n(i) = T(pick(-8, 9));
    } while (n.squaredNorm() == 0);
    Eigen::Matrix<T, 3, 1> p;
    for (int i = 0; i < 3; ++i) p(i) = T(pick(-512, 513)) / T(8);
    return plane_from_normal_and_point<T>(n, p);
  }
}

/// An orthonormal frame (columns right, up, normal, centre) at a point within 64 units.
template <class T, class Pick>
Matrix4<T> portal_frame(Pick&& pick) {
  Matrix4<T> f = rigid_view<T>(pick);
  for (int i = 0; i < 3; ++i) f(i, 3) *= T(1) / T(4);
  return f;
}

/// Three points of `plane` (within 64 units of its point nearest the origin, computed in long
/// double and rounded; the properties project them onto it exactly) and one in front of it.
template <class T, class Pick>
void plane_samples(const Vector4<T>& plane, Pick&& pick, std::vector<Vector4<T>>& surface_points,
                   Vector4<T>& front_point) {
  using Wide = long double;
  const Eigen::Matrix<Wide, 3, 1> n = plane.template head<3>().template cast<Wide>();
  const Wide nn = n.squaredNorm();
  const Eigen::Matrix<Wide, 3, 1> base = -Wide(plane.w()) * n / nn;
  const Eigen::Matrix<Wide, 3, 1> t1 = n.unitOrthogonal(), t2 = n.cross(t1).normalized();
  for (int k = 0; k < 3; ++k) {
    const Wide s = Wide(pick(-64, 65)), t = Wide(pick(-64, 65));
    const Eigen::Matrix<Wide, 3, 1> x = base + s * t1 + t * t2;
    surface_points.push_back(Vector4<T>(T(x(0)), T(x(1)), T(x(2)), T(1)));
  }
  const Eigen::Matrix<Wide, 3, 1> front = base + Wide(pick(1, 65)) * n / std::sqrt(nn);
  front_point = Vector4<T>(T(front(0)), T(front(1)), T(front(2)), T(1));
}

/// The passes whose camera and plane are checked.
enum class PassKind { mirror, clip, portal };

inline constexpr EnumName<PassKind> pass_kind_names[] = {
    {PassKind::mirror, "mirror"}, {PassKind::clip, "clip"}, {PassKind::portal, "portal"}};

constexpr std::string_view pass_kind_name(PassKind kind) noexcept {
  return name_in(pass_kind_names, kind);
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
template <class T, class Pick>
PassPlaneCase<T> pass_plane_case(Pick&& pick) {
  {
    PassPlaneCase<T> out;
    out.kind = static_cast<PassKind>(pick(0, 3));
    out.main_view = rigid_view<T>(pick);
    const Vector4<T> eye = out.main_view.inverse().col(3);
    Vector4<T> plane;
    if (out.kind == PassKind::portal) {
      Matrix4<T> frame = portal_frame<T>(pick);
      const Matrix4<T> linked = portal_frame<T>(pick);
      plane = plane_from_normal_and_point<T>(frame.template block<3, 1>(0, 2),
                                             frame.template block<3, 1>(0, 3));
      if (plane.dot(eye) < 0) {  // the portal turned about its up axis, to face the eye
        frame = frame * Matrix4<T>(Vector4<T>(-1, 1, -1, 1).asDiagonal());
        plane = -plane;
      }
      out.pass_view = portal_view(out.main_view, frame, linked);
      out.kept_plane = portal_kept_plane(portal_map(frame, linked), plane);
    } else {
      plane = world_plane<T>(pick);
      const bool eye_in_front = out.kind == PassKind::mirror;
      if (plane.dot(eye) == T(0)) plane.w() += T(1);
      if ((plane.dot(eye) > 0) != eye_in_front) plane = -plane;
      out.pass_view =
          out.kind == PassKind::mirror ? mirror_view(out.main_view, plane) : out.main_view;
      out.kept_plane = plane;
    }
    plane_samples(out.kept_plane, pick, out.surface_points, out.front_point);
    return out;
  }
}

// Asking the consumer one case and judging its answer, for the cases a round builds and for the
// passes of a scene (`oblique check`): each finding goes to `settle` with the inputs as text,
// a violated one first through `explain` where given (its likely cause).

/// consumers.camera_plane on a pass: plane_on_surface and plane_kept_side.
template <class T>
void ask_camera_plane(const Consumers<T>& consumers, const PassPlaneCase<T>& pass,
                      const oracle::Settle& settle, const oracle::Explain<T>& explain = {});

/// consumers.mirror_view on a main view and a mirror's world plane.
template <class T>
void ask_mirror_view(const Consumers<T>& consumers, const Matrix4<T>& view,
                     const Vector4<T>& mirror, const oracle::Settle& settle,
                     const oracle::Explain<T>& explain = {});

/// consumers.portal_view on a main view and two portals' frames.
template <class T>
void ask_portal_view(const Consumers<T>& consumers, const Matrix4<T>& view, const Matrix4<T>& frame,
                     const Matrix4<T>& linked, const oracle::Settle& settle,
                     const oracle::Explain<T>& explain = {});

}  // namespace oblique::oracle::consumer_cases
