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

#include "oblique/oblique.h"
#include "oblique/properties/judge.h"
#include "oblique/properties/seeded_recipes.h"
#include "oblique/properties/tolerance.h"

namespace oblique::properties {

template <class T>
struct Implementation {
  std::string name;
  /// Whether it answers statuses (the recipes return a matrix whatever the input).
  bool reports_statuses = true;
  /// Whether it refuses in its own words (a bool "no"): any refusal of an input without an answer
  /// is then right (StatusContract::any_refusal).
  bool own_refusals = false;
  /// The inputs it is meant for; others are not given to it.
  std::function<bool(Convention, const Matrix4<T>&)> accepts;
  std::function<Outcome<T>(const Matrix4<T>&, const Vector4<T>&, Convention)> run;
  /// The accuracy it promises in ulps of the correctly rounded answer (exact::ulp_distance);
  /// infinity for none beyond the conditioning-aware bounds.
  double max_ulps = std::numeric_limits<double>::infinity();

  /// How judge() treats its statuses.
  StatusContract status_contract() const {
    if (!reports_statuses) return StatusContract::answers_only;
    return own_refusals ? StatusContract::any_refusal : StatusContract::exact;
  }
  /// What judge() checks of its answers: every property under its status contract and, with
  /// `accuracy`, row 3 within its bound and the ulps it promises.
  Checks checks(bool accuracy = false) const {
    Checks out;
    out.statuses = status_contract();
    out.row3_accuracy = accuracy;
    if (accuracy) out.max_ulps = max_ulps;
    return out;
  }
};

namespace mutants {

/// The core's general method with one planted fault, through its corner-sign seam
/// (detail::general's CornerRule).
enum class Fault {
  signs_from_c,      ///< the corner's x, y signs from C instead of C' (Listing 5.1's shortcut)
  wrong_face,        ///< the far corner on the wrong depth face
  sign_by_division,  ///< sgn(x) computed as x / |x|, NaN at 0
  no_camera_check,   ///< no C_w < 0 check
  /// The corner's x sign from C (y's from C'): on the perspective shape C'_x = C_x / M11, so this
  /// is sgn(C'_x) with the sign of M11 ignored, wrong only for a mirror camera (M11 < 0).
  x_sign_from_c,
};

/// detail::TrustedCornerSigns with `fault` planted: the same trusted components of C' (a rounded
/// zero counts as zero), then their signs taken wrongly.
struct PlantedCornerRule {
  Fault fault;

  bool checks_camera() const noexcept { return fault != Fault::no_camera_check; }

  template <class T>
  Vector4<T> corner_signs(const Vector4<T>& plane, const Vector4<T>& c_clip,
                          const Vector4<T>& error_bound) const {
    // C'_i where its sign is trusted, else 0.
    const Vector4<T> trusted = detail::TrustedCornerSigns::corner_signs(plane, c_clip, error_bound)
                                   .cwiseAbs()
                                   .cwiseProduct(c_clip);
    const auto sgn = [this](T x) {
      return fault == Fault::sign_by_division ? x / std::abs(x) : detail::sign(x);
    };
    const bool from_c = fault == Fault::signs_from_c;
    const bool x_from_c = from_c || fault == Fault::x_sign_from_c;
    const T z_sign = fault == Fault::wrong_face ? -sgn(trusted.z()) : sgn(trusted.z());
    return Vector4<T>(sgn(x_from_c ? plane.x() : trusted.x()),
                      sgn(from_c ? plane.y() : trusted.y()), z_sign, T(0));
  }
};

/// The general method with `fault` planted, behind apply()'s input checks.
template <class T>
ObliqueResult<T> with_fault(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                            Fault fault) {
  if (!all_finite(m) || !all_finite(c))
    return detail::refuse(m, Method::general, Status::invalid_input);
  if (magnitude_spread(m) > max_magnitude_spread<T>())
    return detail::refuse(m, Method::general, Status::out_of_range);
  return detail::general(m, c, convention, PlantedCornerRule{fault});
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

/// The core's general method with one planted fault, as an implementation named NAME.
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
