// The numerical routes (numerical_routes.h): their words, and each computed in T through the
// model of the computation (variant.h) with the route's one step in between.
#include "oblique/mistakes/numerical_routes.h"

#include <stdexcept>

#include "variant.h"

namespace oblique::mistakes {

namespace {

// clang-format off
constexpr NumericalRouteEntry kRoutes[] = {
    {NumericalRoute::reversed_z_through_zero_one, "reversed_z_through_zero_one",
     "reversed Z computed on the [0, 1] matrix and flipped back",
     "The code turns the reversed-Z matrix into a [0, 1] one (row 3 M_4 - M_3), modifies that and "
     "flips back (M'_3 = M_4 - the [0, 1] row 3). Row 3 of the [0, 1] matrix, formed in T, is "
     "about -1 - n / (f - n): of its n / (f - n), which is all Q_w depends on, T keeps only the "
     "bits below 1's last one: Q_w, and the scale a with it, lose as many bits as f / n has. In "
     "float, for a plane halfway out, a C is off by 0.0074% at f / n = 10^4, 0.06% at 10^5 and "
     "2% at 10^6: the far plane misses Q.",
     "Modify the reversed-Z matrix as it is (its near row M_4 - M_3, its far face z = 0, "
     "M'_3 = M_4 - a C with a = 1 / (C . Q)), as the core does: M_3's small entries are then used "
     "as they are, never added to 1.",
     "reversed-Z matrices with a large far / near ratio (float: 10^3 and beyond)"},
    {NumericalRoute::far_corner_as_point, "far_corner_as_point",
     "the far corner taken as a point Q / Q_w",
     "The code turns the far corner into a point, Q / Q_w (as when it unprojects the corner of "
     "the far face to camera space), and scales C by a = k (M_4 . Q) / (C . Q) on it. That is "
     "right wherever Q_w != 0, but for an infinite far plane the corner is at infinity, Q_w = 0: "
     "the division gives infinities and 0 / 0, and the whole row 3 becomes NaN.",
     "Keep Q homogeneous, Q = M^-1 Q' with Q' = (sgn C'_x, sgn C'_y, z, 1), and a = k / (C . Q): "
     "C . Q is finite (and positive) where the point is not.",
     "matrices with an infinite far plane (Q_w = 0)"},
};
// clang-format on

}  // namespace

const NumericalRouteEntry& numerical_route_entry(NumericalRoute route) {
  for (const NumericalRouteEntry& e : kRoutes) {
    if (e.route == route) return e;
  }
  throw std::logic_error("a numerical route without an entry");
}

template <class T>
RouteAnswer<T> route_answer(NumericalRoute route, const Matrix4<T>& m, const Vector4<T>& c,
                            Convention convention) {
  RouteAnswer<T> out;
  out.projection = out.modified = m;
  out.modified_convention = convention;
  auto careful = [&m, convention](const Matrix4<T>& matrix, const variant::Evaluation<T>& e) {
    RouteAnswer<T> a;
    a.status = e.status;
    a.projection = e.status == Status::ok ? variant::answer_matrix(matrix, e) : matrix;
    a.modified = m;
    a.modified_convention = convention;
    return a;
  };
  switch (route) {
    case NumericalRoute::reversed_z_through_zero_one: {
      if (convention != Convention::reversed_z)
        return careful(m, variant::evaluate<T>(m, c, convention, variant::Knobs{}));
      Matrix4<T> zero_one = m;
      zero_one.row(2) = m.row(3) - m.row(2);  // the step: about -1 - n / (f - n), rounded in T
      const auto e = variant::evaluate<T>(zero_one, c, Convention::zero_one, variant::Knobs{});
      RouteAnswer<T> flipped = careful(zero_one, e);
      if (flipped.status != Status::ok) {
        flipped.projection = m;
        return flipped;
      }
      out.projection.row(2) = m.row(3) - flipped.projection.row(2);
      out.modified = zero_one;
      out.modified_convention = Convention::zero_one;
      return out;
    }
    case NumericalRoute::far_corner_as_point: {
      variant::Evaluation<T> e = variant::evaluate<T>(m, c, convention, variant::Knobs{});
      if (e.status != Status::ok || e.unchanged || e.non_finite) return careful(m, e);
      // The step: Q / Q_w, then a = k (M_4 . Q) / (C . Q) on the point.
      T point[4], m4q = 0, cq = 0;
      for (int i = 0; i < 4; ++i) point[i] = e.q[i] / e.q[3];
      for (int i = 0; i < 4; ++i) {
        m4q += m(3, i) * point[i];
        cq += e.c[i] * point[i];
      }
      e.a = T(e.choices.numerator) * m4q / cq;
      return careful(m, e);
    }
  }
  return out;
}

template RouteAnswer<float> route_answer<float>(NumericalRoute, const Matrix4<float>&,
                                                const Vector4<float>&, Convention);
template RouteAnswer<double> route_answer<double>(NumericalRoute, const Matrix4<double>&,
                                                  const Vector4<double>&, Convention);
template RouteAnswer<long double> route_answer<long double>(NumericalRoute,
                                                            const Matrix4<long double>&,
                                                            const Vector4<long double>&,
                                                            Convention);

}  // namespace oblique::mistakes
