// `oblique fuzz-report`: many crash files of a fuzz target, one report per distinct finding.
// Each input is run alone through the target (its libFuzzer binary or its replay build: both
// take a file), its output read, and the inputs grouped by what they found: a property of
// oblique::fuzzing's judgement by its likely cause where the diagnosis names one (one bug, one
// report, whatever property, family and convention each input broke), otherwise by property,
// implementation, projection family and convention;
// a sanitizer's error (by kind and the function it names), a crash or a hang. The smallest input
// of each group gets the report verify writes (Markdown + JSON, pictures, the commands that
// replay it), and an index lists the groups.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "oblique/expected.h"

namespace oblique::fuzzing {

struct FuzzReportOptions {
  std::string target;               ///< the fuzz target's command, run by /bin/sh with a file
  std::vector<std::string> inputs;  ///< files, or directories (walked, in name order)
  std::string report_dir = "oblique-reports";
  double timeout_seconds = 10;   ///< per input: longer is a hang
  std::string self = "oblique";  ///< how to invoke this tool, for the index's replay command
  /// Where "input i of n" lines go while it runs (a line at most every second); null: none.
  std::ostream* progress = nullptr;
};

/// One distinct finding and the inputs that show it.
struct FuzzFinding {
  std::string key;  ///< "likely cause wrong_face x make_oblique", "near_is_clip_plane x
                    ///< make_oblique x frustum x gl", ...
  std::vector<std::string> inputs;  ///< smallest first
  std::string report;               ///< the report of the smallest input
  /// What the inputs found, by "property x family x convention", with counts (a likely cause's
  /// finding holds several).
  std::vector<std::pair<std::string, long>> kinds;
};

struct FuzzReport {
  long inputs = 0;  ///< inputs run
  long total = 0;   ///< inputs given (more than `inputs` when an interrupt stopped the run)
  std::vector<std::string> not_run;  ///< the inputs an interrupt left unrun
  int interrupted = 0;               ///< the signal that stopped the run (its reports written)
  long holds = 0;                    ///< inputs the target runs without a finding now
  std::vector<FuzzFinding> findings;
  std::string index;  ///< the index's path ("" without findings)
};

/// Runs every input through the target and writes the reports; fails (saying why) when there is
/// no input, the report folder cannot be written, or the target cannot be run at all.
Expected<FuzzReport> fuzz_report(const FuzzReportOptions& options);

}  // namespace oblique::fuzzing
