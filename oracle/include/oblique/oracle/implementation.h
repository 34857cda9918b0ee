// An implementation the suite judges: its name, the inputs it is for, how it answers and what it
// promises (the implementations the project knows: implementations.h; yours: adapter.h).
#pragma once

#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/oracle/vocabulary.h"
#include "oblique/plane.h"

namespace oblique::oracle {

template <class T>
struct Implementation {
  std::string name;
  /// Whether it answers statuses (the recipes return a matrix whatever the input).
  bool reports_statuses = true;
  /// Whether it refuses in its own words (a bool "no"): any refusal of an input without an answer
  /// is then right (StatusContract::any_refusal).
  bool own_refusals = false;
  /// The depth conventions it serves: a function that takes no convention serves the one stated
  /// to adapt(); the default contract's conventions are these.
  std::vector<Convention> conventions{std::begin(all_conventions), std::end(all_conventions)};
  /// The inputs it is meant for; others are not given to it.
  std::function<bool(Convention, const Matrix4<T>&)> accepts;
  std::function<Answer<T>(const Matrix4<T>&, const Vector4<T>&, Convention)> run;
  /// The accuracy it promises in ulps of the correctly rounded answer
  /// (oracle::exact::ulp_distance); infinity for none beyond the conditioning-aware bounds.
  double max_ulps = std::numeric_limits<double>::infinity();

  /// What it answered, in its own words: a void function answers, a bool one refuses by
  /// returning false, a Status one names the status.
  std::string answer_words(Status status) const {
    if (status == Status::ok) return reports_statuses ? "answered ok" : "answered";
    if (own_refusals) return "refused (returned false)";
    return "answered " + std::string(status_code(status));
  }

  /// How judge() treats its statuses.
  StatusContract status_contract() const {
    if (!reports_statuses) return StatusContract::answers_only;
    return own_refusals ? StatusContract::any_refusal : StatusContract::exact;
  }
  /// What judge() checks of its answers: every property under its status contract and, with
  /// `accuracy`, row 3 within its bound and the ulps it promises.
  Checks checks(bool accuracy = false) const {
    Checks out;
    out.statuses = status_contract();
    out.row3_accuracy = accuracy;
    if (accuracy) out.max_ulps = max_ulps;
    return out;
  }
};

}  // namespace oblique::oracle
