// Counterexample reports: a Markdown page a person can read and a JSON sidecar a tool (and the
// regression replay) can read, each naming the one command that replays the case.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "oblique/plane.h"

namespace oblique::properties {

/// Shortest round-trip decimal (%.17g for double, %.9g for float, %.21Lg for long double).
template <class T>
std::string decimal(T x);
/// Exact hexadecimal (%a / %La).
template <class T>
std::string hexadecimal(T x);
/// "float", "double", "long_double".
template <class T>
const char* scalar_name();

struct Counterexample {
  std::string property;        ///< the property's name, or "status"
  std::string relation;        ///< what was compared
  std::string lhs, rhs;        ///< both sides
  double ratio = 0;            ///< |residual| / bound
  std::string implementation;  ///< e.g. core_general, listing_5_1
  std::string scalar;          ///< float, double, long_double
  std::string family, convention, place;
  std::vector<std::string> projection_decimal, projection_hex;  ///< 16, row-major
  std::vector<std::string> plane_decimal, plane_hex;            ///< 4
  std::vector<std::string> result_decimal;                      ///< 16, or empty if refused
  std::string status_expected, status_got;
  /// Further facts for the reader (the exact answer, what an external program printed...),
  /// shown as a table in the Markdown and as an object in the JSON.
  std::vector<std::pair<std::string, std::string>> notes;
};

template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c);

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
};

/// Writes NAME.md and NAME.json into the reports folder; returns the Markdown path.
std::string write_report(const Counterexample& ce, const ReportContext& context);

/// The `oblique apply` request line for the case (numbers as exact hex strings).
std::string request_line(const Counterexample& ce);

/// The same request with plain JSON numbers (shortest round-trip decimals; "nan", "inf", "-inf"
/// strings for non-finite values), which any JSON reader takes.
std::string request_line_decimal(const Counterexample& ce);

}  // namespace oblique::properties
