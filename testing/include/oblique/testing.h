// The property suite on your own function, in GoogleTest and RapidCheck:
//
//   #include <oblique/testing.h>
//   void make_oblique(float m[16], const float plane[4]);   // yours: column-major, in place
//
//   const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
//                                            make_oblique, oblique::perspective_shape_only<float>);
//   oblique::testing::Contract gl_only() {
//     oblique::testing::Contract c;
//     c.conventions = {oblique::Convention::gl};
//     return c;
//   }
//   OBLIQUE_PROPERTY_TEST(MakeOblique, hasEveryProperty, mine, gl_only())
//
// Each property of the contract is a RapidCheck run over the project's generators (every family,
// convention and hard place the contract names), shrunk on failure to a small counterexample
// written as Markdown + JSON (OBLIQUE_REPORT_DIR, default ./oblique-reports) with the command
// that replays it. The statistics (families, conventions, places, checks applied) are printed,
// and a run that missed a family, convention or hard place of the contract fails.
//
// RC_PARAMS works as RapidCheck documents it: "seed=S max_success=N" and, pasted from a failure,
// "reproduce=..." (tests and properties it does not name are skipped, with a message).
#pragma once

#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "oblique/properties/adapter.h"
#include "oblique/properties/counterexample_report.h"
#include "oblique/properties/filtered.h"
#include "oblique/properties/generators.h"
#include "oblique/properties/implementations.h"
#include "oblique/properties/properties.h"
#include "oblique/protocol/numbers.h"

namespace oblique::testing {

using properties::Checks;
using properties::Counterexample;
using properties::FilteredProblem;
using properties::Finding;
using properties::Implementation;
using properties::Judgement;
using properties::Outcome;
using properties::Problem;
using properties::Property;
using properties::StatusContract;

/// What your function promises: the inputs it is for and how its statuses are judged.
struct Contract {
  std::vector<generators::Family> families = generators::every_family();
  std::vector<Convention> conventions = generators::every_convention();
  std::vector<generators::Place> places = {std::begin(generators::all_places),
                                           std::end(generators::all_places)};
  /// answers_only: a function without statuses (only an answer to an input without one fails;
  /// inputs undecidable at its precision are left out, properties::not_judged()); any_refusal:
  /// it refuses inputs without an answer, in its own words; exact: oblique::Status.
  /// Empty: from the adapter (void: answers_only, bool: any_refusal, Status: exact).
  std::optional<StatusContract> statuses;
  /// The properties judged (extracted_planes_match included).
  std::vector<Property> properties = Checks{}.properties;
};

/// Where reports go and what their replay commands name.
struct Settings {
  std::string report_directory;  ///< empty: $OBLIQUE_REPORT_DIR, else ./oblique-reports
  std::string binary;            ///< empty: this executable (/proc/self/exe)
  std::string cli = "oblique";   ///< the oblique executable, for `oblique apply` replays
  /// The replay command repeats the run with OBLIQUE_IMPL=<implementation> (the project's own
  /// suite, which picks implementations by name); otherwise with the seed alone.
  bool replay_names_implementation = false;
};

inline Settings& settings() {
  static Settings s;
  return s;
}

/// Which kinds of case a run must have covered.
enum class Coverage { valid, places_only, perspective_shape, invalid, none };

/// What the cases of one property run covered, and its last (so most shrunk) failure.
struct Tally {
  std::map<std::string, int> families, conventions, places, defects, implementations, applied;
  std::map<std::string, int> left_out;  ///< answers not judged, by properties::not_judged()
  std::optional<Counterexample> failure;
  std::string property;  ///< the RapidCheck test id of the run
};

inline Tally& tally() {
  static Tally t;
  return t;
}

inline std::string summary(const std::map<std::string, int>& counts) {
  std::string out;
  for (const auto& [name, count] : counts)
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return out;
}

inline std::string current_test_id(char separator) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + separator + info->name();
}

inline properties::ReportContext report_context(const std::string& property) {
  const Settings& s = settings();
  properties::ReportContext context;
  const char* dir = std::getenv("OBLIQUE_REPORT_DIR");
  context.directory = dir && *dir                   ? std::string(dir)
                      : !s.report_directory.empty() ? s.report_directory
                                                    : std::string("oblique-reports");
  context.test_id = current_test_id('.');
  if (!property.empty()) context.stem = context.test_id + "." + property;
  context.seed = rc::detail::configuration().testParams.seed;
  context.max_success = rc::detail::configuration().testParams.maxSuccess;
  context.binary = s.binary;
  if (context.binary.empty()) {
    std::error_code error;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
    context.binary = error ? std::string("<this test executable>") : self.string();
  }
  context.cli = s.cli;
  if (!s.replay_names_implementation) {
    context.replay_run = "RC_PARAMS=\"seed=" + std::to_string(context.seed) +
                         " max_success=" + std::to_string(context.max_success) + "\" " +
                         context.binary + " --gtest_filter='" + context.test_id + "'";
  }
  return context;
}

/// The RapidCheck test id of one property run of the current test: "Suite/Name" or
/// "Suite/Name/property". RC_PARAMS="reproduce=..." names runs by these ids.
inline std::string run_id(const std::string& property) {
  const std::string id = current_test_id('/');
  return property.empty() ? id : id + "/" + property;
}

/// Whether RC_PARAMS="reproduce=..." is set and leaves out the run `id`.
inline bool left_out_by_reproduce(const std::string& id) {
  const auto& reproduce = rc::detail::configuration().reproduce;
  return !reproduce.empty() && reproduce.count(id) == 0;
}

/// Runs `testable` as a RapidCheck property of the current test (RapidCheck id run_id(property));
/// fails the test with the report's path on a counterexample, and when the cases missed a family,
/// convention or hard place the contract names (the `require_*` lists).
template <class Testable>
void run(Testable&& testable, Coverage coverage, const std::string& property = "",
         const Contract& require = Contract{}) {
  tally() = Tally{};
  const std::string id = run_id(property);
  tally().property = property;
  if (left_out_by_reproduce(id)) {
    if (property.empty()) GTEST_SKIP() << id << ": not named by RC_PARAMS reproduce=..., skipped";
    std::cout << id << ": not named by RC_PARAMS reproduce=..., skipped" << std::endl;
    return;
  }
  const bool reproducing = !rc::detail::configuration().reproduce.empty();
  rc::detail::TestMetadata metadata;
  metadata.id = id;
  metadata.description = property.empty() ? current_test_id('.') : property;
  const auto result = rc::detail::checkTestable(std::forward<Testable>(testable), metadata);
  std::ostringstream message;
  rc::detail::printResultMessage(result, message);
  const Tally& t = tally();
  std::cout << (property.empty() ? "" : property + ": ") << message.str()
            << "\nran: " << summary(t.implementations) << "\nfamilies: " << summary(t.families)
            << "\nconventions: " << summary(t.conventions) << "\nplaces: " << summary(t.places);
  if (!t.defects.empty()) std::cout << "\ndefects: " << summary(t.defects);
  if (!t.applied.empty()) std::cout << "\napplied: " << summary(t.applied);
  if (!t.left_out.empty()) std::cout << "\nleft out: " << summary(t.left_out);
  std::cout << std::endl;
  if (!result.template is<rc::detail::SuccessResult>()) {
    std::string where;
    if (t.failure) where = "\nreport: " + write_report(*t.failure, report_context(property));
    ADD_FAILURE() << (property.empty() ? "" : property + ": ") << message.str() << where;
    return;
  }
  if (t.implementations.empty()) {
    ADD_FAILURE() << id
                  << ": no implementation ran: check OBLIQUE_IMPL and the contract (or the "
                     "generator discarded every case)";
    return;
  }
  if (reproducing || coverage == Coverage::none) return;  // one case: nothing to cover
  auto needs = [&](const std::map<std::string, int>& counts, auto names, const char* what) {
    for (const auto& name : names) {
      EXPECT_GT(counts.count(std::string(name)) ? counts.at(std::string(name)) : 0, 0)
          << id << ": no case covered " << what << " " << name << ": raise max_success";
    }
  };
  std::vector<std::string_view> families, conventions, places, defects;
  for (auto f : require.families) families.push_back(generators::family_name(f));
  for (auto c : require.conventions) conventions.push_back(convention_name(c));
  for (auto p : require.places) places.push_back(generators::place_name(p));
  for (auto d : generators::all_defects) defects.push_back(generators::defect_name(d));
  needs(t.conventions, conventions, "convention");
  switch (coverage) {
    case Coverage::valid:
      needs(t.families, families, "family");
      needs(t.places, places, "hard place");
      break;
    case Coverage::places_only:
    case Coverage::perspective_shape: needs(t.places, places, "hard place"); break;
    case Coverage::invalid: needs(t.defects, defects, "defect"); break;
    case Coverage::none: break;
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
  Counterexample ce = properties::make_counterexample(c.matrix, c.plane, c.convention);
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
  if (outcome && outcome->status == Status::ok) properties::set_result(ce, outcome->projection);
  // The report's pictures: the case's volumes and the point the answer clips (exact Problem).
  properties::set_views(ce, Problem<T>(c.matrix, c.plane, c.convention),
                        outcome && outcome->status == Status::ok ? &outcome->projection : nullptr);
  tally().failure = ce;
  if (finding.kind == "status")
    RC_FAIL(impl.name + " answered " + finding.got + ", expected " + finding.expected);
  RC_FAIL(impl.name + " violates " + finding.kind + ": " + finding.lhs + " against " + finding.rhs);
}

/// Runs each implementation on the case and judges each answer (judge(), with `checks` and the
/// implementation's status contract, or `statuses` when given); fails the case on the first
/// violation. Inputs properties::not_judged() leaves out for the contract are skipped and counted
/// (Tally::left_out), except that inputs without an answer are judged where invalid inputs are
/// the point (judge_statuses): there an answer to an input that allows none is the finding.
/// `problem` is a Problem<T> or a FilteredProblem<T> (filtered.h: the same verdicts, most
/// without GMP).
template <class T, class AnyProblem>
void for_each_answer(const std::vector<Implementation<T>>& implementations,
                     const generators::Case<T>& c, const AnyProblem& problem, Checks checks,
                     bool judge_statuses = false,
                     std::optional<StatusContract> statuses = std::nullopt) {
  for (const Implementation<T>& impl : implementations) {
    if (!impl.accepts(c.convention, c.matrix)) continue;
    const StatusContract contract = statuses ? *statuses : impl.status_contract();
    if (const std::string why = properties::not_judged(problem, contract); !why.empty()) {
      if (!judge_statuses || problem.exact_status() == Status::ok) {
        ++tally().left_out[why];
        continue;
      }
    }
    ++tally().implementations[impl.name];
    const Outcome<T> outcome = impl.run(c.matrix, c.plane, c.convention);
    checks.statuses = contract;
    const Judgement judgement = judge(problem, outcome, checks);
    for (const Finding& f : judgement.checks) {
      if (f.kind != "status" && f.kind != "finite_result") ++tally().applied[f.kind];
    }
    if (const Finding* violation = judgement.violation()) fail_with(c, impl, *violation, &outcome);
  }
}

/// A valid case of the contract's families, conventions and places.
template <class T>
rc::Gen<generators::Case<T>> valid_case(const Contract& contract) {
  return rc::gen::exec([contract] {
    const generators::Case<T> c =
        *generators::valid_case_in<T>(contract.families, contract.conventions);
    RC_PRE(std::find(contract.places.begin(), contract.places.end(), c.place) !=
           contract.places.end());
    return c;
  });
}

/// Checks `impl` against every property of `contract`, one RapidCheck run each (named by the
/// property; RC_PARAMS="reproduce=..." names them so), and, when the contract has statuses, the
/// status of inputs without an answer. Fails the current GoogleTest test on a violation, with a
/// report, or when the contract is empty.
template <class T>
void check_properties(const Implementation<T>& impl, const Contract& contract = Contract{}) {
  if (contract.families.empty() || contract.conventions.empty() || contract.places.empty()) {
    ADD_FAILURE() << "oblique::testing: the contract names no family, convention or place";
    return;
  }
  const auto& reproduce = rc::detail::configuration().reproduce;
  const std::string prefix = run_id("") + "/";
  if (!reproduce.empty() &&
      std::none_of(reproduce.begin(), reproduce.end(),
                   [&](const auto& entry) { return entry.first.rfind(prefix, 0) == 0; }))
    GTEST_SKIP() << run_id("") << ": not named by RC_PARAMS reproduce=..., skipped";
  const std::vector<Implementation<T>> implementations{impl};
  for (Property p : contract.properties) {
    if (p == Property::infinite_edge_parallel &&
        std::find(contract.families.begin(), contract.families.end(),
                  generators::Family::infinite) == contract.families.end())
      continue;
    Contract require = contract;
    Coverage coverage = Coverage::valid;
    Contract generate = contract;
    if (p == Property::infinite_edge_parallel) {
      generate.families = {generators::Family::infinite};
      coverage = Coverage::places_only;
    }
    run(
        [=] {
          const generators::Case<T> c = *valid_case<T>(generate);
          const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
          if (problem.exact_status() == Status::ok) count_case(c);
          Checks checks;
          checks.properties = {p};
          for_each_answer(implementations, c, problem, checks, false, contract.statuses);
        },
        coverage, std::string(properties::property_name(p)), require);
  }
  const StatusContract statuses = contract.statuses ? *contract.statuses : impl.status_contract();
  if (statuses == StatusContract::answers_only) return;
  run(
      [=] {
        const generators::InvalidCase<T> ic =
            *generators::invalid_case_in<T>(contract.families, contract.conventions);
        const generators::Case<T>& c = ic.base;
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        ++tally().defects[std::string(generators::defect_name(ic.defect))];
        ++tally().conventions[std::string(convention_name(c.convention))];
        RC_TAG(std::string(generators::defect_name(ic.defect)));
        Checks checks;  // an ok answer is allowed only in a gray zone, and then has every property
        checks.properties = contract.properties;
        for_each_answer(implementations, c, problem, checks, true, contract.statuses);
      },
      Coverage::invalid, "invalid_inputs_get_their_status", contract);
}

}  // namespace oblique::testing

/// A GoogleTest test that checks `implementation` (oblique::adapt()) against `contract`
/// (oblique::testing::Contract), in the spirit of RC_GTEST_PROP.
#define OBLIQUE_PROPERTY_TEST(Suite, Name, implementation, contract)    \
  TEST(Suite, Name) {                                                   \
    ::oblique::testing::check_properties((implementation), (contract)); \
  }

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

inline void showValue(Family f, std::ostream& os) {
  os << family_name(f);
}
inline void showValue(Place p, std::ostream& os) {
  os << place_name(p);
}
inline void showValue(Defect d, std::ostream& os) {
  os << defect_name(d);
}

}  // namespace oblique::generators

namespace oblique {

inline void showValue(Convention c, std::ostream& os) {
  os << convention_name(c);
}

}  // namespace oblique
