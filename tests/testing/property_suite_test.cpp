// The property suite: every property of the core issue, on generated inputs of every family,
// convention and hard place, for every selected implementation and scalar type.
//
// Default budget: RapidCheck's 100 cases per property. Longer: RC_PARAMS="max_success=5000".
// Replay: RC_PARAMS="seed=S" with the test's --gtest_filter (every report prints the command), or
// RapidCheck's own RC_PARAMS="reproduce=..." (the tests it does not name are skipped).
// Another implementation: OBLIQUE_IMPL=listing_5_1 (see implementations.h for the names); an
// unknown name fails every test. closedFormAndGeneralAgree and accurateMethodIsWithinTwoUlps are
// about the core's own methods: they skip, saying so, unless OBLIQUE_IMPL selects them.
// Answers are judged by the filtered checker (oracle/filtered.h), which hands every violation
// and every close call to the exact one.
#include "property_suite.h"

namespace oblique::oracle::suite {

using mistakes::core_method;
namespace {

using cases::Case;
using cases::Family;

template <class T>
void property_holds(Property which, Coverage coverage, const rc::Gen<Case<T>>& gen) {
  run_property(
      [=] {
        const Case<T> c = *gen;
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        count_generated(c);
        Checks checks;
        checks.properties = {which};
        if (for_each_answer(c, problem, checks)) count_judged(c);
      },
      coverage);
}

template <class T>
void invalid_inputs_get_their_status() {
  run_property(
      [] {
        const Case<T> c = *cases::invalid_case<T>();
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        count_generated(c);
        // An ok answer is allowed only in a gray zone, and must then have every property.
        Checks checks;
        checks.properties.assign(std::begin(all_properties), std::end(all_properties));
        if (for_each_answer(c, problem, checks, /*judge_statuses=*/true)) count_judged(c);
      },
      Coverage::invalid);
}

template <class T>
rc::Gen<Case<T>> perspective_shape_case() {
  return rc::gen::exec([] {
    const auto& families = cases::perspective_shape_families;
    return *cases::valid_case_of<T>(
        families[*rc::gen::inRange<std::size_t>(0, std::size(families))]);
  });
}

template <class T>
void closed_form_and_general_agree() {
  if (!runs_only_for({"core_closed_form", "core_general"})) GTEST_SKIP();
  run_property(
      [] {
        const Case<T> c = *perspective_shape_case<T>();
        const Problem<T> problem(c.matrix, c.plane, c.convention);
        RC_PRE(problem.exact_status() == Status::ok);
        count_generated(c);
        count_judged(c);  // the core's own methods, judged below
        ++tally().implementations["core_closed_form vs core_general"];
        const auto closed = apply<T>(c.matrix, c.plane, c.convention, Method::closed_form);
        const auto general = apply<T>(c.matrix, c.plane, c.convention, Method::general);
        if (!closed.ok() || !general.ok()) return;  // statuses are judged by the other properties
        const std::optional<oracle::exact::Vec> maybe_bounds = problem.row3_bounds();
        if (!maybe_bounds) return;  // within rounding of no answer: neither can be held to a bound
        const oracle::exact::Vec& bounds = *maybe_bounds;
        ++tally().applied["closed_form_and_general_agree"];
        for (int i = 0; i < 4; ++i) {
          const oracle::exact::Rational gap =
              oracle::exact::abs(oracle::exact::to_rational(closed.projection(2, i)) -
                                 oracle::exact::to_rational(general.projection(2, i)));
          if (gap <= 2 * bounds[i]) continue;
          Finding f;
          f.check = Check::methods_agree;
          f.column = i + 1;
          f.residual = gap.get_d();
          f.bound = oracle::exact::Rational(2 * bounds[i]).get_d();
          f.ratio = bounds[i] > 0 ? oracle::exact::Rational(gap / (2 * bounds[i])).get_d()
                                  : std::numeric_limits<double>::infinity();
          fail_with(c, core_method<T>(Method::closed_form), f);
        }
      },
      Coverage::perspective_shape);
}

/// The accurate method within oracle::tolerance::kAccurateUlps of the correctly rounded exact
/// answer, on every family, convention and hard place the generators make.
template <class T>
void accurate_method_is_within_its_ulps() {
  if (!runs_only_for({"core_accurate"})) GTEST_SKIP();
  run_property(
      [] {
        const Case<T> c = *cases::valid_case<T>();
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        RC_PRE(problem.exact_status() == Status::ok);
        count_generated(c);
        count_judged(c);  // the core's own methods, judged below
        ++tally().implementations["core_accurate (ulps)"];
        const auto result = apply<T>(c.matrix, c.plane, c.convention, Method::accurate);
        if (!result.ok()) return;  // statuses are judged by the other properties
        ++tally().applied["accurate_method_is_within_its_ulps"];
        Checks checks;
        checks.properties.clear();
        checks.max_ulps = oracle::tolerance::kAccurateUlps;
        const Answer<T> outcome{result.status, result.projection};
        const Judgement judgement = judge(problem, outcome, checks);
        if (const Finding* violation = judgement.violation())
          fail_with(c, core_method<T>(Method::accurate), *violation, &outcome);
      },
      Coverage::valid);
}

template <class T>
void extracted_planes_match() {
  run_property(
      [] {
        const Case<T> c = *cases::valid_case<T>();
        const FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
        count_generated(c);
        Checks checks;
        checks.properties = {Property::extracted_planes_match};
        if (for_each_answer(c, problem, checks)) count_judged(c);
      },
      Coverage::valid);
}

#define OBLIQUE_PROPERTY_SUITE(Suite, T)                                                       \
  TEST(Suite, nearPlaneIsTheClipPlane) {                                                       \
    property_holds<T>(Property::near_is_clip_plane, Coverage::valid, cases::valid_case<T>());  \
  }                                                                                            \
  TEST(Suite, sideRowsAreUnchanged) {                                                          \
    property_holds<T>(Property::side_rows_unchanged, Coverage::valid, cases::valid_case<T>()); \
  }                                                                                            \
  TEST(Suite, farPlanePassesThroughTheFarCorner) {                                             \
    property_holds<T>(Property::far_plane_through_corner, Coverage::valid,                     \
                      cases::valid_case<T>());                                                 \
  }                                                                                            \
  TEST(Suite, viewVolumeInFrontOfThePlaneIsNotClipped) {                                       \
    property_holds<T>(Property::no_clipping, Coverage::valid, cases::valid_case<T>());         \
  }                                                                                            \
  TEST(Suite, infiniteFarPlaneIsParallelToTheFrustumEdge) {                                    \
    property_holds<T>(Property::infinite_edge_parallel, Coverage::places_only,                 \
                      cases::valid_case_of<T>(Family::infinite));                              \
  }                                                                                            \
  TEST(Suite, invalidInputsGetTheirStatus) {                                                   \
    invalid_inputs_get_their_status<T>();                                                      \
  }                                                                                            \
  TEST(Suite, closedFormAndGeneralAgree) {                                                     \
    closed_form_and_general_agree<T>();                                                        \
  }                                                                                            \
  TEST(Suite, extractedFrustumPlanesMatch) {                                                   \
    extracted_planes_match<T>();                                                               \
  }                                                                                            \
  TEST(Suite, accurateMethodIsWithinTwoUlps) {                                                 \
    accurate_method_is_within_its_ulps<T>();                                                   \
  }

OBLIQUE_PROPERTY_SUITE(PropertiesFloat, float)
OBLIQUE_PROPERTY_SUITE(PropertiesDouble, double)
OBLIQUE_PROPERTY_SUITE(PropertiesLongDouble, long double)

}  // namespace
}  // namespace oblique::oracle::suite
