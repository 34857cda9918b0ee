// Counterexample reports: a Markdown page a person can read and a JSON sidecar a tool (and the
// regression replay) can read, each naming the one command that replays the case.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/projection.h"
#include "oblique/properties/judge.h"

namespace oblique::properties {

struct Counterexample {
  Finding finding;             ///< what the answer violates (its kind names the property)
  std::string implementation;  ///< e.g. core_general, listing_5_1
  std::string scalar;          ///< float, double, long_double (protocol::scalar_name)
  std::string family, convention, place;
  std::vector<std::string> projection_decimal, projection_hex;  ///< 16, row-major
  std::vector<std::string> plane_decimal, plane_hex;            ///< 4
  std::string request, request_decimal;     ///< the `oblique apply` request: hex strings, numbers
  std::vector<std::string> result_decimal;  ///< 16, or empty if refused
  /// Further facts for the reader (the exact answer, what an external program printed...),
  /// shown as a table in the Markdown and as an object in the JSON.
  std::vector<std::pair<std::string, std::string>> notes;
};

/// The input's part of a counterexample: the numbers (shortest decimal and exact hex), the
/// request lines (protocol::request_line), the scalar and the convention.
template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);

/// Fills result_decimal from an answered M'.
template <class T>
void set_result(Counterexample& ce, const Matrix4<T>& result);

/// Where the report goes and how it is replayed.
struct ReportContext {
  std::string directory;   ///< reports folder
  std::string test_id;     ///< "Suite.Name"
  std::uint64_t seed = 0;  ///< RapidCheck's seed for this run
  int max_success = 100;   ///< RapidCheck's max_success for this run
  std::string binary;      ///< the test executable
  std::string cli;         ///< the oblique executable
  // Set by tools other than the property suite (oblique verify):
  std::string stem;         ///< the report's file name without extension (default: test id.impl)
  std::string replay_run;   ///< the command that repeats the whole run, instead of the suite's
  std::string replay_case;  ///< the command that replays this one case, instead of `oblique apply`
  /// Never replace an earlier report: a taken stem gets "-2", "-3", ... (oblique verify).
  bool keep_existing = false;
};

/// Writes NAME.md and NAME.json into the reports folder (each to a temporary file renamed into
/// place, so a failed write leaves no empty report over an earlier one); returns the Markdown
/// path. Throws std::runtime_error (or std::filesystem::filesystem_error) when it cannot.
std::string write_report(const Counterexample& ce, const ReportContext& context);

}  // namespace oblique::properties
