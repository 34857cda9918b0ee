// What apply() is asked for and what it answers: the method that finds the far corner, and the
// result (status, matrix, far corner, method that ran); an Answer, what every judge reads of any
// implementation's answer.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "oblique/plane.h"
#include "oblique/status.h"
#include "oblique/util/enum_names.h"

namespace oblique {

/// How the far corner Q is found.
enum class Method {
  automatic,    ///< closed_form when the matrix has the standard perspective shape, else general
  closed_form,  ///< Q from the matrix entries, no solve; standard perspective shape only
  general,      ///< C' = M^-T C and Q = M^-1 Q' by one LU factorisation; any invertible M
  accurate,     ///< any invertible M, each entry of M'_3 within an ulp or two of the exact answer
                ///< (accurate/accurate.h); closed-form solves for the perspective shape
};

inline constexpr EnumName<Method> method_names[] = {
    {Method::automatic, "auto"},
    {Method::closed_form, "closed_form"},
    {Method::general, "general"},
    {Method::accurate, "accurate"},
};
inline constexpr auto all_methods = values_in(method_names);

constexpr std::string_view method_name(Method value) noexcept {
  return name_in(method_names, value);
}
/// Inverse of method_name(); none for an unknown name.
constexpr std::optional<Method> parse_method(std::string_view name) noexcept {
  return value_in(method_names, name);
}

template <class T>
struct [[nodiscard]] ObliqueResult {
  Status status = Status::ok;
  /// A more specific reason than status_message(status); empty when there is none.
  std::string_view detail;
  /// M' when ok; otherwise the input matrix, unchanged.
  Matrix4<T> projection;
  /// Q = M^-1 Q' in camera space (a direction, w = 0, for infinite projections); set when the
  /// computation got that far (ok, plane_misses_view_volume, out_of_range), else zero.
  Vector4<T> far_corner = Vector4<T>::Zero();
  /// The method that ran: closed_form or general (automatic resolved), accurate where one of them
  /// handed a stiff input to it, or what was asked for if the request was refused before one
  /// ran.
  Method method = Method::automatic;

  bool ok() const noexcept { return status == Status::ok; }
  std::string_view message() const noexcept {
    return detail.empty() ? status_message(status) : detail;
  }
};

/// What an implementation answered for one input, as every judge reads it: apply()'s result
/// (an ObliqueResult converts), a user's function's, or a program's answer line read back.
template <class T>
struct Answer {
  Status status = Status::ok;
  Matrix4<T> projection = Matrix4<T>::Zero();  ///< M' when ok
  std::string message;                         ///< a refusal's own words, when it gave some

  Answer() = default;
  Answer(Status s, const Matrix4<T>& m, std::string words = {})
      : status(s), projection(m), message(std::move(words)) {}
  Answer(const ObliqueResult<T>& r)  // NOLINT(google-explicit-constructor): apply()'s answer
      : status(r.status), projection(r.projection), message(r.detail) {}
};

}  // namespace oblique
