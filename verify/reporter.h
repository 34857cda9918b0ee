// oblique verify's words: the report of a shrunk finding (Markdown + JSON, with the commands that
// replay it), the summary of a passing run, the index of a --keep-going run, and the messages of
// protocol problems. Internal to oblique::verify.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "cases.h"
#include "oblique/protocol/numbers.h"
#include "oblique/report/report_files.h"
#include "oblique/verify/verifier.h"
#include "session.h"

namespace oblique::verify {

/// The command that runs `options`' run again: every flag it was given, and its seed.
std::string rerun_command(const VerifyOptions& options);

/// The flags that name the program a replay asks: --impl and, where not the protocol's own,
/// --layout.
std::string impl_flags(const VerifyOptions& options);

/// What a Ctrl-C says (oblique/protocol/interrupts.h): `judged` `what` ("cases judged") in
/// `seconds`, no violation so far, the seed, and rerun_command(); published for the handler.
void set_interrupted_line(const VerifyOptions& options, long judged, const std::string& what,
                          double seconds);
/// The same once a violation is being shrunk: the run is repeated to find it again.
void set_shrinking_line(const VerifyOptions& options);
/// The same once the shrunk violation's report is being written (its pictures drawn): nothing of
/// it is left behind (report::ReportFiles), and the run is repeated to write it.
void set_reporting_line(const VerifyOptions& options);

/// A matrix or vector's entries, row by row, as a JSON list of exact hex strings (what a report
/// keeps for its replay).
template <class Derived>
std::string hex_list(const Eigen::MatrixBase<Derived>& m) {
  std::string out = "[";
  for (int i = 0; i < m.rows(); ++i)
    for (int j = 0; j < m.cols(); ++j)
      out += (i + j > 0 ? ", " : "") + protocol::json_number(m(i, j), protocol::Notation::hex);
  return out + "]";
}

/// Commits a report staged in `files` (DIR/STEM.md and the rest) and says on `err` where it is,
/// or on one line why it could not be written: Verdict::violated, or Verdict::error.
Verdict commit_report(report::ReportFiles& files, const std::string& stem, std::ostream& err);

/// --keep-going: one report per kind of finding (property x family x place).
struct Kind {
  std::string report;
  long repeats = 0;   ///< cases of this kind found (the first one shrunk and reported)
  std::string cause;  ///< its likely cause (Reporter::last_cause()), by which the index groups
};

template <class T>
class Reporter {
 public:
  /// `save_regressions`: a folder where each report is kept as a regression too ("" none).
  Reporter(const VerifyOptions& options, std::string save_regressions, const Draws<T>& draws,
           std::ostream& out, std::ostream& err);

  /// Writes the report of a (shrunk) finding, keeps it as a regression when asked, and prints
  /// it: Verdict::violated.
  Verdict finding(const cases::Case<T>& v, const Found<T>& found, int steps, bool out_of_time,
                  long found_after_cases, double found_after_seconds,
                  const mistakes::Diagnosis& diagnosis = {});
  /// --keep-going: a finding whose named likely cause was reported already gets no report of its
  /// own; it is printed with the earlier report's path, and the index lists it under the cause.
  void one_report_per_cause() { one_per_cause_ = true; }
  const std::string& last_report() const { return last_report_; }
  /// Whether the last finding got a report of its own (not one_report_per_cause()'s earlier one).
  bool last_report_is_new() const { return last_report_new_; }
  const std::string& last_kind() const { return last_kind_; }
  /// The likely cause of the last finding reported ("" where none was diagnosed).
  const std::string& last_cause() const { return last_cause_; }

  /// The summary of a run without a finding: Verdict::holds.
  Verdict passed(long done, double elapsed, const run::Tally& tally, bool stopped_by_time,
                 long dropped);
  /// The index of a --keep-going run's findings: Verdict::violated.
  Verdict index(const std::map<std::string, Kind>& kinds, long done);

  // Protocol problems (the implementation is stopped first): Verdict::error.
  Verdict protocol_error(const std::string& request, const std::string& answer,
                         const std::string& why);
  /// Answers out of step with requests: lines beyond one per request, or one missing.
  Verdict count_error(const std::string& what, const std::vector<std::string>& requests,
                      const std::vector<std::string>& lines);
  Verdict overlong_line(const std::string& request, const std::string& line_start);
  Verdict issue(const Issue& issue);

  /// The whole run again: this run's own flags (every one of them), with its seed.
  std::string replay_run_command() const;
  /// This case alone, judged: the run's contract and bounds flags, with --replay.
  std::string replay_case_command(const std::string& report_json) const;

 private:
  const VerifyOptions& options_;
  const std::string save_regressions_;
  const Draws<T>& draws_;
  std::ostream& out_;
  std::ostream& err_;
  std::string last_report_, last_kind_, last_cause_;
  bool one_per_cause_ = false, last_report_new_ = false;
  std::map<std::string, std::string> cause_reports_;  ///< named cause -> its report
};

}  // namespace oblique::verify
