// check_consumers(): the code around the matrix (oblique::Consumers) against the
// consumer properties (oblique/oracle/consumers.h), one RapidCheck run per property, for
// float, double and long double.
#include <functional>
#include <iostream>
#include <sstream>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oblique.h"
#include "oblique/report/report_files.h"
#include "oblique/testing/harness.h"

namespace oblique::testing {

namespace {

/// Fails the current case with the finding, and keeps the report the run writes if it is the
/// last (most shrunk) failure.
void fail(const std::string& consumer, const oracle::ConsumerFinding& finding,
          const std::string& inputs,
          std::function<std::string(report::ReportFiles&, const std::string&)> pictures) {
  tally().markdown_failure = report::consumer_report_markdown(consumer, finding, inputs);
  tally().markdown_pictures = std::move(pictures);
  tally().failure.reset();
  fail_case(consumer + " violates " + oracle::describe(finding) + "\n" + inputs);
}

/// Counts the finding; fails the case when it is violated (with the pictures of the case when it
/// is an oblique matrix's: M's volume, C, the core's M' and the finding's points).
template <class T>
void judged(const std::string& consumer, const oracle::ConsumerFinding& finding,
            const std::string& inputs, const cases::Case<T>* c) {
  if (!finding.judged) {
    // Counted against the family only where the contract claims the case (ConsumerFinding::
    // Unjudged: not an input without an answer, nor a property that says nothing of the matrix).
    count_left_out(c ? run::kinds_of(*c) : std::vector<run::Kind>{{"consumer", consumer}},
                   finding.detail, "",
                   finding.unjudged != oracle::ConsumerFinding::Unjudged::undecided);
    return;
  }
  ++tally().applied[std::string(oracle::consumer_check_name(finding.check))];
  if (finding.holds) return;
  // Shrinking can end on a case where the answer is within half of the digits of the correct
  // one (it names no cause there): the cause the first failing case named is kept, said so.
  if (!finding.likely_cause.empty() && tally().first_consumer_cause.empty())
    tally().first_consumer_cause = finding.likely_cause;
  if (finding.likely_cause.empty() && !tally().first_consumer_cause.empty()) {
    oracle::ConsumerFinding carried = finding;
    carried.likely_cause = tally().first_consumer_cause + mistakes::kNamedBeforeShrinking;
    return judged(consumer, carried, inputs, c);
  }
  std::function<std::string(report::ReportFiles&, const std::string&)> pictures;
  if (c) {
    pictures = [c = *c, finding, consumer](report::ReportFiles& files, const std::string& stem) {
      return report::stage_consumer_pictures(files, stem, c.matrix, c.plane, c.convention, finding,
                                             consumer);
    };
  } else if (!finding.drawn.empty()) {
    pictures = [finding, consumer](report::ReportFiles& files, const std::string& stem) {
      return report::stage_drawn_pictures(files, stem, finding, consumer);
    };
  }
  fail(consumer, finding, inputs, std::move(pictures));
}

/// One property's run: a case of the contract (one with an answer, for the functions that take
/// an oblique matrix), one consumer round with only `only` given, and the findings of `check`.
template <class T>
void run_check(const oblique::Consumers<T>& only, oracle::ConsumerCheck check, Contract contract) {
  const bool needs_oblique = only.view_position || only.linear_depth || only.world_position ||
                             only.culling_planes || only.corners;
  const std::string property(oracle::consumer_check_name(check));
  if (needs_oblique) {
    // The families the property has something to judge on (not_applicable()), said once.
    std::vector<cases::Family> applicable;
    std::string left;
    for (cases::Family f : contract.families) {
      const std::string_view why = oracle::not_applicable(check, f);
      if (why.empty()) {
        applicable.push_back(f);
      } else {
        append_item(left, std::string(cases::family_name(f)) + " (" + std::string(why) + ")");
      }
    }
    if (!left.empty()) std::cout << property << ": not applicable to " << left << "\n";
    if (applicable.empty()) {
      ADD_FAILURE() << run_id(property) << ": nothing to judge: " << property
                    << " is not applicable to any family of the contract (" << left
                    << "): widen the contract's families or leave this function out";
      return;
    }
    contract.families = std::move(applicable);
  }
  run(
      [=] {
        cases::Case<T> c{};
        if (needs_oblique) {
          c = *cases::valid_case_for<T>(contract);
          RC_PRE(apply<T>(c.matrix, c.plane, c.convention).status == Status::ok);
          count_generated(c);
          // A camera the functions are not for: counted refused, never judged (a claimed family
          // with every case refused fails the run, saying so).
          if (only.accepts && !only.accepts(c.convention, c.matrix)) {
            count_left_out(run::kinds_of(c), "", only.name);
            return;
          }
        }
        ++tally().implementations[only.name];
        bool counted = false;  // a round's first judged finding counts its case judged
        oracle::consumer_round<T>(
            c.matrix, c.plane, c.convention, only, cases::rc_pick,
            [&](const oracle::ConsumerFinding& f, const std::string& inputs, bool oblique) {
              if (f.check != check) return;
              if (f.judged && needs_oblique && !counted) {
                count_judged(c);
                counted = true;
              }
              const std::string which =
                  oblique ? "- case: family " + std::string(cases::family_name(c.family)) +
                                ", place " + std::string(cases::place_name(c.place)) + "\n"
                          : "";
              judged(only.name, f, which + inputs, oblique ? &c : nullptr);
            },
            mistakes::explain_consumer<T>);
        // A case whose every finding was left out (counted so) is discarded, and RapidCheck
        // draws another of the same size, so of the same family: the run's count is of cases
        // judged (a family with none would end in RapidCheck's "too many discards").
        if (needs_oblique && !counted) RC_DISCARD("nothing of " + property + " could be judged");
      },
      needs_oblique ? Coverage::valid : Coverage::none, property, contract);
}

}  // namespace

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
void check_consumers(const oblique::Consumers<T>& consumers, const Contract& given) {
  const Contract contract =
      resolved(given, cases::every_convention(), cases::StatusContract::exact, false);
  bool any = false;
  using Check = oracle::ConsumerCheck;
  auto with = [&](auto member, std::initializer_list<Check> checks) {
    if (!(consumers.*member)) return;
    any = true;
    oblique::Consumers<T> only = settings_of(consumers);
    only.*member = consumers.*member;
    for (const Check check : checks) run_check(only, check, contract);
  };
  using C = oblique::Consumers<T>;
  with(&C::view_position, {Check::view_position});
  with(&C::linear_depth, {Check::linear_depth});
  with(&C::world_position, {Check::world_position});
  with(&C::culling_planes, {Check::culling_keeps_visible, Check::culling_near_is_c});
  with(&C::camera_plane, {Check::plane_on_surface, Check::plane_kept_side});
  with(&C::mirror_view, {Check::mirror_view});
  with(&C::portal_view, {Check::portal_view});
  with(&C::corners, {Check::corners_contain_kept});
  if (!any) ADD_FAILURE() << consumers.name << ": oblique::Consumers gives no function to check";
}

template void check_consumers<float>(const oblique::Consumers<float>&, const Contract&);
template void check_consumers<double>(const oblique::Consumers<double>&, const Contract&);
template void check_consumers<long double>(const oblique::Consumers<long double>&, const Contract&);

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing
