// The case builder's definitions (oblique/cases/case_builder.h declares them): compiled once in
// oblique::cases (case_builder.cpp), and in a file built with OBLIQUE_CHECKER_HEADER_ONLY with
// that file's own flags (its Eigen layout).
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

#include "oblique/cases/case_builder.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/projection.h"
#include "oblique/references/frustum_planes.h"

namespace oblique::cases {
inline namespace OBLIQUE_EIGEN_LAYOUT {

namespace building {

using Wide = long double;

/// 0, -1, 1, -2, 2, ... from a pick 0, 1, 2, 3, 4, ... (shrinks toward 0).
inline int zigzag(int pick) {
  return pick % 2 ? -(pick + 1) / 2 : pick / 2;
}

/// 10^e exactly rounded to T (e small).
template <class T>
T decade(int e) {
  return static_cast<T>(std::pow(Wide(10), Wide(e)));
}

/// An exponent in [low, high] (low <= 0 <= high) that shrinks toward 0: picks 0, 1, 2, ...
/// give 0, -1, 1, -2, 2, ... and then the rest of the longer side.
int exponent(const Pick& pick, int low, int high) {
  std::vector<int> order;
  for (int e = 0; e <= std::max(-low, high); ++e) {
    if (e != 0 && -e >= low) order.push_back(-e);
    if (e <= high) order.push_back(e);
  }
  return order[static_cast<std::size_t>(pick(0, static_cast<int>(order.size())))];
}

/// The smallest positive power of two exponent a stiff parameter should reach for T.
template <class T>
int stiff_bits() {
  return std::numeric_limits<T>::digits - 8;
}

template <class T>
Matrix4<T> rotation_about(int ax, int ay, int az, int sixteenths_of_pi) {
  Eigen::Matrix<Wide, 3, 1> axis{Wide(ax), Wide(ay), Wide(az)};
  if (axis.isZero(0)) axis = Eigen::Matrix<Wide, 3, 1>(0, 1, 0);
  const Wide angle = Wide(sixteenths_of_pi) * Wide(3.14159265358979323846264338327950288L) / 16;
  Matrix4<Wide> r = Matrix4<Wide>::Identity();
  r.template topLeftCorner<3, 3>() =
      Eigen::AngleAxis<Wide>(angle, axis.normalized()).toRotationMatrix();
  return r.template cast<T>();
}

/// True when every corner of the view volume maps to camera-space w >= 0 (a proper volume).
template <class T>
bool proper_volume(const Matrix4<T>& m, Convention convention) {
  const Eigen::FullPivLU<Matrix4<Wide>> lu(m.template cast<Wide>());
  if (!lu.isInvertible()) return false;
  const DepthRange range = clip_depth_range(convention);
  for (int x : {-1, 1}) {
    for (int y : {-1, 1}) {
      for (int z : {range.z_low, range.z_high}) {
        const Vector4<Wide> q = lu.solve(Vector4<Wide>(Wide(x), Wide(y), Wide(z), 1));
        if (q.w() < -1e-12L * q.cwiseAbs().maxCoeff()) return false;
      }
    }
  }
  return true;
}

/// Camera-space point for a clip-space point (x, y, z, 1), normalised to w = 1 when finite.
template <class T>
Vector4<Wide> unproject(const Matrix4<T>& m, const Vector4<Wide>& clip) {
  Vector4<Wide> p = m.template cast<Wide>().fullPivLu().solve(clip);
  if (std::abs(p.w()) > Wide(0)) p /= p.w();
  return p;
}

template <class T>
Vector4<T> round_plane(const Vector4<Wide>& c) {
  return c.template cast<T>();
}

}  // namespace building

template <class T>
Matrix4<T> build_projection(Family family, Convention convention, int round, const Pick& pick) {
  const int near_exponent = building::exponent(pick, -6, 1);
  const T n = building::decade<T>(near_exponent) * (T(1) + T(pick(0, 8)) / T(8));
  const int ratio_exponent = pick(0, 13);
  const T f = n * building::decade<T>(ratio_exponent) * (T(2) + T(pick(0, 8)) / T(4));
  const T top = n * (T(1) + T(pick(0, 6))) / T(2);
  const T right = top * (T(1) + T(pick(0, 8)) / T(4));
  const int pattern = round >= 0 ? round % 4 : pick(0, 4);
  const T sign_x = pattern & 1 ? T(-1) : T(1), sign_y = pattern & 2 ? T(-1) : T(1);
  // A lean of 0 (from `low` = 0: centred), 1/4 .. 2 half-widths (beyond 1: the axis outside).
  auto lean = [&](int low) { return T(pick(low, 9)) / T(4); };
  // The flipped, jittered and left-handed frustums: centred in x in a run's rounds 4, 12, ...
  // and in y in rounds 5, 13, ..., else leaning by lean(1); without a round, centred one in
  // nine. (Not lean(0): RapidCheck's inRange favours its low end at small sizes, and a run's
  // early rounds then drew no lean at all.)
  auto lean_x = [&] { return (round >= 0 ? round % 8 == 4 : pick(0, 9) == 0) ? T(0) : lean(1); };
  auto lean_y = [&] { return (round >= 0 ? round % 8 == 5 : pick(0, 9) == 0) ? T(0) : lean(1); };
  // The frustum leaning by sx, sy half-widths: M13 = sx, M23 = sy.
  auto leaning = [&](T sx, T sy, bool infinite_far) {
    const T l = -right * (T(1) - sx), r = right * (T(1) + sx);
    const T b = -top * (T(1) - sy), t = top * (T(1) + sy);
    return infinite_far ? infinite_frustum<T>(l, r, b, t, n, convention)
                        : frustum<T>(l, r, b, t, n, f, convention);
  };
  switch (family) {
    case Family::perspective: return frustum<T>(-right, right, -top, top, n, f, convention);
    case Family::off_axis: return leaning(sign_x * lean(1), sign_y * lean(1), false);
    case Family::infinite: return infinite_frustum<T>(-right, right, -top, top, n, convention);
    case Family::orthographic: {
      // Near may be negative: a box reaching behind the eye (then C'_z can be negative).
      const T near_o = pick(0, 4) == 3 ? -n * T(4) : n;
      const T depth = n * building::decade<T>(pick(0, 7)) * T(8);
      const T half =
          building::decade<T>(building::exponent(pick, -2, 3)) * (T(1) + T(pick(0, 8)) / T(8));
      // Half-widths h .. 2h and h; the centre off by 1/4 .. 1 half-width either way (M14,
      // M24), or centred (a shadow map's box): in a run's rounds 7, 15, ... (one in eight: a
      // default run of 100 cases over the 13 families has rounds 0 .. 7, the sign patterns in
      // 0 .. 3 and 4 .. 6 off centre), else one in five.
      const T hx = half * (T(1) + T(pick(0, 5)) / T(4)), hy = half;
      const bool centred = round >= 0 ? round % 8 == 7 : pick(0, 5) == 0;
      auto offset = [&](T sign) { return centred ? T(0) : sign * T(1 + pick(0, 4)) / T(4); };
      const T ox = offset(sign_x), oy = offset(sign_y);
      return orthographic<T>(hx * (ox - T(1)), hx * (ox + T(1)), hy * (oy - T(1)), hy * (oy + T(1)),
                             near_o, near_o + depth, convention);
    }
    case Family::y_flipped:
    case Family::x_flipped:
    case Family::xy_flipped: {
      // Flipped after building, as engines flip: a leaning frustum's M13, M23 flip with it.
      Matrix4<T> m = leaning(sign_x * lean_x(), sign_y * lean_y(), false);
      if (family != Family::y_flipped) m.row(0) *= T(-1);
      if (family != Family::x_flipped) m.row(1) *= T(-1);
      return m;
    }
    case Family::left_handed:
    case Family::left_handed_x_flipped: {
      // Camera z negated (M times diag(1, 1, -1, 1)): M43 = +1, M33 and a lean's M13, M23
      // change sign. Finite or infinite: by the round (rounds 4 .. 7 of each 8), so a run
      // draws each sign pattern both ways. 0 - x, so a centred frustum's M13 and M23 stay +0
      // as an engine's are.
      const bool infinite_far = round >= 0 ? (round / 4) % 2 == 1 : pick(0, 4) == 3;
      Matrix4<T> m = leaning(sign_x * lean_x(), sign_y * lean_y(), infinite_far);
      m.col(2) = Vector4<T>::Zero() - m.col(2);
      // A Direct3D-style mirror pass: clip x negated after building, as for x_flipped.
      if (family == Family::left_handed_x_flipped) m.row(0) *= T(-1);
      return m;
    }
    case Family::jittered: {
      Matrix4<T> m = leaning(sign_x * lean_x(), sign_y * lean_y(), false);
      // A sub-pixel offset in NDC, as temporal anti-aliasing applies: M_i += j M_4.
      m.row(0) += (T(pick(-4, 5)) / T(4096)) * m.row(3);
      m.row(1) += (T(pick(-4, 5)) / T(4096)) * m.row(3);
      return m;
    }
    case Family::stereo_shift: {
      // Which shift: horizontal (a stereo eye), vertical (a lens shift), or both; from the
      // round too, so that a run draws each with each sign.
      const int which = round >= 0 ? (round / 4) % 3 : pick(0, 3);
      const bool infinite_far = pick(0, 2) == 1;
      // A stereo pair's frustums lean toward each other: off-axis by 1/8 .. 1/2 in x, either
      // way (M13), the way of the eye's shift (the left eye, at -x, sees the scene moved by
      // tx > 0 and leans toward +x).
      const T sx = sign_x * T(1 + pick(0, 4)) / T(8);
      Matrix4<T> m = leaning(sx, T(0), infinite_far);
      // Shifts of n/8 .. 2n (an interocular half-distance of 0.032 with n = 0.1 is 0.32 n),
      // exact multiples of n: tx with the x sign, ty with the y sign.
      auto shift = [&](T sign) { return sign * n * T(1 + pick(0, 16)) / T(8); };
      const T tx = which != 1 ? shift(sign_x) : T(0);
      const T ty = which != 0 ? shift(sign_y) : T(0);
      Matrix4<T> translation = Matrix4<T>::Identity();
      translation(0, 3) = tx;
      translation(1, 3) = ty;
      return Matrix4<T>(m * translation);
    }
    case Family::rotated:
    case Family::general: {
      const Matrix4<T> p = frustum<T>(-right, right, -top, top, n, f, convention);
      const Matrix4<T> r =
          building::rotation_about<T>(pick(0, 4), pick(0, 4), pick(0, 4), pick(1, 32));
      Matrix4<T> m = p * r;
      if (family == Family::general) {
        // A projective perturbation of every entry, scaled to each row: a matrix of no
        // particular shape whose view volume stays proper.
        Matrix4<T> e;
        for (int i = 0; i < 4; ++i) {
          for (int j = 0; j < 4; ++j) e(i, j) = T(pick(-2, 3)) / T(32);
        }
        Matrix4<T> perturbed = m;
        for (int i = 0; i < 4; ++i) perturbed.row(i) += m.row(i).cwiseAbs().maxCoeff() * e.row(i);
        if (building::proper_volume(perturbed, convention)) m = perturbed;
      }
      return m;
    }
  }
  return Matrix4<T>(Matrix4<T>::Identity());
}

template <class T>
Vector4<T> build_plane(const Matrix4<T>& m, Convention convention, Place place, const Pick& pick) {
  const DepthRange range = clip_depth_range(convention);
  // A point inside the view volume (clip-space grid, never on a face).
  const Vector4<building::Wide> clip(
      building::Wide(pick(-3, 4)) / 4, building::Wide(pick(-3, 4)) / 4,
      range.z_low + building::Wide(range.z_high - range.z_low) * building::Wide(1 + pick(0, 7)) / 8,
      1);
  const Vector4<building::Wide> p = building::unproject(m, clip);
  // A normal near (0, 0, -1): the picks shrink toward the standard near plane's direction.
  Eigen::Matrix<building::Wide, 3, 1> normal(
      building::Wide(building::zigzag(pick(0, 9))) / 4,
      building::Wide(building::zigzag(pick(0, 9))) / 4,
      building::Wide(-1) + building::Wide(building::zigzag(pick(0, 9))) / 4);
  if (normal.isZero(0)) normal.z() = -1;
  auto through_point = [&](const Eigen::Matrix<building::Wide, 3, 1>& nrm) {
    Vector4<building::Wide> c;
    c << nrm, -nrm.dot(p.template head<3>());
    if (c.w() > 0) c = -c;
    if (c.w() == 0) c.w() = -nrm.norm() * std::ldexp(building::Wide(1), -20);
    return c;
  };
  switch (place) {
    case Place::typical: return building::round_plane<T>(through_point(normal));
    case Place::scaled: {
      // 1e-8 .. 1e8, or to the edges of T's range: every entry subnormal, or near overflow.
      const int scale = pick(0, 19);
      const Vector4<building::Wide> c = through_point(normal);
      if (scale < 17)
        return building::round_plane<T>(
            c * std::pow(building::Wide(10), building::Wide(building::zigzag(scale))));
      const int e = scale == 17 ? std::numeric_limits<T>::min_exponent - 6
                                : std::numeric_limits<T>::max_exponent - 4;
      Vector4<T> out = building::round_plane<T>(c / c.cwiseAbs().maxCoeff());
      for (int i = 0; i < 4; ++i) out(i) = std::ldexp(out(i), e);
      if (!(out.w() < T(0))) out.w() = -std::numeric_limits<T>::denorm_min();
      return out;
    }
    case Place::zero_in_clip_plane: {
      // C' = M^-T C with C'_x and/or C'_y zero: C = M^T C'.
      const int which = pick(0, 3);  // x, y, both
      Vector4<building::Wide> c = through_point(normal);
      const Matrix4<building::Wide> mw = m.template cast<building::Wide>();
      Vector4<building::Wide> c_clip = mw.transpose().fullPivLu().solve(c);
      if (which != 1) c_clip.x() = 0;
      if (which != 0) c_clip.y() = 0;
      c = mw.transpose() * c_clip;
      if (c.w() > 0) c = -c;
      return building::round_plane<T>(c);
    }
    case Place::near_eye: {
      // Through (almost) the eye, the kept side toward the interior point p.
      Eigen::Matrix<building::Wide, 3, 1> nrm = normal;
      if (p.w() != 0 && nrm.dot(p.template head<3>()) < 0) nrm = -nrm;
      const int k = 8 + pick(0, building::stiff_bits<T>() - 7);
      Vector4<building::Wide> c;
      c << nrm, -nrm.norm() * std::ldexp(building::Wide(1), -k);
      return building::round_plane<T>(c);
    }
    case Place::near_far_corner: {
      // C . Q = delta |N| |Q| for the far corner Q of N's sign pattern.
      const int k = 1 + pick(0, building::stiff_bits<T>());
      const building::Wide delta = std::ldexp(building::Wide(1), -k);
      Eigen::Matrix<building::Wide, 3, 1> nrm = normal;
      Vector4<building::Wide> c;
      for (int attempt = 0; attempt < 2; ++attempt) {
        c << nrm, -1;
        const Matrix4<building::Wide> mw = m.template cast<building::Wide>();
        const Vector4<building::Wide> c_clip = mw.transpose().fullPivLu().solve(c);
        const building::Wide z_far = c_clip.z() >= 0 ? range.z_high : range.z_low;
        auto sgn = [](building::Wide x) {
          return x > 0 ? building::Wide(1) : (x < 0 ? building::Wide(-1) : building::Wide(0));
        };
        const Vector4<building::Wide> q = mw.fullPivLu().solve(
            Vector4<building::Wide>(sgn(c_clip.x()), sgn(c_clip.y()), z_far, 1));
        const building::Wide target = delta * nrm.norm() * q.template head<3>().norm();
        if (std::abs(q.w()) > building::Wide(1e-9) * q.template head<3>().norm()) {
          c.w() = (target - nrm.dot(q.template head<3>())) / q.w();
        } else if (q.z() != 0) {  // Q is a direction: tilt N so that N . Q = delta |N| |Q|
          nrm.z() += (target - nrm.dot(q.template head<3>())) / q.z();
          c << nrm, -nrm.norm();
        }
      }
      return building::round_plane<T>(c);
    }
    case Place::along_axis: {
      const building::Wide t =
          std::ldexp(building::Wide(1), -(2 + pick(0, building::stiff_bits<T>() / 2)));
      Eigen::Matrix<building::Wide, 3, 1> nrm(1, building::Wide(building::zigzag(pick(0, 5))) * t,
                                              -t);
      return building::round_plane<T>(through_point(nrm));
    }
    case Place::near_standard: {
      const building::Wide t =
          std::ldexp(building::Wide(1), -(2 + pick(0, building::stiff_bits<T>())));
      const Vector4<building::Wide> near =
          near_plane<T>(m, convention).template cast<building::Wide>();
      const Vector4<building::Wide> wiggle(
          building::zigzag(pick(0, 5)), building::zigzag(pick(0, 5)), building::zigzag(pick(0, 5)),
          building::zigzag(pick(0, 5)));
      return building::round_plane<T>(near + t * near.cwiseAbs().maxCoeff() * wiggle);
    }
  }
  return Vector4<T>(0, 0, -1, -1);
}

template <class T>
Case<T> build_case(Family family, Convention convention, Place place, int round, const Pick& pick) {
  Case<T> c;
  c.family = family;
  c.convention = convention;
  c.place = place;
  c.matrix = build_projection<T>(family, convention, round, pick);
  c.plane = build_plane<T>(c.matrix, convention, place, pick);
  return c;
}

template <class T>
Case<T> spoil(Case<T> c, Defect defect, const Pick& pick) {
  c.defect = defect;
  const Vector4<T> nrm(c.plane.x(), c.plane.y(), c.plane.z(), T(0));
  switch (defect) {
    case Defect::camera_in_front: {
      const T choices[] = {T(0), T(-0.0), nrm.norm(), nrm.norm() * std::ldexp(T(1), -40)};
      c.plane.w() = choices[pick(0, 4)];
      break;
    }
    case Defect::misses_view_volume: {
      // With the near plane (u, d), |u| = 1, the volume has u . p + d >= 0. Keep instead
      // u . p <= -(2 |d| + 1): behind the camera, outside the near plane. For a finite volume
      // with far plane (v, e), keep v . p + e <= -(|e| / 2 + 1): beyond the far plane.
      // Either way C_w < 0, so the camera stays behind C.
      const Vector4<T> far = far_plane<T>(c.matrix, c.convention);
      const Vector4<T> near = near_plane<T>(c.matrix, c.convention);
      const bool beyond_far = pick(0, 2) == 1 && far.template head<3>().norm() > T(0);
      if (beyond_far) {
        const Vector4<T> f = far / far.template head<3>().norm();
        c.plane << -f.template head<3>(), -f.w() - (std::abs(f.w()) / T(2) + T(1));
      } else {
        const Vector4<T> u = near / near.template head<3>().norm();
        c.plane << -u.template head<3>(), -(T(2) * std::abs(u.w()) + T(1));
      }
      break;
    }
    case Defect::singular: {
      const int row = pick(0, 4), factor = pick(0, 3);
      c.matrix.row(row) = T(factor) * c.matrix.row((row + 1) % 4);
      break;
    }
    case Defect::near_singular: {
      const int k = std::numeric_limits<T>::digits - 12 + pick(0, 16);
      c.matrix.row(2) = c.matrix.row(3) + std::ldexp(T(1), -k) * c.matrix.row(2);
      break;
    }
    case Defect::non_finite: {
      const T values[] = {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                          -std::numeric_limits<T>::infinity()};
      const T value = values[pick(0, 3)];
      const int index = pick(0, 20);
      if (index < 16) {
        c.matrix(index / 4, index % 4) = value;
      } else {
        c.plane(index - 16) = value;
      }
      break;
    }
  }
  return c;
}

template <class T>
Vector4<T> unit_normal(const Vector4<T>& c) {
  if (!all_finite(c)) return c;
  const Vector4<long double> wide = c.template cast<long double>();
  const long double norm = wide.template head<3>().norm();
  if (!(norm > 0) || !std::isfinite(norm)) return c;
  return (wide / norm).template cast<T>();
}

template <class T>
Case<T> choose_case(const Contract& contract, bool defects, const Pick& pick) {
  auto one_of = [&pick](const auto& list) {
    return list[static_cast<std::size_t>(pick(0, static_cast<int>(list.size())))];
  };
  const bool spoiled = defects && !contract.defects.empty() && pick(0, 5) == 4;
  const std::optional<Defect> defect =
      spoiled ? std::optional<Defect>(one_of(contract.defects)) : std::nullopt;
  const Family family = one_of(contract.families);
  const Convention convention = one_of(contract.conventions);
  const Place place = one_of(contract.places);
  Case<T> c = build_case<T>(family, convention, place, pick(0, kRounds), pick);
  if (defect) c = spoil(std::move(c), *defect, pick);
  // After spoiling, as invalid_case_for() does: a spoiled plane keeps its defect at unit scale.
  if (contract.planes == Planes::unit) c.plane = unit_normal(c.plane);
  return c;
}

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::cases
