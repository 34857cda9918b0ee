// The reference scene of a case (a floor, pillars, markers where two matrices disagree): geometry
// only, in double, made in the frame of M's view (its axis, its screen's right and up).
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>

#include "oblique/raster/case_scene.h"

namespace oblique::raster {

namespace {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;

/// NDC z of the near and far faces of `convention`.
double near_z(Convention convention) {
  return convention == Convention::gl ? -1 : convention == Convention::zero_one ? 0 : 1;
}
double far_z(Convention convention) {
  return convention == Convention::reversed_z ? 0 : 1;
}

/// The eye-space point (w = 1) an NDC point comes from, or none (at infinity, or behind).
std::optional<Vec3> from_ndc(const Eigen::Matrix4d& inverse, double x, double y, double z) {
  const Vec4 v = inverse * Vec4(x, y, z, 1);
  if (!(v.w() > 0) || !v.allFinite()) return std::nullopt;
  const Vec3 p = v.head<3>() / v.w();
  if (!p.allFinite()) return std::nullopt;
  return p;
}

/// NDC z of an eye-space point through M (NaN when w <= 0).
double ndc_z(const Eigen::Matrix4d& m, const Vec3& p) {
  const Vec4 q = m * p.homogeneous();
  return q.w() > 0 ? q.z() / q.w() : std::numeric_limits<double>::quiet_NaN();
}

Eigen::Vector4f rgba(double r, double g, double b, double a = 1) {
  return Eigen::Vector4f(static_cast<float>(r), static_cast<float>(g), static_cast<float>(b),
                         static_cast<float>(a));
}

/// A colour of hue h in [0, 1), brightness `light`.
Eigen::Vector4f hue(double h, double light) {
  const double r = 0.5 + 0.5 * std::cos(2 * M_PI * h);
  const double g = 0.5 + 0.5 * std::cos(2 * M_PI * (h - 1.0 / 3));
  const double b = 0.5 + 0.5 * std::cos(2 * M_PI * (h - 2.0 / 3));
  return rgba(light * (0.25 + 0.75 * r), light * (0.25 + 0.75 * g), light * (0.25 + 0.75 * b));
}

void triangle(std::vector<Eigen::Vector4f>& points, std::vector<Eigen::Vector4f>& colors,
              const Vec3& a, const Vec3& b, const Vec3& c, const Eigen::Vector4f& color) {
  for (const Vec3* p : {&a, &b, &c}) {
    points.push_back(p->cast<float>().homogeneous());
    colors.push_back(color);
  }
}

void quad(std::vector<Eigen::Vector4f>& points, std::vector<Eigen::Vector4f>& colors, const Vec3& a,
          const Vec3& b, const Vec3& c, const Vec3& d, const Eigen::Vector4f& color) {
  triangle(points, colors, a, b, c, color);
  triangle(points, colors, a, c, d, color);
}

/// `color` with its red, green and blue times `light`.
Eigen::Vector4f shaded(const Eigen::Vector4f& color, double light) {
  const float l = static_cast<float>(light);
  return Eigen::Vector4f(color.x() * l, color.y() * l, color.z() * l, color.w());
}

/// A box: `base` the centre of its bottom face, axes r (half width), u (height), f (half depth);
/// its faces in `color`, shaded by which way they face.
void box(std::vector<Eigen::Vector4f>& points, std::vector<Eigen::Vector4f>& colors,
         const Vec3& base, const Vec3& r, const Vec3& u, const Vec3& f,
         const Eigen::Vector4f& color) {
  auto at = [&](int i, int j, int k) {
    return Vec3(base + (2 * i - 1) * r + j * u + (2 * k - 1) * f);
  };
  // Front (toward the eye: -f), back, left, right, top, bottom.
  quad(points, colors, at(0, 0, 0), at(1, 0, 0), at(1, 1, 0), at(0, 1, 0), shaded(color, 1.0));
  quad(points, colors, at(0, 0, 1), at(0, 1, 1), at(1, 1, 1), at(1, 0, 1), shaded(color, 0.55));
  quad(points, colors, at(0, 0, 0), at(0, 1, 0), at(0, 1, 1), at(0, 0, 1), shaded(color, 0.75));
  quad(points, colors, at(1, 0, 0), at(1, 0, 1), at(1, 1, 1), at(1, 1, 0), shaded(color, 0.65));
  quad(points, colors, at(0, 1, 0), at(1, 1, 0), at(1, 1, 1), at(0, 1, 1), shaded(color, 0.9));
  quad(points, colors, at(0, 0, 0), at(0, 0, 1), at(1, 0, 1), at(1, 0, 0), shaded(color, 0.4));
}

/// The frame of M's view: where its view axis starts (the near face's centre) and ends (the far
/// face's, or a reach along the axis where the far plane is at infinity or very far), the screen's
/// right and up at each depth.
struct ViewFrame {
  Vec3 near_centre, far_centre, forward, right, up;
  bool ok = false;
};

ViewFrame view_frame(const Eigen::Matrix4d& m, Convention convention) {
  ViewFrame v;
  const Eigen::Matrix4d inverse = m.inverse();
  const double zn = near_z(convention), zf = far_z(convention);
  const std::optional<Vec3> n = from_ndc(inverse, 0, 0, zn);
  if (!n) return v;
  v.near_centre = *n;
  // The eye: the point M sends to clip w = 0 on the axis (M^-1 (0, 0, 1, 0)); none for an
  // affine (orthographic) M.
  const Vec4 eye_h = inverse * Vec4(0, 0, 1, 0);
  const bool finite_eye = std::abs(eye_h.w()) > 1e-300 && (eye_h.head<3>() / eye_h.w()).allFinite();
  // The far end: the far face's centre, or (infinite far) a direction.
  Vec3 far_point;
  const Vec4 f_h = inverse * Vec4(0, 0, zf, 1);
  if (f_h.w() > 0 && (f_h.head<3>() / f_h.w()).allFinite()) {
    far_point = f_h.head<3>() / f_h.w();
  } else {
    // Just inside the far face.
    const std::optional<Vec3> inside = from_ndc(inverse, 0, 0, zn + (zf - zn) * (1 - 1e-6));
    if (!inside) return v;
    far_point = *inside;
  }
  Vec3 axis = far_point - v.near_centre;
  if (!(axis.norm() > 0) || !axis.allFinite()) return v;
  if (finite_eye) {
    // Pillars beyond 60 times the near distance would be a few pixels: the scene stops there.
    const Vec3 eye = eye_h.head<3>() / eye_h.w();
    const double near_distance = (v.near_centre - eye).norm();
    const double reach = 60 * near_distance;
    if (near_distance > 0 && axis.norm() > reach) axis *= reach / axis.norm();
  }
  v.far_centre = v.near_centre + axis;
  v.forward = axis.normalized();
  // Screen right and up: where NDC x and y grow, at the near face, made orthogonal to the axis.
  const std::optional<Vec3> rx = from_ndc(inverse, 0.5, 0, zn), uy = from_ndc(inverse, 0, 0.5, zn);
  if (!rx || !uy) return v;
  Vec3 right = *rx - v.near_centre;
  right -= right.dot(v.forward) * v.forward;
  Vec3 up = *uy - v.near_centre;
  up -= up.dot(v.forward) * v.forward + up.dot(right.normalized()) * right.normalized();
  if (!(right.norm() > 0) || !(up.norm() > 0)) return v;
  v.right = right.normalized();
  v.up = up.normalized();
  v.ok = v.right.allFinite() && v.up.allFinite();
  return v;
}

/// Half the width and height of M's view at the axis point p (its NDC z): eye-space distances
/// from p to where NDC x = 1 and y = 1 at that depth.
std::pair<double, double> half_sizes(const Eigen::Matrix4d& m, const Eigen::Matrix4d& inverse,
                                     const Vec3& p) {
  const double z = ndc_z(m, p);
  const std::optional<Vec3> x = from_ndc(inverse, 1, 0, z), y = from_ndc(inverse, 0, 1, z);
  const std::optional<Vec3> c = from_ndc(inverse, 0, 0, z);
  if (!x || !y || !c) return {0, 0};
  return {(*x - *c).norm(), (*y - *c).norm()};
}

}  // namespace

bool keeps(const Eigen::Matrix4d& projection, const Eigen::Vector4d& p, Convention convention) {
  const Vec4 q = projection * p;
  const double w = q.w();
  const double z_low = convention == Convention::gl ? -w : 0;
  return -w <= q.x() && q.x() <= w && -w <= q.y() && q.y() <= w && z_low <= q.z() && q.z() <= w;
}

std::vector<Eigen::Vector4d> disagreements(const Eigen::Matrix4d& m,
                                           const Eigen::Matrix4d& expected,
                                           const Eigen::Matrix4d& answer, Convention convention,
                                           const std::vector<Eigen::Vector4d>& hints, int count) {
  const Eigen::Matrix4d inverse = m.inverse();
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> unit(-1, 1), depth(0, 1);
  const double zn = near_z(convention), zf = far_z(convention);
  const double z_low = std::min(zn, zf), z_high = std::max(zn, zf);
  // Each found point with its NDC (for spreading), the correct M''s kept ones first.
  std::vector<std::pair<Vec3, Vec4>> kept_by_expected, kept_by_answer;
  auto sample = [&](double x, double y, double z) {
    const std::optional<Vec3> p = from_ndc(inverse, x, y, z);
    if (!p) return;
    const Vec4 point = p->homogeneous();
    const bool e = keeps(expected, point, convention), a = keeps(answer, point, convention);
    if (e != a) (e ? kept_by_expected : kept_by_answer).push_back({Vec3(x, y, z), point});
  };
  for (int i = 0; i < 20000; ++i)
    sample(0.8 * unit(random), 0.8 * unit(random), zn + (zf - zn) * depth(random));
  // Between the two matrices' near planes, and between their far planes, on rays through the
  // screen: a slab however thin (a far plane that misses the far corner by a little), and what
  // one draws beyond M's far plane.
  const Eigen::Matrix4d expected_back = expected.inverse(), answer_back = answer.inverse();
  auto affine_of = [](const Vec4& v) -> std::optional<Vec3> {
    if (!(v.w() > 0) || !v.allFinite()) return std::nullopt;
    const Vec3 p = v.head<3>() / v.w();
    return p.allFinite() ? std::optional<Vec3>(p) : std::nullopt;
  };
  // The eye (M^-1 (0, 0, 1, 0): a point, or for an orthographic M a direction of the rays).
  const Vec4 eye = inverse * Vec4(0, 0, 1, 0);
  auto sample_eye_point = [&](const Vec3& p) {
    const Vec4 q = m * p.homogeneous();
    if (!(q.w() > 0)) return;
    const Vec3 ndc = q.head<3>() / q.w();
    if (ndc.allFinite()) sample(ndc.x(), ndc.y(), ndc.z());
  };
  auto between_faces = [&](double x, double y) {
    for (double face : {zn, zf}) {
      const std::optional<Vec3> e = affine_of(expected_back * Vec4(x, y, face, 1));
      const std::optional<Vec3> a = affine_of(answer_back * Vec4(x, y, face, 1));
      if (e && a) {
        for (double t : {0.25, 0.5, 0.75}) sample_eye_point(*e + t * (*a - *e));
      } else if (e || a) {
        // One face is at or beyond infinity: the ray beyond the other's.
        const Vec3 p = e ? *e : *a;
        for (double s : {1.25, 2.0, 8.0}) {
          if (std::abs(eye.w()) > 0 && (eye.head<3>() / eye.w()).allFinite()) {
            const Vec3 from = eye.head<3>() / eye.w();
            sample_eye_point(from + s * (p - from));
          } else if (eye.head<3>().norm() > 0) {
            const Vec3 along = eye.head<3>().normalized();
            const double sign = along.dot(p) >= 0 ? 1 : -1;
            sample_eye_point(p + sign * (s - 1) * (p.norm() + 1) * along);
          }
        }
      }
    }
  };
  for (int i = 0; i < 2000; ++i) between_faces(0.8 * unit(random), 0.8 * unit(random));
  // Around each hint, in ever smaller boxes of NDC (a sliver the answer cuts off at a corner).
  for (const Vec4& hint : hints) {
    const Vec4 q = m * hint;
    Vec3 centre;
    if (q.w() > 0) {
      centre = q.head<3>() / q.w();
    } else if (q.w() == 0) {  // a point at infinity: its corner of the far face
      centre = Vec3(q.x() > 0 ? 1 : -1, q.y() > 0 ? 1 : -1, zf);
    } else {
      continue;
    }
    if (!centre.allFinite()) continue;
    for (int i = 0; i < 200; ++i)
      between_faces(std::clamp(centre.x() + 0.05 * unit(random), -1.0, 1.0),
                    std::clamp(centre.y() + 0.05 * unit(random), -1.0, 1.0));
    for (double half : {0.1, 0.01, 1e-3, 1e-4}) {
      for (int i = 0; i < 1500; ++i) {
        sample(std::clamp(centre.x() + half * unit(random), -1.0, 1.0),
               std::clamp(centre.y() + half * unit(random), -1.0, 1.0),
               std::clamp(centre.z() + half * unit(random), z_low, z_high));
      }
    }
  }
  // A point whose neighbours a few pixels away on the screen (at its depth) disagree the same
  // way is robust: its marker shows the difference around its centre. Those first.
  auto robust = [&](const std::pair<Vec3, Vec4>& found) {
    const bool e = keeps(expected, found.second, convention);
    for (const Vec3& step :
         {Vec3(0.02, 0, 0), Vec3(-0.02, 0, 0), Vec3(0, 0.02, 0), Vec3(0, -0.02, 0)}) {
      const Vec3 ndc = found.first + step;
      const std::optional<Vec3> p = from_ndc(inverse, ndc.x(), ndc.y(), ndc.z());
      if (!p) return false;
      const Vec4 point = p->homogeneous();
      if (keeps(expected, point, convention) != e || keeps(answer, point, convention) == e)
        return false;
    }
    return true;
  };
  std::vector<std::pair<Vec3, Vec4>> groups[4];  // robust kept by M', by the answer; thin ones
  for (const auto& found : kept_by_expected) groups[robust(found) ? 0 : 2].push_back(found);
  for (const auto& found : kept_by_answer) groups[robust(found) ? 1 : 3].push_back(found);
  std::vector<Eigen::Vector4d> out;
  std::vector<Vec3> chosen;
  // Farthest-point choice (in NDC): spread over the screen, the most central first; robust
  // points before thin ones, a point the correct M' keeps and one the answer keeps in turn.
  auto pick = [&](std::vector<std::pair<Vec3, Vec4>>& group) {
    std::size_t best = 0;
    double best_distance = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < group.size(); ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec3& c : chosen) nearest = std::min(nearest, (group[i].first - c).norm());
      if (chosen.empty()) nearest = -std::abs(group[i].first.x()) - std::abs(group[i].first.y());
      if (nearest > best_distance) best_distance = nearest, best = i;
    }
    chosen.push_back(group[best].first);
    out.push_back(group[best].second);
    group.erase(group.begin() + static_cast<std::ptrdiff_t>(best));
  };
  for (int pass = 0; pass < 4; pass += 2) {
    while (static_cast<int>(out.size()) < count &&
           !(groups[pass].empty() && groups[pass + 1].empty())) {
      for (int g = pass; g < pass + 2 && static_cast<int>(out.size()) < count; ++g)
        if (!groups[g].empty()) pick(groups[g]);
    }
  }
  return out;
}

Mesh reference_scene(const Eigen::Matrix4d& m, const Eigen::Vector4d& c, Convention convention,
                     const std::vector<Eigen::Vector4d>& marks) {
  Mesh mesh;
  const ViewFrame v = view_frame(m, convention);
  if (!v.ok) return mesh;
  const Eigen::Matrix4d inverse = m.inverse();
  const double length = (v.far_centre - v.near_centre).norm();
  auto axis_point = [&](double t) {
    return Vec3(v.near_centre + t * (v.far_centre - v.near_centre));
  };
  // The floor: a plane below the axis, under the screen at the near end and at 30% below the
  // centre at the far end (seen from above by every projection, orthographic ones included).
  // Plain variables, not structured bindings: clang 14 (the fuzz preset) cannot capture those.
  const auto near_size = half_sizes(m, inverse, axis_point(0.02));
  const auto far_size = half_sizes(m, inverse, axis_point(1));
  const double near_w = near_size.first, near_h = near_size.second;
  const double far_w = far_size.first, far_h = far_size.second;
  if (!(near_h > 0) || !(far_h > 0)) return mesh;
  auto floor_height = [&](double t) { return -(1.1 * near_h) * (1 - t) - (0.3 * far_h) * t; };
  auto half_width = [&](double t) { return 1.4 * ((1 - t) * near_w + t * far_w); };
  auto floor_point = [&](double t, double s) {
    return Vec3(axis_point(t) + floor_height(t) * v.up + s * half_width(t) * v.right);
  };
  const int cells = 10;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells; ++j) {
      const double t0 = double(i) / cells, t1 = double(i + 1) / cells;
      const double s0 = -1 + 2.0 * j / cells, s1 = -1 + 2.0 * (j + 1) / cells;
      const double grey = (i + j) % 2 == 0 ? 0.78 : 0.6;
      quad(mesh.points, mesh.colors, floor_point(t0, s0), floor_point(t0, s1), floor_point(t1, s1),
           floor_point(t1, s0), rgba(grey, grey, grey * 1.05));
    }
  }
  // Pillars: spread along the axis (more of them near the eye) and across it, and two where C
  // crosses the axis, so C cuts them.
  std::vector<std::pair<double, double>> spots;  // (t, s)
  const int pillars = 9;
  for (int k = 0; k < pillars; ++k) {
    const double t = 0.08 + 0.88 * std::pow(double(k) / (pillars - 1), 1.6);
    spots.push_back({t, (k % 3 - 1) * 0.45 + (k % 2 ? 0.1 : -0.1)});
  }
  // C . axis_point(t) = 0: C . n + t C . (f - n) = 0.
  const double cn = c.head<3>().dot(v.near_centre) + c.w();
  const double cd = c.head<3>().dot(v.far_centre - v.near_centre);
  if (cd != 0) {
    const double t = -cn / cd;
    if (t > 0.03 && t < 0.97) {
      spots.push_back({t, -0.3});
      spots.push_back({t, 0.3});
    }
  }
  for (std::size_t k = 0; k < spots.size(); ++k) {
    const auto [t, s] = spots[k];
    const auto [w, h] = half_sizes(m, inverse, axis_point(t));
    const double size = 0.09 * half_width(t) / 1.4;
    const Vec3 base = floor_point(t, s * 0.7);
    const double height = std::max(0.4 * h, 1.5 * size) + (k % 2) * 0.3 * h - floor_height(t) * 0.5;
    box(mesh.points, mesh.colors, base, size * v.right, height * v.up,
        std::min(size, 0.02 * length) * v.forward, hue(double(k) / spots.size(), 1));
  }
  // A marker at each disagreement: a small cube, drawn over everything (magenta).
  for (const Eigen::Vector4d& mark : marks) {
    const Vec3 p = mark.head<3>() / mark.w();
    const auto [w, h] = half_sizes(m, inverse, p);
    const double size = 0.035 * std::max(w, h);
    // Flat, facing the eye, at the mark's own depth: the part of it one matrix clips and the
    // other keeps is around its centre, whichever way the plane between them runs.
    quad(mesh.overlay_points, mesh.overlay_colors, p - size * v.right - size * v.up,
         p + size * v.right - size * v.up, p + size * v.right + size * v.up,
         p - size * v.right + size * v.up, rgba(0.85, 0, 0.85));
  }
  return mesh;
}

}  // namespace oblique::raster
