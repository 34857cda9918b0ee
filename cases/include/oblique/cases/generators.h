// RapidCheck generators of projections and planes: every family, every convention, magnitudes
// from tiny to huge, planes biased toward the hard places, and the invalid inputs.
//
// Every choice is an integer pick whose zero is the simplest value (RapidCheck shrinks integers
// toward the low end of their range), so a shrunk counterexample reads like 1, 0.5, 1e-6, not
// like 0.7368421052631579. RapidCheck's own double generator produces no zeros, subnormals or
// boundaries and shrinks doubles poorly; nothing here uses it.
#pragma once

#include <rapidcheck.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/cases/contract.h"
#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/frustum_planes.h"

namespace oblique::generators {

template <class T>
struct Case {
  Family family = Family::perspective;
  Convention convention = Convention::gl;
  Place place = Place::typical;
  Matrix4<T> matrix = Matrix4<T>::Identity();
  Vector4<T> plane = Vector4<T>::Zero();
};

template <class T>
struct InvalidCase {
  Defect defect = Defect::camera_in_front;
  Case<T> base;  ///< the valid case it was made from, with matrix and plane already spoiled
};

namespace detail {

using Wide = long double;

/// One of `choices`, uniformly whatever RapidCheck's size (which otherwise favours the first),
/// shrinking toward the first.
template <class E>
rc::Gen<E> category(std::vector<E> all) {
  const std::size_t n = all.size();
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<std::size_t>(0, n)),
                      [all = std::move(all)](std::size_t i) { return all[i]; });
}
/// One of `all` by the generation's size: size k gives all[k % n]. RapidCheck spreads a run's
/// sizes evenly over 0..max_size (100), so a run of 100 cases draws each of up to 11 choices 9
/// times or more, whatever the seed (a uniform pick of 11 misses one in about 1 run of 1,000,
/// and the suite runs dozens). The pick does not shrink.
template <class E>
rc::Gen<E> cycled(std::vector<E> all) {
  return rc::gen::withSize([all = std::move(all)](int size) {
    return rc::gen::just(all[static_cast<std::size_t>(size) % all.size()]);
  });
}
template <class E, std::size_t N>
rc::Gen<E> category(const E (&choices)[N]) {
  return category(std::vector<E>(choices, choices + N));
}  // construction arithmetic; the results are rounded to T once

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
inline rc::Gen<int> exponent(int low, int high) {
  std::vector<int> order;
  for (int e = 0; e <= std::max(-low, high); ++e) {
    if (e != 0 && -e >= low) order.push_back(-e);
    if (e <= high) order.push_back(e);
  }
  return rc::gen::map(rc::gen::inRange<std::size_t>(0, order.size()),
                      [order](std::size_t pick) { return order[pick]; });
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

}  // namespace detail

/// A projection of `family` in `convention`, its parameters from readable picks:
/// near 1e-6 .. 10, far / near 1.5 .. ~1e12 (or infinite), symmetric to fully off-axis.
///
/// Every sign an engine's matrix takes is drawn: a frustum leans either way in x and y (M13,
/// M23: a VR eye has more field of view on one side, a tiled screenshot's row above or below the
/// axis), a stereo eye leans and shifts either way (M14, M24), a box is centred or off-centre
/// either way, and the flipped and jittered frustums lean too. Which signs: `round`'s pattern
/// (round % 4: bit 0 the x sign, bit 1 the y sign), so that a run that cycles its rounds draws
/// every pattern of every family (valid_case_in() passes the run's round); picked when negative.
template <class T>
rc::Gen<Matrix4<T>> projection(Family family, Convention convention, int round = -1) {
  return rc::gen::exec([=] {
    using detail::decade;
    const int near_exponent = *detail::exponent(-6, 1);
    const T n = decade<T>(near_exponent) * (T(1) + T(*rc::gen::inRange(0, 8)) / T(8));
    const int ratio_exponent = *rc::gen::inRange(0, 13);
    const T f = n * decade<T>(ratio_exponent) * (T(2) + T(*rc::gen::inRange(0, 8)) / T(4));
    const T top = n * (T(1) + T(*rc::gen::inRange(0, 6))) / T(2);
    const T right = top * (T(1) + T(*rc::gen::inRange(0, 8)) / T(4));
    const int pattern = round >= 0 ? round % 4 : *rc::gen::inRange(0, 4);
    const T sign_x = pattern & 1 ? T(-1) : T(1), sign_y = pattern & 2 ? T(-1) : T(1);
    // A lean of 0 (from `low` = 0: centred), 1/4 .. 2 half-widths (beyond 1: the axis outside).
    auto lean = [](int low) { return T(*rc::gen::inRange(low, 9)) / T(4); };
    // The flipped, jittered and left-handed frustums: centred in x in a run's rounds 4, 12, ...
    // and in y in rounds 5, 13, ..., else leaning by lean(1); without a round, centred one in
    // nine. (Not lean(0): RapidCheck's inRange favours its low end at small sizes, and a run's
    // early rounds then drew no lean at all.)
    auto lean_x = [&] {
      return (round >= 0 ? round % 8 == 4 : *rc::gen::inRange(0, 9) == 0) ? T(0) : lean(1);
    };
    auto lean_y = [&] {
      return (round >= 0 ? round % 8 == 5 : *rc::gen::inRange(0, 9) == 0) ? T(0) : lean(1);
    };
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
        const T near_o = *rc::gen::inRange(0, 4) == 3 ? -n * T(4) : n;
        const T depth = n * decade<T>(*rc::gen::inRange(0, 7)) * T(8);
        const T half =
            decade<T>(*detail::exponent(-2, 3)) * (T(1) + T(*rc::gen::inRange(0, 8)) / T(8));
        // Half-widths h .. 2h and h; the centre off by 1/4 .. 1 half-width either way (M14,
        // M24), or centred (a shadow map's box): in a run's rounds 8, 20, ... (one in three of
        // its fourth rounds), else one in five.
        const T hx = half * (T(1) + T(*rc::gen::inRange(0, 5)) / T(4)), hy = half;
        const bool centred = round >= 0 ? (round / 4) % 3 == 2 : *rc::gen::inRange(0, 5) == 0;
        auto offset = [&](T sign) {
          return centred ? T(0) : sign * T(1 + *rc::gen::inRange(0, 4)) / T(4);
        };
        const T ox = offset(sign_x), oy = offset(sign_y);
        return orthographic<T>(hx * (ox - T(1)), hx * (ox + T(1)), hy * (oy - T(1)),
                               hy * (oy + T(1)), near_o, near_o + depth, convention);
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
      case Family::left_handed: {
        // Camera z negated (M times diag(1, 1, -1, 1)): M43 = +1, M33 and a lean's M13, M23
        // change sign. Finite or infinite: by the round (rounds 4 .. 7 of each 8), so a run
        // draws each sign pattern both ways. 0 - x, so a centred frustum's M13 and M23 stay +0
        // as an engine's are.
        const bool infinite_far = round >= 0 ? (round / 4) % 2 == 1 : *rc::gen::inRange(0, 4) == 3;
        Matrix4<T> m = leaning(sign_x * lean_x(), sign_y * lean_y(), infinite_far);
        m.col(2) = Vector4<T>::Zero() - m.col(2);
        return m;
      }
      case Family::jittered: {
        Matrix4<T> m = leaning(sign_x * lean_x(), sign_y * lean_y(), false);
        // A sub-pixel offset in NDC, as temporal anti-aliasing applies: M_i += j M_4.
        m.row(0) += (T(*rc::gen::inRange(-4, 5)) / T(4096)) * m.row(3);
        m.row(1) += (T(*rc::gen::inRange(-4, 5)) / T(4096)) * m.row(3);
        return m;
      }
      case Family::stereo_shift: {
        // Which shift: horizontal (a stereo eye), vertical (a lens shift), or both; from the
        // round too, so that a run draws each with each sign.
        const int which = round >= 0 ? (round / 4) % 3 : *rc::gen::inRange(0, 3);
        const bool infinite_far = *rc::gen::inRange(0, 2) == 1;
        // A stereo pair's frustums lean toward each other: off-axis by 1/8 .. 1/2 in x, either
        // way (M13), the way of the eye's shift (the left eye, at -x, sees the scene moved by
        // tx > 0 and leans toward +x).
        const T sx = sign_x * T(1 + *rc::gen::inRange(0, 4)) / T(8);
        Matrix4<T> m = leaning(sx, T(0), infinite_far);
        // Shifts of n/8 .. 2n (an interocular half-distance of 0.032 with n = 0.1 is 0.32 n),
        // exact multiples of n: tx with the x sign, ty with the y sign.
        auto shift = [&](T sign) { return sign * n * T(1 + *rc::gen::inRange(0, 16)) / T(8); };
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
            detail::rotation_about<T>(*rc::gen::inRange(0, 4), *rc::gen::inRange(0, 4),
                                      *rc::gen::inRange(0, 4), *rc::gen::inRange(1, 32));
        Matrix4<T> m = p * r;
        if (family == Family::general) {
          // A projective perturbation of every entry, scaled to each row: a matrix of no
          // particular shape whose view volume stays proper.
          Matrix4<T> e;
          for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j) e(i, j) = T(*rc::gen::inRange(-2, 3)) / T(32);
          }
          Matrix4<T> perturbed = m;
          for (int i = 0; i < 4; ++i) perturbed.row(i) += m.row(i).cwiseAbs().maxCoeff() * e.row(i);
          if (detail::proper_volume(perturbed, convention)) m = perturbed;
        }
        return m;
      }
    }
    return Matrix4<T>(Matrix4<T>::Identity());
  });
}

/// A plane at `place` for the projection m. The camera is behind it (C_w < 0) by construction
/// except where rounding or the family's geometry prevents it; properties filter those with the
/// exact status.
template <class T>
rc::Gen<Vector4<T>> plane(const Matrix4<T>& m, Convention convention, Place place) {
  return rc::gen::exec([=] {
    using detail::Wide;
    const DepthRange range = clip_depth_range(convention);
    // A point inside the view volume (clip-space grid, never on a face).
    const Vector4<Wide> clip(
        Wide(*rc::gen::inRange(-3, 4)) / 4, Wide(*rc::gen::inRange(-3, 4)) / 4,
        range.z_low + Wide(range.z_high - range.z_low) * Wide(1 + *rc::gen::inRange(0, 7)) / 8, 1);
    const Vector4<Wide> p = detail::unproject(m, clip);
    // A normal near (0, 0, -1): the picks shrink toward the standard near plane's direction.
    Eigen::Matrix<Wide, 3, 1> normal(Wide(detail::zigzag(*rc::gen::inRange(0, 9))) / 4,
                                     Wide(detail::zigzag(*rc::gen::inRange(0, 9))) / 4,
                                     Wide(-1) + Wide(detail::zigzag(*rc::gen::inRange(0, 9))) / 4);
    if (normal.isZero(0)) normal.z() = -1;
    auto through_point = [&](const Eigen::Matrix<Wide, 3, 1>& nrm) {
      Vector4<Wide> c;
      c << nrm, -nrm.dot(p.template head<3>());
      if (c.w() > 0) c = -c;
      if (c.w() == 0) c.w() = -nrm.norm() * std::ldexp(Wide(1), -20);
      return c;
    };
    switch (place) {
      case Place::typical: return detail::round_plane<T>(through_point(normal));
      case Place::scaled: {
        // 1e-8 .. 1e8, or to the edges of T's range: every entry subnormal, or near overflow.
        const int pick = *rc::gen::inRange(0, 19);
        const Vector4<Wide> c = through_point(normal);
        if (pick < 17)
          return detail::round_plane<T>(c * std::pow(Wide(10), Wide(detail::zigzag(pick))));
        const int e = pick == 17 ? std::numeric_limits<T>::min_exponent - 6
                                 : std::numeric_limits<T>::max_exponent - 4;
        Vector4<T> out = detail::round_plane<T>(c / c.cwiseAbs().maxCoeff());
        for (int i = 0; i < 4; ++i) out(i) = std::ldexp(out(i), e);
        if (!(out.w() < T(0))) out.w() = -std::numeric_limits<T>::denorm_min();
        return out;
      }
      case Place::zero_in_clip_plane: {
        // C' = M^-T C with C'_x and/or C'_y zero: C = M^T C'.
        const int which = *rc::gen::inRange(0, 3);  // x, y, both
        Vector4<Wide> c = through_point(normal);
        const Matrix4<Wide> mw = m.template cast<Wide>();
        Vector4<Wide> c_clip = mw.transpose().fullPivLu().solve(c);
        if (which != 1) c_clip.x() = 0;
        if (which != 0) c_clip.y() = 0;
        c = mw.transpose() * c_clip;
        if (c.w() > 0) c = -c;
        return detail::round_plane<T>(c);
      }
      case Place::near_eye: {
        // Through (almost) the eye, the kept side toward the interior point p.
        Eigen::Matrix<Wide, 3, 1> nrm = normal;
        if (p.w() != 0 && nrm.dot(p.template head<3>()) < 0) nrm = -nrm;
        const int k = 8 + *rc::gen::inRange(0, detail::stiff_bits<T>() - 7);
        Vector4<Wide> c;
        c << nrm, -nrm.norm() * std::ldexp(Wide(1), -k);
        return detail::round_plane<T>(c);
      }
      case Place::near_far_corner: {
        // C . Q = delta |N| |Q| for the far corner Q of N's sign pattern.
        const int k = 1 + *rc::gen::inRange(0, detail::stiff_bits<T>());
        const Wide delta = std::ldexp(Wide(1), -k);
        Eigen::Matrix<Wide, 3, 1> nrm = normal;
        Vector4<Wide> c;
        for (int attempt = 0; attempt < 2; ++attempt) {
          c << nrm, -1;
          const Matrix4<Wide> mw = m.template cast<Wide>();
          const Vector4<Wide> c_clip = mw.transpose().fullPivLu().solve(c);
          const Wide z_far = c_clip.z() >= 0 ? range.z_high : range.z_low;
          auto sgn = [](Wide x) { return x > 0 ? Wide(1) : (x < 0 ? Wide(-1) : Wide(0)); };
          const Vector4<Wide> q =
              mw.fullPivLu().solve(Vector4<Wide>(sgn(c_clip.x()), sgn(c_clip.y()), z_far, 1));
          const Wide target = delta * nrm.norm() * q.template head<3>().norm();
          if (std::abs(q.w()) > Wide(1e-9) * q.template head<3>().norm()) {
            c.w() = (target - nrm.dot(q.template head<3>())) / q.w();
          } else if (q.z() != 0) {  // Q is a direction: tilt N so that N . Q = delta |N| |Q|
            nrm.z() += (target - nrm.dot(q.template head<3>())) / q.z();
            c << nrm, -nrm.norm();
          }
        }
        return detail::round_plane<T>(c);
      }
      case Place::along_axis: {
        const Wide t =
            std::ldexp(Wide(1), -(2 + *rc::gen::inRange(0, detail::stiff_bits<T>() / 2)));
        Eigen::Matrix<Wide, 3, 1> nrm(1, Wide(detail::zigzag(*rc::gen::inRange(0, 5))) * t, -t);
        return detail::round_plane<T>(through_point(nrm));
      }
      case Place::near_standard: {
        const Wide t = std::ldexp(Wide(1), -(2 + *rc::gen::inRange(0, detail::stiff_bits<T>())));
        const Vector4<Wide> near = near_plane<T>(m, convention).template cast<Wide>();
        const Vector4<Wide> wiggle(
            detail::zigzag(*rc::gen::inRange(0, 5)), detail::zigzag(*rc::gen::inRange(0, 5)),
            detail::zigzag(*rc::gen::inRange(0, 5)), detail::zigzag(*rc::gen::inRange(0, 5)));
        return detail::round_plane<T>(near + t * near.cwiseAbs().maxCoeff() * wiggle);
      }
    }
    return Vector4<T>(0, 0, -1, -1);
  });
}

/// A valid-looking case of one of `families` in one of `conventions` at one of `places` (all
/// non-empty).
template <class T>
rc::Gen<Case<T>> valid_case_in(std::vector<Family> families, std::vector<Convention> conventions,
                               std::vector<Place> places = every_place()) {
  return rc::gen::exec([families, conventions, places] {
    Case<T> c;
    c.family = *detail::cycled(families);  // every family in every run, not by luck
    // The family's round in the run (the families cycle by size): its sign pattern, so every
    // pattern of every family is drawn in every run too.
    const int round = *rc::gen::withSize(
        [n = static_cast<int>(families.size())](int size) { return rc::gen::just(size / n); });
    c.convention = *detail::category(conventions);
    c.place = *detail::category(places);
    c.matrix = *projection<T>(c.family, c.convention, round);
    c.plane = *plane<T>(c.matrix, c.convention, c.place);
    return c;
  });
}

/// A valid-looking case of one family (for the properties that apply to one family only).
template <class T>
rc::Gen<Case<T>> valid_case_of(Family family) {
  return valid_case_in<T>({family}, every_convention());
}

/// A valid-looking case of any family, convention and hard place (the picks cover all of them).
template <class T>
rc::Gen<Case<T>> valid_case() {
  return valid_case_in<T>(every_family(), every_convention());
}

/// An input that has no answer, or sits next to one that has none.
template <class T>
rc::Gen<InvalidCase<T>> invalid_case_in(std::vector<Family> families,
                                        std::vector<Convention> conventions,
                                        std::vector<Place> places = every_place(),
                                        std::vector<Defect> defects = std::vector<Defect>(
                                            std::begin(all_defects), std::end(all_defects))) {
  return rc::gen::exec([families, conventions, places, defects] {
    InvalidCase<T> out;
    out.defect = *detail::category(defects);
    out.base = *valid_case_in<T>(families, conventions, places);
    Case<T>& c = out.base;
    const Vector4<T> nrm(c.plane.x(), c.plane.y(), c.plane.z(), T(0));
    switch (out.defect) {
      case Defect::camera_in_front: {
        const T choices[] = {T(0), T(-0.0), nrm.norm(), nrm.norm() * std::ldexp(T(1), -40)};
        c.plane.w() = choices[*rc::gen::inRange(0, 4)];
        break;
      }
      case Defect::misses_view_volume: {
        // With the near plane (u, d), |u| = 1, the volume has u . p + d >= 0. Keep instead
        // u . p <= -(2 |d| + 1): behind the camera, outside the near plane. For a finite volume
        // with far plane (v, e), keep v . p + e <= -(|e| / 2 + 1): beyond the far plane.
        // Either way C_w < 0, so the camera stays behind C.
        const Vector4<T> far = far_plane<T>(c.matrix, c.convention);
        const Vector4<T> near = near_plane<T>(c.matrix, c.convention);
        const bool beyond_far =
            *rc::gen::inRange(0, 2) == 1 && far.template head<3>().norm() > T(0);
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
        const int row = *rc::gen::inRange(0, 4), factor = *rc::gen::inRange(0, 3);
        c.matrix.row(row) = T(factor) * c.matrix.row((row + 1) % 4);
        break;
      }
      case Defect::near_singular: {
        const int k = std::numeric_limits<T>::digits - 12 + *rc::gen::inRange(0, 16);
        c.matrix.row(2) = c.matrix.row(3) + std::ldexp(T(1), -k) * c.matrix.row(2);
        break;
      }
      case Defect::non_finite: {
        const T values[] = {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                            -std::numeric_limits<T>::infinity()};
        const T value = values[*rc::gen::inRange(0, 3)];
        const int index = *rc::gen::inRange(0, 20);
        if (index < 16) {
          c.matrix(index / 4, index % 4) = value;
        } else {
          c.plane(index - 16) = value;
        }
        break;
      }
    }
    return out;
  });
}

/// An input of any family and convention that has no answer, or sits next to one that has none.
template <class T>
rc::Gen<InvalidCase<T>> invalid_case() {
  return invalid_case_in<T>(every_family(), every_convention());
}

/// C scaled to a unit normal (in long double, rounded once), as engines build planes; a plane
/// with a non-finite entry or a zero normal is left as it is.
template <class T>
Vector4<T> unit_normal(const Vector4<T>& c) {
  if (!all_finite(c)) return c;
  const Vector4<long double> wide = c.template cast<long double>();
  const long double norm = wide.template head<3>().norm();
  if (!(norm > 0) || !std::isfinite(norm)) return c;
  return (wide / norm).template cast<T>();
}

/// A valid-looking case of a resolved contract (oblique::resolved()): its families, conventions
/// and places, the plane scaled to a unit normal when its planes are unit.
template <class T>
rc::Gen<Case<T>> valid_case_for(const Contract& contract) {
  return rc::gen::map(valid_case_in<T>(contract.families, contract.conventions, contract.places),
                      [unit = contract.planes == Planes::unit](Case<T> c) {
                        if (unit) c.plane = unit_normal(c.plane);
                        return c;
                      });
}

/// An input without an answer (or next to one) of a resolved contract: one of its defects on a
/// case of valid_case_for().
template <class T>
rc::Gen<InvalidCase<T>> invalid_case_for(const Contract& contract) {
  return rc::gen::map(invalid_case_in<T>(contract.families, contract.conventions, contract.places,
                                         contract.defects),
                      [unit = contract.planes == Planes::unit](InvalidCase<T> ic) {
                        if (unit) ic.base.plane = unit_normal(ic.base.plane);
                        return ic;
                      });
}

/// The generators oblique::generators compiles (cases/generators.cpp), for T = float, double
/// and long double: `declare` is `template` there and `extern template` in a program that links
/// them (OBLIQUE_LINKED_GENERATORS, which the oblique::generators target sets).
#define OBLIQUE_GENERATOR_INSTANCES(declare, T)                                                    \
  declare rc::Gen<Matrix4<T>> projection<T>(Family, Convention, int);                              \
  declare rc::Gen<Vector4<T>> plane<T>(const Matrix4<T>&, Convention, Place);                      \
  declare rc::Gen<Case<T>> valid_case_in<T>(std::vector<Family>, std::vector<Convention>,          \
                                            std::vector<Place>);                                   \
  declare rc::Gen<Case<T>> valid_case_of<T>(Family);                                               \
  declare rc::Gen<Case<T>> valid_case<T>();                                                        \
  declare rc::Gen<InvalidCase<T>> invalid_case_in<T>(std::vector<Family>, std::vector<Convention>, \
                                                     std::vector<Place>, std::vector<Defect>);     \
  declare rc::Gen<InvalidCase<T>> invalid_case<T>();                                               \
  declare rc::Gen<Case<T>> valid_case_for<T>(const Contract&);                                     \
  declare rc::Gen<InvalidCase<T>> invalid_case_for<T>(const Contract&);

#if defined(OBLIQUE_LINKED_GENERATORS) && !defined(OBLIQUE_CHECKER_HEADER_ONLY)
OBLIQUE_GENERATOR_INSTANCES(extern template, float)
OBLIQUE_GENERATOR_INSTANCES(extern template, double)
OBLIQUE_GENERATOR_INSTANCES(extern template, long double)
#endif

}  // namespace oblique::generators

namespace oblique::generators {

/// How RapidCheck shows a case: every number so that it reads back to the same value.
template <class T>
void showValue(const Case<T>& c, std::ostream& os) {
  os << family_name(c.family) << " " << convention_name(c.convention) << " " << place_name(c.place)
     << "\nM = [";
  for (int i = 0; i < 16; ++i)
    os << (i ? (i % 4 ? ", " : "; ") : "") << protocol::format_number(c.matrix(i / 4, i % 4));
  os << "]\nC = (";
  for (int i = 0; i < 4; ++i) os << (i ? ", " : "") << protocol::format_number(c.plane(i));
  os << ")";
}

template <class T>
void showValue(const InvalidCase<T>& c, std::ostream& os) {
  os << defect_name(c.defect) << ": ";
  showValue(c.base, os);
}

inline void showValue(Family f, std::ostream& os) {
  os << family_name(f);
}
inline void showValue(Place p, std::ostream& os) {
  os << place_name(p);
}
inline void showValue(Defect d, std::ostream& os) {
  os << defect_name(d);
}

}  // namespace oblique::generators

namespace oblique {

inline void showValue(Convention c, std::ostream& os) {
  os << convention_name(c);
}

}  // namespace oblique
