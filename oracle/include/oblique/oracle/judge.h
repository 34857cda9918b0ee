// The one judgement of one answer: the status contract first, then the properties, then (when
// asked) the third row's accuracy. The property suite, `oblique verify`, the fuzz targets and
// `oblique check` all judge through judge().
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "oblique/oracle/finding.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/vocabulary.h"
#include "oblique/protocol/numbers.h"

namespace oblique::oracle {

/// not_judged() for `problem` (a Problem<T> or a FilteredProblem<T>).
template <class AnyProblem>
std::string not_judged(const AnyProblem& problem, StatusContract contract,
                       const std::vector<Status>& refusals = {}) {
  using T = typename std::decay_t<decltype(problem.matrix())>::Scalar;
  if (has_every_refusal(contract, refusals)) return "";  // (no status asked of the problem)
  return not_judged<T>(problem.exact_status(), problem.acceptable_statuses(), contract, refusals);
}

namespace judging {

/// The status finding for `got` (or nothing when the contract allows it), given the input's
/// exact status and the statuses it allows.
inline std::optional<Finding> status_finding(Status exact, const std::vector<Status>& acceptable,
                                             Status got, StatusContract contract) {
  if (std::find(acceptable.begin(), acceptable.end(), got) != acceptable.end()) {
    return std::nullopt;
  }
  if (got != Status::ok) {
    if (contract == StatusContract::answers_only) return std::nullopt;
    // any_refusal: a refusal in the implementation's own words is right wherever the input
    // allows some refusal (it has no answer, or rounding allows one).
    const bool some_refusal_allowed =
        exact != Status::ok ||
        std::any_of(acceptable.begin(), acceptable.end(), [](Status s) { return s != Status::ok; });
    if (contract == StatusContract::any_refusal && some_refusal_allowed) return std::nullopt;
  }
  Finding f;
  f.check = Check::status;
  f.shows = Shows::statuses;
  f.answered = got;
  f.exact = exact;
  f.allowed = acceptable;
  return f;
}

/// The status finding for `got` on `problem`.
template <class T>
std::optional<Finding> status_finding(const Problem<T>& problem, Status got,
                                      StatusContract contract) {
  return status_finding(problem.exact_status(), problem.acceptable_statuses(), got, contract);
}

template <class T>
Finding row3_accuracy(const Problem<T>& problem, const Matrix4<T>& result) {
  const auto closeness = problem.compare_row3(result);
  Finding f;
  f.check = Check::row3_accuracy;
  f.holds = closeness.within;
  f.ratio = closeness.ratio;
  const std::optional<oracle::exact::Vec> bounds = problem.row3_bounds();
  if (!bounds) {
    f.shows = Shows::no_bound;
    return f;
  }
  const int i = closeness.worst_entry;
  const oracle::exact::Vec expected = problem.exact_row3();
  f.shows = Shows::entry;
  f.row = 3;
  f.column = i + 1;
  f.value = static_cast<double>(result(2, i));
  f.reference = expected[i].get_d();
  f.residual = oracle::exact::Rational(
                   oracle::exact::abs(oracle::exact::to_rational(result(2, i)) - expected[i]))
                   .get_d();
  f.bound = (*bounds)[i].get_d();
  return f;
}

}  // namespace judging

/// Judges what an implementation answered for the input `problem` describes:
///  1. the status (Checks::statuses);
///  2. an ok answer is finite ("finite_result"; the judgement ends at a non-finite one);
///  3. where the input has an exact answer: the selected properties (Problem::check(), and
///     Problem::check_extracted_planes()), row 3's accuracy, the ulps promise.
/// An ok answer to an input within rounding of having none is judged by 1 and 2 only.
template <class T>
Judgement judge(const Problem<T>& problem, const Answer<T>& outcome, const Checks& checks = {}) {
  Judgement out;
  // Records a check; true when the judgement goes on.
  auto record = [&](Finding f) {
    const bool go_on = f.holds || checks.every;
    out.checks.push_back(std::move(f));
    return go_on;
  };
  if (auto f = judging::status_finding(problem, outcome.status, checks.statuses)) {
    if (!record(std::move(*f))) return out;
  }
  if (outcome.status != Status::ok) return out;
  if (!all_finite(outcome.projection)) {
    // Nothing further is judged, even with Checks::every: the exact checks take finite entries.
    Finding f;
    f.check = Check::finite_result;
    f.shows = Shows::non_finite_answer;
    record(std::move(f));
    return out;
  }
  if (problem.exact_status() != Status::ok) return out;
  auto wanted = [&](Property p) {
    return std::find(checks.properties.begin(), checks.properties.end(), p) !=
           checks.properties.end();
  };
  const bool any_of_the_five = std::any_of(std::begin(all_properties), std::end(all_properties),
                                           [&](Property p) { return wanted(p); });
  if (any_of_the_five) {
    const Verdicts verdicts = problem.check(outcome.projection);
    for (const Verdict& v : verdicts.items) {
      if (!v.applies || !wanted(v.property())) continue;
      if (!record(v)) return out;  // a Verdict is its Finding
    }
  }
  if (wanted(Property::extracted_planes_match)) {
    if (!record(problem.check_extracted_planes(outcome.projection))) return out;
  }
  if (checks.row3_accuracy) {
    if (!record(judging::row3_accuracy(problem, outcome.projection))) return out;
  }
  if (checks.max_ulps < std::numeric_limits<double>::infinity()) {
    const double ulps = problem.ulps_from_exact(outcome.projection);
    Finding f;
    f.check = Check::accurate_ulps;
    f.holds = ulps <= checks.max_ulps;
    f.residual = ulps;
    f.bound = checks.max_ulps;
    f.ratio = ulps / checks.max_ulps;
    record(std::move(f));
  }
  return out;
}

}  // namespace oblique::oracle
