// oblique verify's cases: the contract into draws (the generator, the checks, what it leaves
// out), an answer line read back, and its judgement. Internal to oblique::verify.
#pragma once

#include <rapidcheck.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/checks.h"
#include "oblique/cases/contract.h"
#include "oblique/cases/generators.h"
#include "oblique/expected.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/finding.h"
#include "oblique/protocol/protocol.h"
#include "oblique/run/tally.h"

namespace oblique::verify {

/// What went wrong with one answer (or with the process while it was answering): the finding
/// and its evidence.
template <class T>
struct Found {
  oracle::Finding finding;  ///< kind: "status", a property, ..., or "crash", "timeout"
  std::optional<Matrix4<T>> result;
  std::string answer_line, process;
};

/// The run's contract, resolved for a program (conventions gl, statuses any_refusal and row 3's
/// accuracy unless it says otherwise), and what follows from it: the generator of cases, the
/// checks of each answer, and which inputs are not sent.
template <class T>
class Draws {
 public:
  explicit Draws(const Contract& given);

  const Contract& contract() const { return contract_; }
  const cases::Checks& checks() const { return checks_; }
  const rc::Gen<cases::Case<T>>& generator() const { return generator_; }
  /// What the contract leaves out whatever is drawn ("place scaled (unit-normal planes)", ...).
  const std::vector<std::string>& notes() const { return notes_; }
  /// Whether some inputs are left out by their status (the contract lacks a refusal).
  bool needs_status() const;
  /// Why the contract leaves out this input ("" when it is sent): oracle::not_judged(), the
  /// rule every tool shares.
  std::string left_out(const oracle::FilteredProblem<T>& problem) const;

 private:
  Contract contract_;
  cases::Checks checks_;
  rc::Gen<cases::Case<T>> generator_;
  std::vector<std::string> notes_;
};

/// The request line of a case.
template <class T>
std::string request_text(const cases::Case<T>& c);

/// The suite's judgement under the run's checks: the first violation, or none. `problem` is the
/// filtered checker (the exact checker's verdicts, most without GMP; used by one thread only).
template <class T>
std::optional<Found<T>> judge_answer(const oracle::FilteredProblem<T>& problem,
                                     const Answer<T>& answer, const cases::Checks& checks);

/// Whether a wrong answer under T wider than float is what float arithmetic gives: every entry
/// of `answer` is a float or has at most 9 significant digits (how a float prints: shortest or
/// %.9g), and the answer rounded to float holds under float's bounds on the input rounded to
/// float (the input a float engine reads). Always false for T = float. The hint that the run
/// wants --precision float.
template <class T>
bool consistent_with_float(const cases::Case<T>& c, const Matrix4<T>& answer,
                           const cases::Checks& checks);

/// How verify's matrix run tells its user what to change when a claimed kind had nothing judged.
run::Advice matrix_advice();

}  // namespace oblique::verify
