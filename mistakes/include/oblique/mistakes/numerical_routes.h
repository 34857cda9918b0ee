// Numerical causes: the correct modification evaluated in the program's precision along a route
// that loses the bits careful code keeps. The formula is right (in exact arithmetic each route
// gives the correct answer wherever it is defined); one step, rounded in T, cancels or divides by
// a value that is 0 or nearly so. diagnose() (diagnosis.h) names a route where no formula mistake
// reproduces the answers and the route, computed in T, does. Compiled in oblique::mistakes.
#pragma once

#include <string_view>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique::mistakes {

enum class NumericalRoute {
  /// reversed Z computed on the [0, 1] matrix (row 3 M_4 - M_3, formed in T) and flipped back
  reversed_z_through_zero_one,
  /// the far corner as a point Q / Q_w, a = k (M_4 . Q) / (C . Q) on it
  far_corner_as_point,
};

inline constexpr NumericalRoute all_numerical_routes[] = {
    NumericalRoute::reversed_z_through_zero_one,
    NumericalRoute::far_corner_as_point,
};

struct NumericalRouteEntry {
  NumericalRoute route;
  std::string_view name;     ///< "reversed_z_through_zero_one"
  std::string_view title;    ///< a short phrase
  std::string_view step;     ///< the step that loses the bits, and why
  std::string_view rewrite;  ///< the rewrite that keeps them
  std::string_view shows;    ///< the inputs where the loss shows
};

const NumericalRouteEntry& numerical_route_entry(NumericalRoute route);

/// The route's answer on (M, C) in `convention`, every step rounded in T: a status, and for ok
/// the matrix (non-finite where a step divides by 0). Precondition: M and C finite.
template <class T>
struct RouteAnswer {
  Status status = Status::ok;
  Matrix4<T> projection = Matrix4<T>::Identity();
  /// The matrix and convention the route modifies carefully (the converted one, for a route
  /// between conventions): two careful programs may differ there by its rounding bound.
  Matrix4<T> modified = Matrix4<T>::Identity();
  Convention modified_convention = Convention::gl;
};

template <class T>
RouteAnswer<T> route_answer(NumericalRoute route, const Matrix4<T>& matrix, const Vector4<T>& plane,
                            Convention convention);

extern template RouteAnswer<float> route_answer<float>(NumericalRoute, const Matrix4<float>&,
                                                       const Vector4<float>&, Convention);
extern template RouteAnswer<double> route_answer<double>(NumericalRoute, const Matrix4<double>&,
                                                         const Vector4<double>&, Convention);
extern template RouteAnswer<long double> route_answer<long double>(NumericalRoute,
                                                                   const Matrix4<long double>&,
                                                                   const Vector4<long double>&,
                                                                   Convention);

}  // namespace oblique::mistakes
