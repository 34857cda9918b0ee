// The property suite on your own function, in GoogleTest and RapidCheck:
//
//   #include <oblique/testing.h>
//   void make_oblique(float m[16], const float plane[4]);   // yours: column-major, in place
//
//   const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
//                                            oblique::Convention::gl, make_oblique);
//   OBLIQUE_PROPERTY_TEST(MakeOblique, hasEveryProperty, mine, oblique::Contract{})
//
// The contract (oblique/cases/contract.h) says what the function promises; its empty lists
// mean every family, place and property, and the conventions stated to adapt(). Each property
// of the contract is a RapidCheck run over the project's generators (every family, convention
// and hard place the contract names), shrunk on failure to a small counterexample
// written as Markdown + JSON (OBLIQUE_REPORT_DIR, default ./oblique-reports) with the command
// that replays it. A passing run prints one line (OBLIQUE_STATISTICS=1 adds the families,
// conventions, places and checks applied), a failure is printed once. Coverage counts cases
// judged, not made: a run in which a family, convention or hard place of the contract had no
// case reach the function and be judged fails, saying why (refused by accepts, left out, or too
// few cases); a kind with more than 10% of its cases left out is a warning (OBLIQUE_STRICT=1:
// a failure). A report an earlier run wrote for a
// property that now passes is moved to OBLIQUE_REPORT_DIR/earlier/, so the folder shows what the
// last runs found.
//
// RC_PARAMS works as RapidCheck documents it: "seed=S max_success=N" and, pasted from a failure,
// "reproduce=..." (tests and properties it does not name are skipped, with a message).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/cases/checks.h"
#include "oblique/cases/contract.h"
#include "oblique/oracle/adapter.h"
#include "oblique/oracle/consumers.h"
#include "oblique/run/tally.h"
#include "oblique/util/eigen_layout.h"

namespace oblique::testing {

using cases::Checks;
using cases::Property;
using cases::StatusContract;
using oracle::Implementation;

/// Where reports go and what their replay commands name.
struct Settings {
  std::string report_directory;  ///< empty: $OBLIQUE_REPORT_DIR, else ./oblique-reports
  std::string binary;            ///< empty: this executable (/proc/self/exe)
  std::string cli = "oblique";   ///< the oblique executable, for `oblique apply` replays
  /// The replay command repeats the run with OBLIQUE_IMPL=<implementation> (the project's own
  /// suite, which picks implementations by name); otherwise with the seed alone.
  bool replay_names_implementation = false;
  /// Print each passing run's case statistics (families, conventions, places, checks applied,
  /// RapidCheck's tags) too; a pass is otherwise one line. Set by OBLIQUE_STATISTICS=1.
  bool statistics = false;
  /// A kind of case (family, defect, consumer function) the contract claims with more than this
  /// share of its cases left out (not judged: within rounding of no answer, beyond a bound) is
  /// named in a warning line of the run's summary.
  double left_out_warning = run::kLeftOutWarning;
  /// The warning fails the test instead. Set by OBLIQUE_STRICT=1.
  bool strict = false;
};

/// The settings of this test program (set them before the tests run).
Settings& settings();

/// Checks `impl` against every property of `contract`, one RapidCheck run each (named by the
/// property; RC_PARAMS="reproduce=..." names them so), row 3's accuracy when the contract says
/// so, and, when the contract has statuses, the status of inputs without an answer. Fails the
/// current GoogleTest test on a violation, with a report, or when the contract names a
/// convention the implementation does not serve.
///
/// Compiled in oblique::testing for float, double and long double (in a namespace named by
/// Eigen's layout: oblique/util/eigen_layout.h).
inline namespace OBLIQUE_EIGEN_LAYOUT {
template <class T>
void check_properties(const Implementation<T>& impl, const Contract& contract = Contract{});
}  // namespace OBLIQUE_EIGEN_LAYOUT

/// Checks each function of `consumers`: one RapidCheck run per property (named by it), on the
/// oblique answers of the core for the contract's families, conventions and places (and, for
/// the pass camera, views and planes of mirrors, clip planes and portals). Fails the current
/// GoogleTest test on a violation, with a report, or when no function is given.
inline namespace OBLIQUE_EIGEN_LAYOUT {
template <class T>
void check_consumers(const oblique::Consumers<T>& consumers, const Contract& contract = Contract{});
}  // namespace OBLIQUE_EIGEN_LAYOUT

/// What profile_accuracy() asks and where it writes.
struct AccuracySettings {
  int cases = 4000;        ///< cases of the contract generated (the same ones every run)
  std::uint64_t seed = 1;  ///< their seed
  std::string directory;  ///< empty: $OBLIQUE_REPORT_DIR (or ./oblique-reports)/Suite.Name.accuracy
};

/// The accuracy profile of `impl` on cases of `contract`: for each answer that passes the
/// properties, row 3 entry by entry against the exact answer, grouped by family, place and
/// stiffness; its time per call in this process; the core's closed form, general and accurate
/// methods on the same cases beside it. Writes the report (oblique/report/accuracy_profile.h:
/// accuracy.md, accuracy.csv, worst-K.json, charts) and prints one line with its path. Fails the
/// current test when answers violate the properties (the property tests report them; they are
/// not profiled) or when the report cannot be written. Compiled for float, double, long double.
inline namespace OBLIQUE_EIGEN_LAYOUT {
template <class T>
void profile_accuracy(const Implementation<T>& impl, const Contract& contract = Contract{},
                      const AccuracySettings& settings = AccuracySettings{});
}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing

/// A GoogleTest test that writes the accuracy profile of `implementation` (oblique::adapt()) on
/// cases of `contract`, beside the core's methods (profile_accuracy()).
#define OBLIQUE_ACCURACY_REPORT(Suite, Name, implementation, contract)  \
  TEST(Suite, Name) {                                                   \
    ::oblique::testing::profile_accuracy((implementation), (contract)); \
  }

/// A GoogleTest test that checks the code around the matrix, `consumers` (oblique::Consumers,
/// oblique/oracle/consumers.h), under `contract` (its families, conventions and places).
#define OBLIQUE_CONSUMERS_TEST(Suite, Name, consumers, contract)  \
  TEST(Suite, Name) {                                             \
    ::oblique::testing::check_consumers((consumers), (contract)); \
  }

/// A GoogleTest test that checks `implementation` (oblique::adapt()) against `contract`
/// (oblique::Contract), in the spirit of RC_GTEST_PROP.
#define OBLIQUE_PROPERTY_TEST(Suite, Name, implementation, contract)    \
  TEST(Suite, Name) {                                                   \
    ::oblique::testing::check_properties((implementation), (contract)); \
  }
