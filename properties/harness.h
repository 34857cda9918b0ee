// Runs RapidCheck properties inside GoogleTest tests: tallies what the cases covered (and fails
// a run that missed a hard place), and writes the shrunk counterexample as a report.
#pragma once

#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "oblique/properties/counterexample_report.h"
#include "oblique/properties/filtered.h"
#include "oblique/properties/generators.h"
#include "oblique/properties/implementations.h"
#include "oblique/properties/properties.h"

namespace oblique::properties::suite {

/// What the cases of one property run covered, and its last (so most shrunk) failure.
struct Tally {
  std::map<std::string, int> families, conventions, places, defects, implementations, applied;
  std::optional<Counterexample> failure;
};

inline Tally& tally() {
  static Tally t;
  return t;
}

/// Which kinds of case a run must have covered.
enum class Coverage { valid, infinite_only, perspective_shape, invalid };

inline ReportContext report_context() {
  ReportContext context;
  const char* dir = std::getenv("OBLIQUE_REPORT_DIR");
  context.directory = dir && *dir ? dir : OBLIQUE_REPORT_DIR;
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  context.test_id = std::string(info->test_suite_name()) + "." + info->name();
  context.seed = rc::detail::configuration().testParams.seed;
  context.max_success = rc::detail::configuration().testParams.maxSuccess;
  context.binary = OBLIQUE_PROPERTY_BINARY;
  context.cli = OBLIQUE_CLI;
  return context;
}

inline std::string summary(const std::map<std::string, int>& counts) {
  std::string out;
  for (const auto& [name, count] : counts)
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return out;
}

/// Runs `testable` as a RapidCheck property of the current test; fails the test with the report's
/// path on a counterexample, and when the cases missed a family, convention or hard place.
template <class Testable>
void run(Testable&& testable, Coverage coverage) {
  tally() = Tally{};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  rc::detail::TestMetadata metadata;
  metadata.id = std::string(info->test_suite_name()) + "/" + info->name();
  metadata.description = info->name();
  const auto result = rc::detail::checkTestable(std::forward<Testable>(testable), metadata);
  std::ostringstream message;
  rc::detail::printResultMessage(result, message);
  const Tally& t = tally();
  std::cout << message.str() << "\nran: " << summary(t.implementations)
            << "\nfamilies: " << summary(t.families) << "\nconventions: " << summary(t.conventions)
            << "\nplaces: " << summary(t.places);
  if (!t.defects.empty()) std::cout << "\ndefects: " << summary(t.defects);
  if (!t.applied.empty()) std::cout << "\napplied: " << summary(t.applied);
  std::cout << std::endl;
  if (!result.template is<rc::detail::SuccessResult>()) {
    std::string where;
    if (t.failure) where = "\nreport: " + write_report(*t.failure, report_context());
    FAIL() << message.str() << where;
  }
  if (t.implementations.empty()) {
    FAIL() << "no implementation ran: check OBLIQUE_IMPL (or the generator discarded every case)";
  }
  auto require = [](const std::map<std::string, int>& counts, auto names, const char* what) {
    for (const auto& name : names) {
      EXPECT_GT(counts.count(std::string(name)) ? counts.at(std::string(name)) : 0, 0)
          << "no case covered " << what << " " << name << ": raise max_success";
    }
  };
  std::vector<std::string_view> families, conventions, places, defects;
  for (auto f : generators::all_families) families.push_back(generators::family_name(f));
  for (auto c : all_conventions) conventions.push_back(convention_name(c));
  for (auto p : generators::all_places) places.push_back(generators::place_name(p));
  for (auto d : generators::all_defects) defects.push_back(generators::defect_name(d));
  require(t.conventions, conventions, "convention");
  switch (coverage) {
    case Coverage::valid:
      require(t.families, families, "family");
      require(t.places, places, "hard place");
      break;
    case Coverage::infinite_only:
    case Coverage::perspective_shape: require(t.places, places, "hard place"); break;
    case Coverage::invalid: require(t.defects, defects, "defect"); break;
  }
}

template <class T>
void count_case(const generators::Case<T>& c) {
  Tally& t = tally();
  ++t.families[std::string(generators::family_name(c.family))];
  ++t.conventions[std::string(convention_name(c.convention))];
  ++t.places[std::string(generators::place_name(c.place))];
  RC_TAG(std::string(generators::family_name(c.family)), std::string(convention_name(c.convention)),
         std::string(generators::place_name(c.place)));
}

template <class T>
Counterexample describe(const generators::Case<T>& c, const Implementation<T>& impl) {
  Counterexample ce = make_counterexample(c.matrix, c.plane, c.convention);
  ce.implementation = impl.name;
  ce.family = std::string(generators::family_name(c.family));
  ce.place = std::string(generators::place_name(c.place));
  return ce;
}

/// Fails the current RapidCheck case with `finding` as its report.
template <class T>
void fail_with(const generators::Case<T>& c, const Implementation<T>& impl, const Finding& finding,
               const Outcome<T>* outcome = nullptr) {
  Counterexample ce = describe(c, impl);
  ce.finding = finding;
  if (outcome && outcome->status == Status::ok) set_result(ce, outcome->projection);
  tally().failure = ce;
  if (finding.kind == "status")
    RC_FAIL(impl.name + " answered " + finding.got + ", expected " + finding.expected);
  RC_FAIL(impl.name + " violates " + finding.kind + ": " + finding.lhs + " against " + finding.rhs);
}

/// Runs every selected implementation on the case and judges each answer (judge(), with
/// `checks` and the implementation's own status contract); fails the case on the first violation.
/// An implementation without statuses is judged on inputs without an answer only where invalid
/// inputs are the point (judge_statuses), so its property failures are not masked. `problem` is
/// a Problem<T> or a FilteredProblem<T> (filtered.h: the same verdicts, most without GMP).
template <class T, class AnyProblem>
void for_each_answer(const generators::Case<T>& c, const AnyProblem& problem, Checks checks,
                     bool judge_statuses = false) {
  for (const Implementation<T>& impl : selected_implementations<T>()) {
    if (!impl.accepts(c.convention, c.matrix)) continue;
    if (!impl.reports_statuses && !judge_statuses && problem.exact_status() != Status::ok) continue;
    ++tally().implementations[impl.name];
    const Outcome<T> outcome = impl.run(c.matrix, c.plane, c.convention);
    checks.statuses = impl.status_contract();
    const Judgement judgement = judge(problem, outcome, checks);
    for (const Finding& f : judgement.checks) {
      if (f.kind != "status" && f.kind != "finite_result") ++tally().applied[f.kind];
    }
    if (const Finding* violation = judgement.violation()) fail_with(c, impl, *violation, &outcome);
  }
}

}  // namespace oblique::properties::suite

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

}  // namespace oblique::generators
