// `oblique report accuracy`: error against run time for every method and scalar type on the
// input regimes that stress the modification, measured against the exact GMP oracle
// (oracle::exact::round_to, the correctly rounded answer), plus how the error grows with each
// regime's stiffness parameter and how close it comes to the checker's bound.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "oblique/cases/contract.h"

namespace oblique::report {

/// An implementation outside this process, asked the same cases over the pipe (the protocol of
/// `oblique verify`): its answers profiled, its round trip per request timed.
struct ExternalImplementation {
  std::string command;   ///< run under /bin/sh -c
  bool float32 = false;  ///< sent and read in float (else double)
  std::string name;      ///< for the tables and charts (protocol::command_name())
};

struct AccuracyOptions {
  int cases_per_step = 24;  ///< generated cases per regime and stiffness step
  int timing_repeats = 20;  ///< passes over a regime's cases when timing
  unsigned long seed = 20261123;
  std::filesystem::path out_dir = "report-out";
  bool progress = true;
  std::vector<ExternalImplementation> implementations;  ///< --impl, --impl-float
  double request_timeout_seconds = 10;                  ///< for one answer of an implementation
  /// What is measured (`--contract`, `--convention`, `--families`, `--statuses`): cases in the
  /// contract's conventions only (empty: every one); regimes whose projections are of a family
  /// it claims (empty: every one; typical to near_standard and tiny_near build perspective
  /// frusta, infinite and orthographic theirs, scaled a general matrix); and an implementation's
  /// refusals judged by its statuses (default any_refusal). The core's methods are measured on the
  /// same cases.
  Contract contract;
};

/// One row: a method (or an implementation, `round_trip`) on a scalar type in one regime (all
/// its stiffness steps together).
struct AccuracyRow {
  std::string regime, scalar, method;
  bool round_trip = false;  ///< an implementation over the pipe: ns_per_call is per request
  int answered = 0;         ///< cases the method answered ok where the exact answer exists
  int refused = 0;          ///< cases it refused (a status) where the exact answer exists
  int violating = 0;  ///< an implementation's answers that violate the properties (not profiled)
  double max_ulps = 0, p999_ulps = 0, mean_ulps = 0;
  double ns_per_call = 0;
  double max_bound_ratio = 0;  ///< largest error / the checker's bound (must stay <= 1)
};

/// One point of a stiffness sweep: a regime's parameter value, the worst error there.
struct StiffnessPoint {
  std::string regime, parameter, scalar, method;
  double value = 0;
  double max_ulps = 0;
  double max_bound_ratio = 0;
};

struct AccuracyReport {
  std::vector<std::string> regimes;  ///< those measured (the contract's families' own)
  /// Families the contract claims that no regime builds: not measured, and said so.
  std::vector<std::string> unmeasured_families;
  std::vector<AccuracyRow> rows;
  std::vector<StiffnessPoint> stiffness;
  std::string error;  ///< an implementation could not be asked (nothing is written then)
};

/// Measures everything (takes tens of seconds at the default size): each answer's error is its
/// worst entry in ulps of the row (accuracy_profile.h), bits = bits_lost(ulps).
AccuracyReport measure_accuracy(const AccuracyOptions& options, std::ostream& progress);

/// Each implementation over the pipe none of whose answers could be profiled (every one violated
/// the properties or was refused), said in a line: such a report measured nothing of it, and
/// `report accuracy` fails.
std::vector<std::string> unprofiled_implementations(const AccuracyReport& report);

/// Writes accuracy.csv, stiffness.csv, accuracy.md, and the gnuplot scripts accuracy.gp and
/// stiffness.gp in options.out_dir; runs gnuplot on them when it is installed (PNG charts).
/// Returns the paths written; all or nothing: empty (the reason on `log`, the folder's earlier
/// files kept) when a file cannot be written.
std::optional<std::vector<std::filesystem::path>> write_accuracy_report(
    const AccuracyReport& report, const AccuracyOptions& options, std::ostream& log);

/// One (method, scalar) pair over every regime: mean ns per call, worst errors, and whether it is
/// on the error-against-time front (no other pair is both faster and more accurate).
struct OverallPoint {
  double ns_per_call = 0;   ///< mean over the regimes it answered in
  bool round_trip = false;  ///< per request over the pipe (an implementation)
  double max_ulps = 0, p999_ulps = 0, max_bound_ratio = 0;  ///< worst over the regimes
  bool on_front = false;
};

std::map<std::pair<std::string, std::string>, OverallPoint> overall_points(
    const AccuracyReport& report);

}  // namespace oblique::report
