// The project's own property suite on oblique::testing (the same harness users get): the
// implementations OBLIQUE_IMPL selects by name, reports in OBLIQUE_REPORT_DIR whose replay
// commands name this test binary and the oblique CLI.
#pragma once

#include <initializer_list>
#include <iostream>
#include <string>
#include <string_view>
#include <utility>

#include "oblique/mistakes/implementations.h"
#include "oblique/oracle/filtered.h"
#include "oblique/testing/harness.h"

namespace oblique::oracle::suite {

using mistakes::implementation_selected;
using mistakes::implementation_selection_error;
using mistakes::selected_implementations;

using testing::count_generated;
using testing::count_judged;
using testing::Coverage;
using testing::fail_with;
using testing::tally;

/// Runs `testable` as a RapidCheck property of the current test (testing::run), after refusing
/// an OBLIQUE_IMPL that names an unknown implementation.
template <class Testable>
void run_property(Testable&& testable, Coverage coverage) {
  testing::Settings& s = testing::settings();
  s.report_directory = OBLIQUE_REPORT_DIR;
  s.binary = OBLIQUE_PROPERTY_BINARY;
  s.cli = OBLIQUE_CLI;
  s.replay_names_implementation = true;
  if (const std::string error = implementation_selection_error(); !error.empty()) FAIL() << error;
  testing::run(std::forward<Testable>(testable), coverage);
}

/// Skips the current test, with a message, unless OBLIQUE_IMPL selects each of `names` (a
/// property of the core's own methods says nothing about another implementation).
inline bool runs_only_for(std::initializer_list<std::string_view> names) {
  if (!implementation_selection_error().empty())
    return true;  // run_property() fails with the error
  for (std::string_view name : names) {
    if (!implementation_selected(name)) {
      std::cout << "OBLIQUE_IMPL does not select " << name << ": this property is about "
                << "the core's own methods, skipped" << std::endl;
      return false;
    }
  }
  return true;
}

/// Every implementation OBLIQUE_IMPL selects, on the case (testing::for_each_answer); `problem`
/// is a Problem<T> or a FilteredProblem<T>. Whether any answer was judged.
template <class T, class AnyProblem>
bool for_each_answer(const cases::Case<T>& c, const AnyProblem& problem, Checks checks,
                     bool judge_statuses = false) {
  return testing::for_each_answer(selected_implementations<T>(), c, problem, checks, judge_statuses,
                                  nullptr);
}

}  // namespace oblique::oracle::suite
