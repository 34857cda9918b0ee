// The implementations the property suite can judge: the core's methods (the default), the
// formulas printed in the source documents, and deliberately broken cores (mutants) that show
// the suite catches the mistakes engines ship. OBLIQUE_IMPL=name selects one; see the README.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/LU>

#include "oblique/oblique.h"
#include "oblique/properties/implementation.h"
#include "oblique/properties/judge.h"
#include "oblique/properties/seeded_recipes.h"
#include "oblique/properties/tolerance.h"

namespace oblique::properties {

namespace mutants {

/// A fault planted in the general method. Each mutant is apply()'s general method, wrapped: where
/// its fault changes nothing (the signs it would take are sgn(C')), it answers what apply()
/// answers; elsewhere it answers the textbook modification on the corner its fault picks.
enum class Fault {
  signs_from_c,      ///< the corner's x, y signs from C instead of C' (Listing 5.1's shortcut)
  wrong_face,        ///< the far corner on the wrong depth face
  sign_by_division,  ///< sgn(x) computed as x / |x|, NaN at 0
  no_camera_check,   ///< no C_w < 0 check
  /// The corner's x sign from C (y's from C'): on the perspective shape C'_x = C_x / M11, so this
  /// is sgn(C'_x) with the sign of M11 ignored, wrong only for a mirror camera (M11 < 0).
  x_sign_from_c,
};

/// The clip-space corner's x, y, z signs the faulty method takes, from C' = M^-T C and C.
template <class T>
Vector4<T> planted_signs(const Vector4<T>& plane, const Vector4<T>& c_clip, Fault fault) {
  const auto sgn = [fault](T x) {
    return fault == Fault::sign_by_division ? x / std::abs(x) : seeded::sgn(x);
  };
  const bool from_c = fault == Fault::signs_from_c;
  const bool x_from_c = from_c || fault == Fault::x_sign_from_c;
  const T z = fault == Fault::wrong_face ? -sgn(c_clip.z()) : sgn(c_clip.z());
  return Vector4<T>(sgn(x_from_c ? plane.x() : c_clip.x()), sgn(from_c ? plane.y() : c_clip.y()), z,
                    T(0));
}

/// The general method with `fault` planted. Where the fault matters (apply() answers or refuses
/// with plane_misses_view_volume and the planted signs differ from sgn(C'), C' solved by
/// partial-pivoting LU in T as an engine solves it; or C_w >= 0 for no_camera_check) the answer
/// is the modification on the planted corner, as an engine writes it:
///   Q = M^-1 Q', a = (z_high - z_low) / (C . Q), M'_3 = s (a C - t M_4)
/// (near_rows(convention): near = s M_3 + t M_4, s = +-1), refused as plane_misses_view_volume
/// when C . Q <= 0; a NaN C . Q (sign_by_division's corner) goes through, as in an engine.
template <class T>
ObliqueResult<T> with_fault(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                            Fault fault) {
  ObliqueResult<T> r = apply<T>(m, c, convention, Method::general);
  const bool unchecked_camera =
      fault == Fault::no_camera_check && r.status == Status::camera_not_behind_plane;
  // The statuses that depend on the corner (C . Q > 0) are the fault's to change, too.
  if (r.status != Status::ok && r.status != Status::plane_misses_view_volume && !unchecked_camera)
    return r;
  const Eigen::PartialPivLU<Matrix4<T>> lu(m);
  const Vector4<T> c_clip = lu.transpose().solve(c);
  const Vector4<T> signs = planted_signs(c, c_clip, fault);
  const bool as_apply = signs.x() == seeded::sgn(c_clip.x()) &&
                        signs.y() == seeded::sgn(c_clip.y()) &&
                        signs.z() == seeded::sgn(c_clip.z());
  if (as_apply && !unchecked_camera) return r;
  const DepthRange range = clip_depth_range(convention);
  const T z = signs.z() > T(0)   ? T(range.z_high)
              : signs.z() < T(0) ? T(range.z_low)
                                 : T(range.z_low + range.z_high) / T(2);
  const Vector4<T> q = lu.solve(Vector4<T>(signs.x(), signs.y(), z, T(1)));
  const T d = c.dot(q);
  r.projection = m;
  r.far_corner = q;
  if (d <= T(0)) {
    r.status = Status::plane_misses_view_volume;
    return r;
  }
  const RowCombination near = near_rows(convention);
  const T a = T(range.z_high - range.z_low) / d;
  const Vector4<T> m4 = m.row(3).transpose();
  r.projection.row(2) = (T(near.m3) * (a * c - T(near.m4) * m4)).transpose();
  r.status = Status::ok;
  return r;
}

}  // namespace mutants

template <class T>
Implementation<T> core_method(Method method) {
  Implementation<T> impl;
  impl.name = std::string("core_") + std::string(method_name(method));
  impl.accepts = [method](Convention, const Matrix4<T>& m) {
    return method != Method::closed_form || has_perspective_shape(m);
  };
  impl.run = [method](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = apply<T>(m, c, convention, method);
    return Outcome<T>{r.status, r.projection};
  };
  if (method == Method::accurate) impl.max_ulps = tolerance::kAccurateUlps;
  return impl;
}

/// The general method with one planted fault (mutants::with_fault), as the implementation NAME.
template <class T>
Implementation<T> planted_mutant(std::string name, mutants::Fault fault) {
  Implementation<T> impl;
  impl.name = std::move(name);
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.run = [fault](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = mutants::with_fault(m, c, convention, fault);
    return Outcome<T>{r.status, r.projection};
  };
  return impl;
}

template <class T>
Implementation<T> recipe(std::string name,
                         std::function<bool(Convention, const Matrix4<T>&)> accepts,
                         std::function<Matrix4<T>(const Matrix4<T>&, const Vector4<T>&)> formula) {
  Implementation<T> impl;
  impl.name = std::move(name);
  impl.reports_statuses = false;
  impl.accepts = std::move(accepts);
  impl.run = [formula](const Matrix4<T>& m, const Vector4<T>& c, Convention) {
    return Outcome<T>{Status::ok, formula(m, c)};
  };
  return impl;
}

/// Every implementation the suite knows, by name.
template <class T>
std::vector<Implementation<T>> known_implementations() {
  std::vector<Implementation<T>> out;
  for (Method m : all_methods) out.push_back(core_method<T>(m));
  out.push_back(recipe<T>(
      "listing_5_1",
      [](Convention c, const Matrix4<T>& m) {
        return c == Convention::gl && has_perspective_shape(m);
      },
      [](const Matrix4<T>& m, const Vector4<T>& c) { return seeded::listing_5_1(m, c); }));
  out.push_back(recipe<T>(
      "paper_eq_20", [](Convention c, const Matrix4<T>&) { return c == Convention::gl; },
      [](const Matrix4<T>& m, const Vector4<T>& c) { return seeded::paper_eq_20(m, c); }));
  out.push_back(recipe<T>(
      "note_zero_one", [](Convention c, const Matrix4<T>&) { return c == Convention::zero_one; },
      [](const Matrix4<T>& m, const Vector4<T>& c) { return seeded::note_zero_one(m, c); }));
  out.push_back(recipe<T>(
      "note_reversed", [](Convention c, const Matrix4<T>&) { return c == Convention::reversed_z; },
      [](const Matrix4<T>& m, const Vector4<T>& c) {
        // The flip is its own inverse (with w kept): forward = flip * M.
        return seeded::note_reversed(Matrix4<T>(seeded::depth_flip<T>() * m), c,
                                     seeded::note_flip_as_printed<T>());
      }));
  using mutants::Fault;
  out.push_back(planted_mutant<T>("mutant_signs_from_c", Fault::signs_from_c));
  out.push_back(planted_mutant<T>("mutant_wrong_face", Fault::wrong_face));
  out.push_back(planted_mutant<T>("mutant_sign_by_division", Fault::sign_by_division));
  out.push_back(planted_mutant<T>("mutant_no_camera_check", Fault::no_camera_check));
  {
    // An engine's closed form for the perspective matrices its cameras make, its far corner's x
    // sign taken as sgn(C_x): right while M11 > 0 (C'_x = C_x / M11), wrong for a mirror camera
    // made by negating M11 (generators::Family::x_flipped, xy_flipped).
    Implementation<T> impl = planted_mutant<T>("mutant_ignores_m11_sign", Fault::x_sign_from_c);
    impl.accepts = [](Convention, const Matrix4<T>& m) { return has_perspective_shape(m); };
    out.push_back(impl);
  }
  {
    Implementation<T> impl;  // the [0, 1] factor (a = 1 / C.Q, M'_3 = a C) applied to gl matrices
    impl.name = "mutant_zero_one_factor";
    impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
    impl.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
      const Convention used = convention == Convention::gl ? Convention::zero_one : convention;
      const ObliqueResult<T> r = apply<T>(m, c, used);
      return Outcome<T>{r.status, r.projection};
    };
    out.push_back(impl);
  }
  return out;
}

/// The names OBLIQUE_IMPL selects (comma-separated; default: the core's four methods).
inline std::vector<std::string> selected_implementation_names() {
  const char* env = std::getenv("OBLIQUE_IMPL");
  const std::string wanted =
      env && *env ? env : "core_auto,core_closed_form,core_general,core_accurate";
  std::vector<std::string> names;
  std::string::size_type start = 0;
  while (start <= wanted.size()) {
    const auto end = std::min(wanted.find(',', start), wanted.size());
    if (end > start) names.push_back(wanted.substr(start, end - start));
    start = end + 1;
  }
  return names;
}

/// An error naming each OBLIQUE_IMPL name that is no known implementation (and the known ones),
/// or empty. An unknown name must stop a run, never select nothing and pass.
inline std::string implementation_selection_error() {
  const auto known = known_implementations<double>();
  std::string unknown, names;
  for (const auto& impl : known) names += (names.empty() ? "" : ", ") + impl.name;
  for (const std::string& name : selected_implementation_names()) {
    const bool found = std::any_of(known.begin(), known.end(),
                                   [&](const Implementation<double>& i) { return i.name == name; });
    if (!found) unknown += (unknown.empty() ? "" : ", ") + name;
  }
  if (unknown.empty() && !selected_implementation_names().empty()) return {};
  return "OBLIQUE_IMPL: unknown implementation " + (unknown.empty() ? "(none named)" : unknown) +
         "; known: " + names;
}

/// Whether OBLIQUE_IMPL selects the implementation `name`.
inline bool implementation_selected(std::string_view name) {
  const auto names = selected_implementation_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// The implementations selected by OBLIQUE_IMPL, in the order known_implementations() lists
/// them. Callers check implementation_selection_error() first: an unknown name is an error.
template <class T>
std::vector<Implementation<T>> selected_implementations() {
  std::vector<Implementation<T>> out;
  for (auto& impl : known_implementations<T>()) {
    if (implementation_selected(impl.name)) out.push_back(impl);
  }
  return out;
}

}  // namespace oblique::properties
