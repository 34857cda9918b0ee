// The harness under oblique::testing, for the project's own property suite and tests: one
// RapidCheck run per property with its tally of what the cases covered, and the judging of each
// answer of a generated case. Users include oblique/testing.h, not this.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/report/counterexample_report.h"
#include "oblique/run/tally.h"
#include "oblique/testing.h"

namespace oblique::testing {

using oracle::FilteredProblem;
using oracle::Finding;
using oracle::Judgement;
using oracle::Problem;
using report::Counterexample;

/// Which kinds of case a run must have covered.
enum class Coverage { valid, places_only, perspective_shape, invalid, none };

/// What the cases of one property run covered, and its last (so most shrunk) failure.
///
/// The coverage counts are of cases *judged*: cases whose input reached a function under test and
/// whose answer was judged (a case counts once however many functions judged it). What was made
/// but not judged is counted apart, by kind (the case's family; for inputs without an answer,
/// its defect), so a run can say why a kind it claims was never judged.
struct Tally {
  /// The cases made, judged, left out (why: oracle::not_judged()) and refused by every function's
  /// accepts, by family, convention, place and defect (run::kinds_of), and the gate's counts.
  run::Tally cases;
  std::map<std::string, long> implementations, applied;
  std::optional<Counterexample> failure;
  /// The last failure of a run judged by other than the matrix properties (a consumer property,
  /// testing/consumers.cpp; the rasterizer, testing/raster.cpp), as the Markdown of its report.
  std::string markdown_failure;
  /// Its pictures: staged in a report's files under a stem, returning their Markdown section;
  /// empty when the finding has none.
  std::function<std::string(report::ReportFiles&, const std::string&)> markdown_pictures;
  /// The last failure's diagnosis, run when its report is written (not at every shrinking step).
  std::function<mistakes::Diagnosis()> diagnose_failure;
  std::string property;  ///< the RapidCheck test id of the run
  /// The likely cause named on the run's first failing consumer case (before shrinking), carried
  /// to a shrunk case too close to the correct answer to name one.
  std::string first_consumer_cause;
};

/// The tally of the property run under way.
Tally& tally();

/// Appends `item` to a comma-separated list.
void append_item(std::string& list, const std::string& item);

/// Fails the RapidCheck case with `message` alone (RC_FAIL would add our source file's path,
/// which means nothing to the user reading the failure).
[[noreturn]] void fail_case(const std::string& message);

/// The current GoogleTest test as "Suite<separator>Name".
std::string current_test_id(char separator);

/// Where the current test's reports go and the commands that replay them (`property`: the run).
report::ReportContext report_context(const std::string& property);

/// The RapidCheck test id of one property run of the current test: "Suite/Name" or
/// "Suite/Name/property". RC_PARAMS="reproduce=..." names runs by these ids.
std::string run_id(const std::string& property);

/// Whether RC_PARAMS="reproduce=..." is set and leaves out the run `id`.
bool left_out_by_reproduce(const std::string& id);

/// Writes the report of a failure Tally::markdown_failure holds (`markdown`, with the replay
/// command appended) as a new file in the context's directory (never over an earlier one); its
/// path, or why it was not written.
std::string write_markdown_report(const std::string& markdown,
                                  const report::ReportContext& context);

/// Runs `testable` (RC_ macros and generators inside) as a RapidCheck property of the current test
/// (RapidCheck id run_id(property)); fails the test with the report's path on a counterexample, and
/// when the cases missed a family, convention or hard place `require` names (its empty lists:
/// every one).
void run(const std::function<void()>& testable, Coverage coverage, const std::string& property = "",
         const Contract& require = Contract{});

/// Whether `impl` serves every convention of `contract`; fails the current test, saying which it
/// does not, when it does not.
template <class T>
bool serves_conventions(const Implementation<T>& impl, const Contract& contract) {
  for (Convention c : contract.conventions) {
    if (std::find(impl.conventions.begin(), impl.conventions.end(), c) == impl.conventions.end()) {
      ADD_FAILURE() << "oblique::testing: the contract names convention " << convention_name(c)
                    << ", which " << impl.name << " does not serve (adapt() was told "
                    << convention_name(impl.conventions.front()) << ")";
      return false;
    }
  }
  return true;
}

/// Counts a case made (on its kinds: run::kinds_of) and tags it for RapidCheck's table;
/// count_judged() says whether it reached a function and was judged.
template <class T>
void count_generated(const cases::Case<T>& c) {
  tally().cases.made(run::kinds_of(c));
  RC_TAG(std::string(cases::family_name(c.family)), std::string(convention_name(c.convention)),
         c.defect ? std::string(cases::defect_name(*c.defect))
                  : std::string(cases::place_name(c.place)));
}

/// Counts a case whose answer was judged, on its kinds (family, convention, place or defect).
template <class T>
void count_judged(const cases::Case<T>& c) {
  tally().cases.judged(run::kinds_of(c));
}

/// Counts a case (of `kinds`) some function left out: refused by its accepts (`refused_by`, the
/// function's name) or not judged (`why`, oracle::not_judged()'s reason). A case the contract
/// does not claim (`unclaimed`: an input without an answer under a contract that lists no status
/// for it) is said among the reasons but is no gap in what the contract claims: it does not count
/// toward a kind judged in part only.
void count_left_out(const std::vector<run::Kind>& kinds, const std::string& why,
                    const std::string& refused_by = "", bool unclaimed = false);

template <class T>
Counterexample describe(const cases::Case<T>& c, const Implementation<T>& impl) {
  Counterexample ce = report::make_counterexample(c.matrix, c.plane, c.convention);
  ce.implementation = impl.name;
  ce.family = std::string(cases::family_name(c.family));
  ce.place = std::string(cases::place_name(c.place));
  return ce;
}

/// Fails the current RapidCheck case with `finding` as its report. The diagnosis asks the
/// implementation its panel within `contract` (when given): its families, and only inputs the
/// contract judges (oracle::not_judged(): an answers-only function is not asked where no answer
/// exists).
template <class T>
void fail_with(const cases::Case<T>& c, const Implementation<T>& impl, const Finding& finding,
               const Answer<T>* outcome = nullptr, const Checks* checks = nullptr,
               const Contract* contract = nullptr) {
  Counterexample ce = describe(c, impl);
  ce.finding = finding;
  if (outcome && outcome->status == Status::ok) report::set_result(ce, outcome->projection);
  // The report's pictures: the case's volumes and the point the answer clips (exact Problem).
  report::set_views(ce, Problem<T>(c.matrix, c.plane, c.convention),
                    outcome && outcome->status == Status::ok ? &outcome->projection : nullptr);
  tally().failure = ce;
  tally().diagnose_failure = nullptr;
  if (outcome && checks) {
    // The likely cause: the answer, and the implementation asked on the diagnosis's panel.
    // The panel's answers are judged on every property (a run may judge one), under the run's
    // status contract.
    Checks every_property;
    every_property.statuses = checks->statuses;
    const std::vector<cases::Family> families =
        contract ? contract->families : std::vector<cases::Family>{};
    const std::vector<Status> refusals = contract ? contract->refusals : std::vector<Status>{};
    tally().diagnose_failure = [c, impl, out = *outcome, judged = every_property, families,
                                refusals]() {
      auto observe = [&impl, &judged](const Matrix4<T>& m, const Vector4<T>& p, Convention k,
                                      const Answer<T>& answer) {
        const Judgement j = judge(Problem<T>(m, p, k), answer, judged);
        return mistakes::Observation<T>{
            m, p, k, answer.status, answer.projection, j.violation() != nullptr, std::nullopt};
      };
      const mistakes::Probe<T> probe = [&](const Matrix4<T>& m, const Vector4<T>& p, Convention k,
                                           cases::Family family) {
        if (std::find(impl.conventions.begin(), impl.conventions.end(), k) ==
                impl.conventions.end() ||
            !impl.accepts(k, m) ||
            (!families.empty() &&
             std::find(families.begin(), families.end(), family) == families.end()) ||
            !oracle::not_judged(Problem<T>(m, p, k), judged.statuses, refusals).empty())
          return std::optional<mistakes::Observation<T>>();
        return std::optional(observe(m, p, k, impl.run(m, p, k)));
      };
      mistakes::Observation<T> seen = observe(c.matrix, c.plane, c.convention, out);
      seen.family = c.family;
      return mistakes::diagnose<T>({seen}, probe, judged.statuses == StatusContract::answers_only);
    };
  }
  if (finding.check == oracle::Check::status)
    fail_case(impl.name + " " + impl.answer_words(outcome ? outcome->status : Status::ok) +
              "; right: " + bound_text(finding));
  fail_case(impl.name + " violates " + std::string(check_name(finding.check)) + ": " +
            residual_text(finding) + " against " + bound_text(finding));
}

/// Runs each implementation on the case and judges each answer (judge(), with `checks` and the
/// implementation's status contract, or the statuses and refusals of `contract` when given);
/// fails the case on the first violation. Inputs oracle::not_judged() leaves out for the
/// contract are skipped and counted (Tally::cases, on the case's kinds),
/// except that inputs without an answer are judged where invalid inputs are the point
/// (judge_statuses): there an answer to an input that allows none is the finding. Inputs an
/// implementation's accepts refuses are counted as refused. `problem` is a Problem<T> or a
/// FilteredProblem<T> (filtered.h: the same verdicts, most without GMP). Returns whether any
/// implementation's answer was judged (the caller counts the case judged).
template <class T, class AnyProblem>
bool for_each_answer(const std::vector<Implementation<T>>& implementations, const cases::Case<T>& c,
                     const AnyProblem& problem, Checks checks, bool judge_statuses = false,
                     const Contract* contract = nullptr) {
  bool judged = false;
  std::string refused_by, left_out_why;
  bool unclaimed = false;
  for (const Implementation<T>& impl : implementations) {
    if (!impl.accepts(c.convention, c.matrix)) {
      refused_by = impl.name;
      continue;
    }
    const StatusContract statuses =
        contract && contract->statuses ? *contract->statuses : impl.status_contract();
    const std::vector<Status> refusals = contract ? contract->refusals : std::vector<Status>{};
    if (const std::string why = oracle::not_judged(problem, statuses, refusals); !why.empty()) {
      if (!judge_statuses || problem.exact_status() == Status::ok) {
        left_out_why = why;
        // No answer, and no status of the contract's for it: outside what it claims.
        unclaimed = problem.exact_status() != Status::ok;
        continue;
      }
    }
    ++tally().implementations[impl.name];
    judged = true;
    const Answer<T> outcome = impl.run(c.matrix, c.plane, c.convention);
    checks.statuses = statuses;
    const Judgement judgement = judge(problem, outcome, checks);
    for (const Finding& f : judgement.checks) {
      if (f.check != oracle::Check::status && f.check != oracle::Check::finite_result)
        ++tally().applied[std::string(check_name(f.check))];
    }
    if (const Finding* violation = judgement.violation())
      fail_with(c, impl, *violation, &outcome, &checks, contract);
  }
  if (!judged && !left_out_why.empty())
    count_left_out(run::kinds_of(c), left_out_why, "", unclaimed);
  else if (!judged && !refused_by.empty())
    count_left_out(run::kinds_of(c), "", refused_by);
  return judged;
}

}  // namespace oblique::testing
