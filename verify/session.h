// oblique verify's session with the implementation: the program (oblique::client), the run's clock,
// and one request sent alone and judged (evaluate()), which confirming, shrinking, isolating a
// request that hangs or kills the process, and replaying reports all use. Internal to
// oblique::verify.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "cases.h"
#include "oblique/client/program.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/verify/verifier.h"

namespace oblique::verify {

using client::Clock;
using protocol::escape_bytes;
using protocol::shell_quote;

/// A protocol problem found while evaluating: what, the request, the lines read.
struct Issue {
  std::string what, request;
  std::vector<std::string> lines;
};

template <class T>
class Session {
 public:
  Session(const VerifyOptions& options, const Draws<T>& draws);

  client::Program& program() { return program_; }
  const Draws<T>& draws() const { return draws_; }

  /// Starts the run's time limit now.
  void start_clock();
  Clock::time_point start() const { return start_; }
  Clock::time_point deadline() const { return deadline_; }
  bool out_of_time() const { return Clock::now() >= deadline_; }
  double seconds_since_start() const;
  /// --timeout: how long one answer may take.
  std::chrono::milliseconds idle() const { return idle_; }

  enum class Evaluation { pass, finding, protocol_error, out_of_time };
  /// Sends one case alone (restarting the implementation when it is not running) and judges
  /// the answer: a finding (in `finding`), a pass (also for an input the contract leaves out),
  /// a protocol problem (issue()), or no time left.
  Evaluation evaluate(const cases::Case<T>& v, Found<T>& finding);
  /// Sends one case alone and judges it, for the diagnosis: the answer and whether it is wrong,
  /// or none (left out by the contract, a protocol problem, no answer, no time left).
  std::optional<mistakes::Observation<T>> observe(const cases::Case<T>& v);
  /// The protocol problem of the last evaluation.
  const Issue& issue() const { return issue_; }
  /// The answer of the last evaluation, when it gave one.
  const std::optional<Answer<T>>& last_answer() const { return last_answer_; }

  /// The finding for a program that exited (a crash) or gave no answer in time (a timeout).
  Found<T> lost_finding(const client::Failure& failure);

 private:
  const VerifyOptions& options_;
  const Draws<T>& draws_;
  std::chrono::milliseconds idle_;
  client::Program program_;
  Clock::time_point start_, deadline_;
  Issue issue_;
  std::string last_request_;
  std::optional<Answer<T>> last_answer_;  ///< of the last evaluation
};

}  // namespace oblique::verify
