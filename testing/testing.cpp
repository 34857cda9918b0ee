// oblique::testing's bodies: RapidCheck's runner (its rc::detail interface stays here, out of the
// headers users include), the run's tally and reports, check_properties() for the three scalars.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string_view>
#include <system_error>

#include "oblique/report/report_files.h"
#include "oblique/testing/harness.h"

namespace oblique::testing {

Settings& settings() {
  static Settings s = [] {
    Settings initial;
    const char* statistics = std::getenv("OBLIQUE_STATISTICS");
    initial.statistics = statistics && *statistics && std::string(statistics) != "0";
    const char* strict = std::getenv("OBLIQUE_STRICT");
    initial.strict = strict && *strict && std::string(strict) != "0";
    return initial;
  }();
  return s;
}

Tally& tally() {
  static Tally t;
  return t;
}

namespace {
/// The JSON form of the contract check_properties() is judging by (for its reports).
std::string& current_contract() {
  static std::string json;
  return json;
}
}  // namespace

void count_left_out(const std::vector<run::Kind>& kinds, const std::string& why,
                    const std::string& refused_by, bool unclaimed) {
  if (!refused_by.empty())
    tally().cases.refused(kinds, refused_by);
  else
    tally().cases.left_out(kinds, why, !unclaimed);
}

void append_item(std::string& list, const std::string& item) {
  list += (list.empty() ? "" : ", ") + item;
}

void fail_case(const std::string& message) {
  throw rc::detail::CaseResult(rc::detail::CaseResult::Type::Failure, message);
}

std::string current_test_id(char separator) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + separator + info->name();
}

report::ReportContext report_context(const std::string& property) {
  const Settings& s = settings();
  report::ReportContext context;
  const char* dir = std::getenv("OBLIQUE_REPORT_DIR");
  context.directory = dir && *dir                   ? std::string(dir)
                      : !s.report_directory.empty() ? s.report_directory
                                                    : std::string("oblique-reports");
  context.test_id = current_test_id('.');
  context.seed = rc::detail::configuration().testParams.seed;
  context.max_success = rc::detail::configuration().testParams.maxSuccess;
  context.binary = s.binary;
  if (context.binary.empty()) {
    std::error_code error;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
    context.binary = error ? std::string("<this test executable>") : self.string();
  }
  const std::string executable = std::filesystem::path(context.binary).filename().string();
  context.report_key = executable.empty() || executable.front() == '<'
                           ? context.test_id
                           : executable + "." + context.test_id;
  if (!property.empty()) context.stem = context.report_key + "." + property;
  context.cli = s.cli;
  context.contract = current_contract();
  if (!s.replay_names_implementation) {
    context.replay_run = "RC_PARAMS=\"seed=" + std::to_string(context.seed) +
                         " max_success=" + std::to_string(context.max_success) + "\" " +
                         context.binary + " --gtest_filter='" + context.test_id + "'";
  }
  return context;
}

std::string run_id(const std::string& property) {
  const std::string id = current_test_id('/');
  return property.empty() ? id : id + "/" + property;
}

namespace {

/// After a passing run of a property: the report an earlier run wrote for it (every file named
/// STEM.*) is moved, never deleted, to DIR/earlier/<UTC time>-<pid>/, so the reports folder shows
/// what the last runs found. A move that fails is said and the files stay.
void move_earlier_reports(const report::ReportContext& context) {
  namespace fs = std::filesystem;
  if (context.stem.empty()) return;
  std::error_code error;
  const fs::path directory = context.directory;
  const std::string prefix = context.stem + ".";
  std::vector<fs::path> found;
  for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) == 0 && it->is_regular_file(error)) found.push_back(it->path());
  }
  if (found.empty()) return;
  const fs::path target = report::move_to_earlier(directory, found, error);
  if (error) {
    std::cout << "note: could not move the earlier report " << prefix << "md to " << target.string()
              << " (" << error.message() << "); it is left where it was\n";
    return;
  }
  std::cout << "passes now: the earlier report " << prefix << "md was moved to " << target.string()
            << "\n";
}

}  // namespace

std::string write_markdown_report(const std::string& markdown,
                                  const report::ReportContext& context) {
  report::ReportFiles files(context.directory);
  const std::string stem =
      files.reserve_stem(context.stem.empty() ? context.report_key : context.stem, {".md"});
  const std::string pictures =
      tally().markdown_pictures ? tally().markdown_pictures(files, stem) : std::string();
  files.open(stem + ".md") << markdown << "\n"
                           << pictures << "## Replay\n\n```\n"
                           << (context.replay_run.empty() ? context.binary : context.replay_run)
                           << "\n```\n";
  std::ostringstream log;
  if (!files.commit(log)) {
    std::string why = log.str();
    while (!why.empty() && why.back() == '\n') why.pop_back();
    return "(not written: " + why + ")";
  }
  return (std::filesystem::path(context.directory) / (stem + ".md")).string();
}

bool left_out_by_reproduce(const std::string& id) {
  const auto& reproduce = rc::detail::configuration().reproduce;
  return !reproduce.empty() && reproduce.count(id) == 0;
}

void run(const std::function<void()>& testable, Coverage coverage, const std::string& property,
         const Contract& given) {
  const Contract require =
      resolved(given, cases::every_convention(), cases::StatusContract::exact, false);
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
  const auto result = rc::detail::checkTestable(testable, metadata);
  std::ostringstream message;
  rc::detail::printResultMessage(result, message);
  const Tally& t = tally();
  const run::Tally& cases = t.cases;
  std::ostringstream statistics;
  statistics << "ran: " << run::counts_text(t.implementations)
             << "\njudged, by family: " << run::counts_text(cases.by("family"))
             << "\njudged, by convention: " << run::counts_text(cases.by("convention"))
             << "\njudged, by place: " << run::counts_text(cases.by("place"));
  if (!cases.by("defect").empty())
    statistics << "\njudged, by defect: " << run::counts_text(cases.by("defect"));
  if (!cases.by("family", &run::Counts::made).empty())
    statistics << "\nmade: " << run::counts_text(cases.by("family", &run::Counts::made));
  if (!cases.by("family", &run::Counts::refused).empty())
    statistics << "\nrefused by accepts: "
               << run::counts_text(cases.by("family", &run::Counts::refused));
  if (!t.applied.empty()) statistics << "\napplied: " << run::counts_text(t.applied);
  if (!cases.reasons().empty()) statistics << "\nleft out: " << run::counts_text(cases.reasons());
  const std::string name = property.empty() ? "" : property + ": ";
  rc::detail::SuccessResult success;
  const bool passed = result.match(success);
  // The kinds the contract claims, by what the coverage counts (empty: not checked): its
  // families (or defects) and conventions.
  std::vector<run::Kind> kinds, conventions;
  if (!reproducing && (coverage == Coverage::valid || coverage == Coverage::invalid)) {
    if (coverage == Coverage::valid) {
      for (auto f : require.families)
        kinds.push_back({"family", std::string(cases::family_name(f))});
    } else {
      for (auto d : require.defects)
        kinds.push_back({"defect", std::string(cases::defect_name(d))});
    }
  }
  for (auto c : require.conventions)
    conventions.push_back({"convention", std::string(convention_name(c))});
  run::Advice advice;
  advice.more = "raise max_success (RC_PARAMS=\"max_success=N\")";
  advice.judge_left_out = "raise max_success";
  // Why a kind the contract claims had no case judged, and what to change (a pass means judged).
  auto unjudged = [&](const std::vector<run::Kind>& claims) {
    std::vector<std::string> lines = run::unjudged(cases, claims, success.numSuccess, advice);
    for (std::string& line : lines) line = id + ": " + line;
    return lines;
  };
  if (!passed) {
    // A claimed kind that accepts refused every case of, said beside the finding: the run fails
    // for the finding, and would fail for the kind too (a pass means judged).
    std::string refused;
    for (const run::Kind& kind : kinds) {
      const run::Counts c = cases.of(kind);
      if (c.judged == 0 && c.refused > 0)
        for (const std::string& line : unjudged({kind})) refused += "\n" + line;
    }
    // Printed once, as the test's failure: RapidCheck's message, the statistics, the report.
    std::string where;
    if (t.failure) {
      Counterexample failure = *t.failure;
      std::string cause_key;  // a named cause, per implementation: one report each in a process
      if (t.diagnose_failure) {
        failure.diagnosis = t.diagnose_failure();
        where = "\n" + mistakes::likely_cause_line(*failure.diagnosis);
        const mistakes::Diagnosis& d = *failure.diagnosis;
        if (d.ran && (!d.causes.empty() || !d.families.empty() || d.numerical))
          cause_key = report_context(property).directory + ": " + failure.implementation + ": " +
                      mistakes::cause_names(d);
      }
      static std::map<std::string, std::string> cause_reports;
      if (const auto earlier = cause_reports.find(cause_key);
          !cause_key.empty() && earlier != cause_reports.end()) {
        // The same bug as an earlier failure of this process: its report, not a second one.
        ADD_FAILURE() << name << message.str() << where << "\nreport: " << earlier->second
                      << " (the same likely cause as an earlier failure; no second report)"
                      << refused;
        return;
      }
      const std::string path = write_report(failure, report_context(property));
      if (!cause_key.empty()) cause_reports[cause_key] = path;
      where += "\nreport: " + path;
    } else if (!t.markdown_failure.empty()) {
      where = "\nreport: " + write_markdown_report(t.markdown_failure, report_context(property));
    }
    ADD_FAILURE() << name << message.str() << "\n" << statistics.str() << where << refused;
    return;
  }
  // Kinds judged in part only: more than the warning share of what the contract claims of their
  // cases left out (inputs without an answer it lists no status for are left out by design).
  const std::string partly =
      run::partly_judged(cases, kinds, settings().left_out_warning, /*with_axis=*/false);
  // Hard places made but never judged (the places' coverage counts what was made: a place is a
  // property of the plane, and its cases are often the ones within rounding of no answer).
  std::string unjudged_places;
  if (!reproducing && coverage != Coverage::invalid && coverage != Coverage::none) {
    for (auto p : require.places) {
      const run::Counts c = cases.of({"place", std::string(cases::place_name(p))});
      if (c.made > 0 && c.judged == 0)
        append_item(unjudged_places, std::string(cases::place_name(p)));
    }
  }
  std::string warning;
  if (!partly.empty() || !unjudged_places.empty()) {
    std::ostringstream w;
    w << "judged in part only:";
    if (!partly.empty()) {
      w << " more than " << static_cast<int>(100 * settings().left_out_warning + 0.5)
        << "% of the cases left out: " << partly << ";";
    }
    if (!unjudged_places.empty())
      w << " hard places made but none judged: " << unjudged_places << ";";
    w << " why: " << run::counts_text(cases.reasons());
    warning = w.str();
  }
  // A pass is one line (and its warnings); the tag table and the statistics with
  // OBLIQUE_STATISTICS=1.
  std::cout << name << "OK, passed " << success.numSuccess << " tests";
  if (!cases.reasons().empty())
    std::cout << " (left out: " << run::counts_text(cases.reasons()) << ")";
  std::cout << "\n";
  if (!warning.empty()) {
    std::cout << "warning: " << id << ": " << warning
              << (settings().strict ? "" : " [OBLIQUE_STRICT=1 makes it a failure]") << "\n";
  }
  if (settings().statistics) std::cout << message.str() << "\n" << statistics.str() << "\n";
  if (!property.empty() && !reproducing) move_earlier_reports(report_context(property));
  std::cout << std::flush;
  if (t.implementations.empty()) {
    ADD_FAILURE() << id
                  << ": no implementation ran: check OBLIQUE_IMPL and the contract (or the "
                     "generator discarded every case)"
                  << (cases.by("family", &run::Counts::refused).empty()
                          ? ""
                          : "; refused by accepts: " +
                                run::counts_text(cases.by("family", &run::Counts::refused)))
                  << (cases.reasons().empty() ? ""
                                              : "; left out: " + run::counts_text(cases.reasons()));
    return;
  }
  if (settings().strict && !warning.empty())
    ADD_FAILURE() << id << ": " << warning << " [OBLIQUE_STRICT=1]";
  if (reproducing || coverage == Coverage::none) return;  // one case: nothing to cover
  for (const std::string& line : unjudged(kinds)) ADD_FAILURE() << line;
  for (const std::string& line : unjudged(conventions)) ADD_FAILURE() << line;
  switch (coverage) {
    case Coverage::valid:
    case Coverage::places_only:
    case Coverage::perspective_shape:
      for (auto p : require.places) {
        const std::string place(cases::place_name(p));
        EXPECT_GT(cases.of({"place", place}).made, 0)
            << id << ": no case of hard place " << place << " was made: " << advice.more;
      }
      break;
    case Coverage::invalid:
    case Coverage::none: break;
  }
}

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
void check_properties(const Implementation<T>& impl, const Contract& given) {
  const Contract contract = resolved(given, impl.conventions, impl.status_contract(), false);
  current_contract() = contract_json(contract);
  struct Forget {
    ~Forget() { current_contract().clear(); }
  } forget;
  if (!serves_conventions(impl, contract)) return;
  const auto& reproduce = rc::detail::configuration().reproduce;
  const std::string prefix = run_id("") + "/";
  if (!reproduce.empty() &&
      std::none_of(reproduce.begin(), reproduce.end(),
                   [&](const auto& entry) { return entry.first.rfind(prefix, 0) == 0; }))
    GTEST_SKIP() << run_id("") << ": not named by RC_PARAMS reproduce=..., skipped";
  const std::vector<Implementation<T>> implementations{impl};
  auto judge_valid = [&](Contract generate, Checks checks, Coverage coverage,
                         const std::string& name) {
    run(
        [=] {
          const cases::Case<T> c = *cases::valid_case_for<T>(generate);
          const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
          count_generated(c);
          if (for_each_answer(implementations, c, problem, checks, false, &contract))
            count_judged(c);
        },
        coverage, name, generate);
  };
  for (Property p : contract.properties) {
    const bool infinite = std::find(contract.families.begin(), contract.families.end(),
                                    cases::Family::infinite) != contract.families.end();
    if (p == Property::infinite_edge_parallel && !infinite) continue;
    Contract generate = contract;
    Coverage coverage = Coverage::valid;
    if (p == Property::infinite_edge_parallel) {
      generate.families = {cases::Family::infinite};
      coverage = Coverage::places_only;
    }
    Checks checks;
    checks.properties = {p};
    judge_valid(generate, checks, coverage, std::string(cases::property_name(p)));
  }
  if (*contract.row3_accuracy) {
    Checks checks;  // row 3 within the bound of careful arithmetic, and no property
    checks.properties = {};
    checks.row3_accuracy = true;
    judge_valid(contract, checks, Coverage::valid, "row3_accuracy");
  }
  if (*contract.statuses == StatusContract::answers_only) return;
  run(
      [=] {
        const cases::Case<T> c = *cases::invalid_case_for<T>(contract);
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        count_generated(c);
        Checks checks;  // an ok answer is allowed only in a gray zone, and then has every property
        checks.properties = contract.properties;
        checks.row3_accuracy = *contract.row3_accuracy;
        if (for_each_answer(implementations, c, problem, checks, true, &contract)) count_judged(c);
      },
      Coverage::invalid, "invalid_inputs_get_their_status", contract);
}

template void check_properties<float>(const Implementation<float>&, const Contract&);
template void check_properties<double>(const Implementation<double>&, const Contract&);
template void check_properties<long double>(const Implementation<long double>&, const Contract&);

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing
