// oblique verify --accuracy DIR: every answer that passes the properties profiled (row 3 against
// the exact answer, oblique::accuracy_profile), the round trip over the pipe timed, and the
// core's methods measured on the same cases; the report written at the end of a run that holds.
// Internal to oblique::verify.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "cases.h"
#include "oblique/report/accuracy_profile.h"
#include "oblique/verify/verifier.h"

namespace oblique::verify {

template <class T>
class AccuracyLook {
 public:
  /// Answers profiled at most (the first ones of the run); the rest are judged as usual.
  static constexpr long kMaxProfiled = 100000;

  /// The report is written into `dir` (MatrixMode::accuracy_dir).
  AccuracyLook(const VerifyOptions& options, std::string dir, std::ostream& out, std::ostream& err);

  /// An answer that passed the properties, to case `v` (sent as `request`): profiled when it is
  /// a matrix for a case with an answer; a status there is counted as refused.
  void passed(const cases::Case<T>& v, const std::string& request, const std::string& answer);

  /// The end of a run that holds: times the round trip (the profiled requests sent again to a
  /// fresh process), measures the core's methods on the same cases, writes the report. false
  /// (said on err) when it could not be written.
  bool write();

 private:
  const VerifyOptions& options_;
  const std::string dir_;
  std::ostream& out_;
  std::ostream& err_;
  report::Profile mine_;
  std::vector<report::ProfileInput<T>> inputs_;
  long skipped_ = 0;  ///< answers beyond kMaxProfiled
};

}  // namespace oblique::verify
