// The implementations the property suite can judge: the core's methods (the default), the
// formulas printed in the source documents, and the catalogue's mistakes (mistakes.h) planted in
// the general method, which show the suite catches the mistakes engines ship. OBLIQUE_IMPL=name
// selects one; see the README.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/cases/seeded_recipes.h"
#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"
#include "oblique/oracle/implementation.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/tolerance.h"

namespace oblique::mistakes {

using oracle::Implementation;

template <class T>
Implementation<T> core_method(Method method) {
  Implementation<T> impl;
  impl.name = std::string("core_") + std::string(method_name(method));
  impl.accepts = [method](Convention, const Matrix4<T>& m) {
    return method != Method::closed_form || has_perspective_shape(m);
  };
  impl.run = [method](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = apply<T>(m, c, convention, method);
    return Answer<T>{r.status, r.projection};
  };
  if (method == Method::accurate) impl.max_ulps = oracle::tolerance::kAccurateUlps;
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
    return Answer<T>{Status::ok, formula(m, c)};
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
      [](const Matrix4<T>& m, const Vector4<T>& c) { return cases::listing_5_1(m, c); }));
  out.push_back(recipe<T>(
      "paper_eq_20", [](Convention c, const Matrix4<T>&) { return c == Convention::gl; },
      [](const Matrix4<T>& m, const Vector4<T>& c) { return cases::paper_eq_20(m, c); }));
  out.push_back(recipe<T>(
      "note_zero_one", [](Convention c, const Matrix4<T>&) { return c == Convention::zero_one; },
      [](const Matrix4<T>& m, const Vector4<T>& c) { return cases::note_zero_one(m, c); }));
  out.push_back(recipe<T>(
      "note_reversed", [](Convention c, const Matrix4<T>&) { return c == Convention::reversed_z; },
      [](const Matrix4<T>& m, const Vector4<T>& c) {
        // The flip is its own inverse (with w kept): forward = flip * M.
        return cases::note_reversed(Matrix4<T>(cases::depth_flip<T>() * m), c,
                                    cases::note_flip_as_printed<T>());
      }));
  // The catalogue's mistakes (mistakes.h), each planted in the general method: the suite must
  // catch each, and its report name the mistake.
  for (Mistake m : all_mistakes) out.push_back(mistaken_implementation<T>({m}));
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

}  // namespace oblique::mistakes
