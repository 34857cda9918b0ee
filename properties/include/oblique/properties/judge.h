// One verdict on one answer: the status contract first, then every property.
#pragma once

#include <algorithm>
#include <string>

#include "oblique/properties/implementations.h"
#include "oblique/properties/properties.h"

namespace oblique::properties {

/// The first thing the outcome violates ("status", a property's name, or "row3_accuracy" when
/// `check_accuracy` asks for the third row to be within its bound of the exact answer, and
/// "accurate_ulps" when it also misses the implementation's own max_ulps), or "".
/// A status outside acceptable_statuses() violates the contract for implementations that report
/// statuses; for those that do not, only an ok answer to an input without one does.
template <class T>
std::string first_violation(const Problem<T>& problem, const Implementation<T>& impl,
                            const Outcome<T>& outcome, bool check_accuracy = false) {
  const auto acceptable = problem.acceptable_statuses();
  const bool allowed =
      std::find(acceptable.begin(), acceptable.end(), outcome.status) != acceptable.end();
  if (!allowed && (impl.reports_statuses || outcome.status == Status::ok)) return "status";
  if (outcome.status != Status::ok || problem.exact_status() != Status::ok) return "";
  const Verdicts verdicts = problem.check(outcome.projection);
  if (const Verdict* v = verdicts.first_failure()) return std::string(property_name(v->property));
  if (!problem.check_extracted_planes(outcome.projection).holds) return "extracted_planes_match";
  if (check_accuracy && !problem.compare_row3(outcome.projection).within) return "row3_accuracy";
  if (check_accuracy && problem.ulps_from_exact(outcome.projection) > impl.max_ulps)
    return "accurate_ulps";
  return "";
}

}  // namespace oblique::properties
