// What a run judged, counted against what it claims, and the gate a pass goes through: "a pass
// means judged", written once for every way in (oblique::testing's property runs, `oblique
// verify` on matrices and on consumers, `oblique check`'s consumers, the fuzz driver's summary).
//
//   run::Tally tally;
//   tally.judged(run::kinds_of(c));                     // a case whose answer was judged
//   tally.left_out(run::kinds_of(c), "within rounding of no answer");
//   for (const std::string& line : run::unjudged(tally, run::claims_of(contract), rounds, advice))
//     err << line;                                       // a claimed kind with nothing judged
//
// A kind is a name on an axis (family perspective, convention gl, property view_position, ...);
// each case or answer counts on each of its kinds. Each way in tells its user in its own terms
// what to change (Advice); the counting and the decision are here.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/cases/contract.h"
#include "oblique/depth_convention.h"

namespace oblique::run {

/// A kind a contract (or a scene) claims: the axis it is on and its name there. The axes the ways
/// in use: "family", "convention", "place", "defect" (of a case), "property" (a consumer
/// property), "consumer" (a scene's consumer).
struct Kind {
  std::string axis, name;
};
[[nodiscard]] bool operator<(const Kind& a, const Kind& b);
[[nodiscard]] bool operator==(const Kind& a, const Kind& b);

/// What became of the cases (or answers) of one kind over a run.
struct Counts {
  long made = 0;            ///< made, counted before their fate (by the ways in that count it)
  long judged = 0;          ///< reached the user's function and were judged
  long left_out = 0;        ///< not judged, each for a reason the tally keeps
  long unclaimed = 0;       ///< of left_out: inputs the contract does not claim (no gap in it)
  long refused = 0;         ///< refused by the function's accepts
  long not_applicable = 0;  ///< the property says nothing of them
};

class Tally {
 public:
  /// A case made, counted on its kinds before it is judged or left out (the made counts say
  /// which claimed kinds the cases drew at all).
  void made(const std::vector<Kind>& kinds);
  /// A case or an answer judged (`n` of them).
  void judged(const std::vector<Kind>& kinds, long n = 1);
  /// Not judged, for `why`; `claimed` false: an input the contract does not claim (said among the
  /// reasons, no gap in what it claims).
  void left_out(const std::vector<Kind>& kinds, const std::string& why, bool claimed = true,
                long n = 1);
  /// Refused by the accepts of the function named `by`.
  void refused(const std::vector<Kind>& kinds, const std::string& by);
  /// A property that says nothing of the case (`why`): neither judged nor a gap.
  void not_applicable(const std::vector<Kind>& kinds, const std::string& why, long n = 1);

  [[nodiscard]] Counts of(const Kind& kind) const;
  /// How many judged(), left_out() were counted (not per kind).
  [[nodiscard]] long judged() const { return judged_; }
  [[nodiscard]] long left_out() const { return left_out_; }
  /// Why cases were left out and how many each, over the run.
  [[nodiscard]] const std::map<std::string, long>& reasons() const { return reasons_; }
  /// Why a property did not apply, and how many each.
  [[nodiscard]] const std::map<std::string, long>& not_applicable_reasons() const {
    return not_applicable_;
  }
  /// The functions whose accepts refused a case, in the order first met.
  [[nodiscard]] const std::vector<std::string>& refusers() const { return refusers_; }
  /// One axis's kinds by name with one of their counts (a summary's "judged, by family").
  [[nodiscard]] std::map<std::string, long> by(const std::string& axis,
                                               long Counts::*count = &Counts::judged) const;
  /// Every kind met on `axis`, counted or not.
  [[nodiscard]] std::vector<Kind> met(const std::string& axis) const;

 private:
  std::map<Kind, Counts> counts_;
  std::map<std::string, long> reasons_, not_applicable_;
  std::vector<std::string> refusers_;
  long judged_ = 0, left_out_ = 0;
};

/// The kinds of a case (a cases::Case): its family, convention, and place (or defect, for an input
/// without an answer).
template <class Case>
[[nodiscard]] std::vector<Kind> kinds_of(const Case& c) {
  std::vector<Kind> out{{"family", std::string(cases::family_name(c.family))},
                        {"convention", std::string(convention_name(c.convention))}};
  if (c.defect)
    out.push_back({"defect", std::string(cases::defect_name(*c.defect))});
  else
    out.push_back({"place", std::string(cases::place_name(c.place))});
  return out;
}

/// The families and conventions a contract claims, in its order.
[[nodiscard]] std::vector<Kind> claims_of(const Contract& contract);

/// How a way in tells its user what to change, in its own terms. `leave_out(kind)` says how to
/// stop claiming a kind ("leave perspective out of the contract").
struct Advice {
  std::string claimant = "the contract claims";  ///< who claims the kinds
  std::string unit = "case";                     ///< what is judged: "case", "answer"
  std::string rounds = "cases";                  ///< what `rounds` counts
  /// Said instead of "none was drawn in N rounds" (a scene: no pass was rendered); empty: that.
  std::string none_drawn;
  std::string more = "raise --cases or --time-limit";  ///< what draws more
  std::string judge_left_out;  ///< what has left-out cases judged (empty: `more`)
  std::string widen_accepts = "widen accepts";
  std::string applicable;  ///< what gives a kind cases it applies to (empty: nothing to say)
  std::function<std::string(const Kind&)> leave_out = [](const Kind& k) {
    return "leave " + k.name + " out of the contract";
  };
};

/// A pass means judged: for each claimed kind of which nothing was judged in `rounds`, one line
/// saying why (none drawn, every one refused, left out or not applicable) and what to change.
/// Empty when each had something judged.
[[nodiscard]] std::vector<std::string> unjudged(const Tally& tally, const std::vector<Kind>& claims,
                                                long rounds, const Advice& advice);

/// A kind (family, convention, property) claimed with more than this share of its drawn cases
/// left out (not judged: within rounding of no answer, beyond a bound) is named in a warning line
/// of every way in's summary (a failure under their strict flags).
inline constexpr double kLeftOutWarning = 0.10;

/// Whether `left` of `drawn` cases of a kind left out is more than `share` beyond chance: the
/// lower end of the Wilson interval (one-sided 99.95%) of the share left out exceeds `share`. A
/// run of 13 cases with 2 left out is no pattern (the interval reaches down to 2%); 13,899 of
/// 111,575 is (12.1% at least). The one test of every way in's "judged in part only".
[[nodiscard]] bool left_out_beyond(long left, long drawn, double share = kLeftOutWarning);

/// The claimed kinds judged in part only: more than `share` of what the contract claims of them
/// left out (inputs it does not claim are not counted), as "NAME L of D, ..." (with the axis
/// first where `with_axis`); empty when none.
[[nodiscard]] std::string partly_judged(const Tally& tally, const std::vector<Kind>& claims,
                                        double share = kLeftOutWarning, bool with_axis = true);

/// The summary's warning line for kinds judged in part only (`partly`: "KIND L of D, ..."), for
/// the command-line ways in, saying what their --strict does.
[[nodiscard]] std::string partly_judged_warning(const std::string& partly, bool strict);

/// Counts by name as a summary says them: "name N, name N" ("none" when empty).
[[nodiscard]] std::string counts_text(const std::map<std::string, long>& counts);

}  // namespace oblique::run
