// The checker's verdict on one answer, as users see it: a Finding per check, the Judgement that
// lists them, and which inputs an implementation is not judged on (not_judged()). Light: no GMP,
// no checker (oblique/properties/checker.h judges; judge.h is the checker's own judge()).
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "oblique/properties/checks.h"
#include "oblique/protocol/numbers.h"
#include "oblique/status.h"

namespace oblique::properties {

/// One check on one answer: what was compared, both sides, and whether it holds.
struct Finding {
  /// "status", "finite_result", a property's name (property_name()), "row3_accuracy",
  /// "accurate_ulps"; tools add their own ("crash", "timeout", "closed_form_and_general_agree").
  std::string kind;
  bool holds = false;
  std::string relation;  ///< what was compared, in words
  std::string lhs;       ///< the residual side
  std::string rhs;       ///< the bound side
  double ratio = 0;      ///< |residual| / bound: holds at ratio <= 1
  std::string expected;  ///< the statuses the input allows (status findings)
  std::string got;       ///< the status answered (status findings)
};

/// The checks that applied, in order.
struct Judgement {
  std::vector<Finding> checks;

  /// The first check that fails, or nullptr.
  const Finding* violation() const {
    for (const Finding& f : checks) {
      if (!f.holds) return &f;
    }
    return nullptr;
  }
  bool holds() const { return violation() == nullptr; }
};

/// "a or b or c".
inline std::string status_list(const std::vector<Status>& statuses) {
  std::string out;
  for (Status s : statuses) out += (out.empty() ? "" : " or ") + std::string(status_code(s));
  return out;
}

/// Whether an implementation under `contract` has every refusal (nothing is left out for it).
inline bool has_every_refusal(StatusContract contract, const std::vector<Status>& refusals) {
  return contract == StatusContract::any_refusal ||
         (contract == StatusContract::exact && refusals.empty());
}

/// Why an implementation is not judged on an input, or "" when it is: the one rule every tool
/// (the property suite, `oblique verify`, the fuzz driver) leaves inputs out by. An answer is
/// judged only where some reply the implementation can give is right:
///  - an input without an exact answer, when its status is not one the implementation has (it
///    has none under answers_only; under exact, `refusals` lists the ones it has, empty: all);
///  - an input *undecidable at the implementation's precision*: it has an exact answer, but it
///    lies within rounding (in T) of a status boundary (C . Q of zero, a singular M, the end of
///    T's range), so acceptable_statuses() holds a refusal besides ok. A computed C . Q there
///    may have either sign or be zero, the answer may be anything, and only a refusal is right;
///    left out when the implementation has none of the refusals allowed (answers_only: none).
/// any_refusal has every refusal: nothing is left out. What the input is decides, never how it
/// was generated.
template <class T>
std::string not_judged(Status exact, const std::vector<Status>& acceptable, StatusContract contract,
                       const std::vector<Status>& refusals = {}) {
  if (has_every_refusal(contract, refusals)) return "";
  auto has = [&](Status s) {
    return contract == StatusContract::exact &&
           std::find(refusals.begin(), refusals.end(), s) != refusals.end();
  };
  if (exact != Status::ok) {
    if (has(exact)) return "";
    return contract == StatusContract::answers_only
               ? "inputs without an answer"
               : "inputs needing status " + std::string(status_code(exact));
  }
  // The first allowed refusal names the boundary; the input is judged when any is the
  // implementation's.
  std::optional<Status> boundary;
  for (Status s : acceptable) {
    if (s == Status::ok) continue;
    if (has(s)) return "";
    if (!boundary) boundary = s;
  }
  if (!boundary) return "";
  const std::string scalar(protocol::scalar_name<T>());
  const std::string where =
      *boundary == Status::plane_misses_view_volume ? "C . Q within rounding of 0"
      : *boundary == Status::singular_projection    ? "M within rounding of singular"
                                                    : "rounding allows out_of_range";
  return "inputs undecidable in " + scalar + " (" + where + ")";
}

}  // namespace oblique::properties
