// The one judgement (oracle/judge.h): each status contract accepts and rejects what it says,
// each check is made only when asked, and `every` lists the checks that hold.
#include "oblique/oracle/judge.h"

#include <gtest/gtest.h>

#include "oblique/oracle/filtered.h"

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>

#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "printers.h"

namespace oblique::oracle {
namespace {

const Matrix4<double> kFrustum = frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, Convention::gl);
const Vector4<double> kPlane(0.25, 0.5, -1.0, -2.0);  // the camera behind it, C . Q > 0

Answer<double> core_answer() {
  const ObliqueResult<double> r = apply<double>(kFrustum, kPlane, Convention::gl);
  EXPECT_TRUE(r.ok()) << r.message();
  return Answer<double>{r.status, r.projection};
}

Checks with_statuses(StatusContract contract) {
  Checks checks;
  checks.statuses = contract;
  return checks;
}

TEST(Judge, theCoresAnswerHoldsEveryCheck) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Checks checks;
  checks.row3_accuracy = true;
  checks.max_ulps = 2;
  checks.every = true;
  const Judgement j = judge(problem, core_answer(), checks);
  EXPECT_TRUE(j.holds());
  std::vector<std::string> kinds;
  for (const Finding& f : j.checks) kinds.push_back(std::string(check_name(f.check)));
  // Properties 1-4 apply to a finite frustum (5 only to infinite ones), then the cross-checks.
  const std::vector<std::string> expected = {
      "near_is_clip_plane", "side_rows_unchanged",    "far_plane_through_corner",
      "no_clipping",        "extracted_planes_match", "row3_accuracy",
      "accurate_ulps"};
  EXPECT_EQ(kinds, expected);
}

TEST(Judge, anOkAnswerToAnInputWithoutOneFailsEveryContract) {
  const Vector4<double> in_front(0.0, 0.0, -1.0, 2.0);  // C_w > 0: camera_not_behind_plane
  const Problem<double> problem(kFrustum, in_front, Convention::gl);
  ASSERT_EQ(problem.exact_status(), Status::camera_not_behind_plane);
  for (StatusContract contract :
       {StatusContract::exact, StatusContract::any_refusal, StatusContract::answers_only}) {
    const Judgement j =
        judge(problem, Answer<double>{Status::ok, kFrustum}, with_statuses(contract));
    ASSERT_NE(j.violation(), nullptr);
    EXPECT_EQ(check_name(j.violation()->check), "status");
    EXPECT_EQ(j.violation()->answered, Status::ok);
    EXPECT_EQ(j.violation()->allowed, std::vector<Status>{Status::camera_not_behind_plane});
  }
}

TEST(Judge, aWrongRefusalFailsOnlyTheExactContract) {
  const Vector4<double> in_front(0.0, 0.0, -1.0, 2.0);
  const Problem<double> problem(kFrustum, in_front, Convention::gl);
  const Answer<double> wrong_code{Status::singular_projection, kFrustum};
  const Judgement exact = judge(problem, wrong_code, with_statuses(StatusContract::exact));
  ASSERT_NE(exact.violation(), nullptr);
  EXPECT_EQ(check_name(exact.violation()->check), "status");
  EXPECT_EQ(exact.violation()->answered, Status::singular_projection);
  EXPECT_TRUE(judge(problem, wrong_code, with_statuses(StatusContract::any_refusal)).holds());
  EXPECT_TRUE(judge(problem, wrong_code, with_statuses(StatusContract::answers_only)).holds());
}

TEST(Judge, refusingAnInputWithAnAnswerFailsUnlessStatusesAreNotReported) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  const Answer<double> refused{Status::camera_not_behind_plane, kFrustum};
  for (StatusContract contract : {StatusContract::exact, StatusContract::any_refusal}) {
    const Judgement j = judge(problem, refused, with_statuses(contract));
    ASSERT_NE(j.violation(), nullptr);
    EXPECT_EQ(check_name(j.violation()->check), "status");
    EXPECT_EQ(j.violation()->allowed, std::vector<Status>{Status::ok});
  }
  EXPECT_TRUE(judge(problem, refused, with_statuses(StatusContract::answers_only)).holds());
}

TEST(Judge, aRefusalInItsOwnWordsWhereRoundingAllowsOnePassesAnyRefusal) {
  // An infinite float frustum and a plane within rounding of its far corner (found by fuzzing
  // the downstream example): the exact answer exists, but rounding allows a refusal.
  Matrix4<float> m;
  m << 0.5616438356164384f, 0, 0.9452054794520548f, 0, 0, 1.9069767441860466f, 0.9069767441860465f,
      0, 0, 0, -1, -10.25f, 0, 0, -1, 0;
  const Vector4<float> plane(-0.0f, 5.125f, 5.125f, -7.75f);
  const Problem<float> problem(m, plane, Convention::gl);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  const auto acceptable = problem.acceptable_statuses();
  ASSERT_NE(std::find(acceptable.begin(), acceptable.end(), Status::plane_misses_view_volume),
            acceptable.end());
  const Answer<float> own_words{Status::invalid_input, m};
  EXPECT_TRUE(judge(problem, own_words, with_statuses(StatusContract::any_refusal)).holds());
  const Judgement exact = judge(problem, own_words, with_statuses(StatusContract::exact));
  ASSERT_NE(exact.violation(), nullptr);
  EXPECT_EQ(exact.violation()->answered, Status::invalid_input);
}

TEST(Judge, aNonFiniteAnswerIsNamedFirst) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Answer<double> answer = core_answer();
  answer.projection(2, 0) = std::numeric_limits<double>::quiet_NaN();
  const Judgement j = judge(problem, answer);
  ASSERT_NE(j.violation(), nullptr);
  EXPECT_EQ(check_name(j.violation()->check), "finite_result");
  // Even when every check is asked for, nothing after it (the exact checks take finite entries).
  Checks every;
  every.every = true;
  every.row3_accuracy = true;
  every.max_ulps = 2;
  const Judgement all = judge(problem, answer, every);
  ASSERT_EQ(all.checks.size(), 1u);
  EXPECT_EQ(check_name(all.checks[0].check), "finite_result");
}

TEST(Judge, onlyTheSelectedPropertiesAreChecked) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Answer<double> answer = core_answer();
  answer.projection(0, 0) *= 2;  // a changed side row; row 3 (and the near plane) untouched
  Checks near_only;
  near_only.properties = {Property::near_is_clip_plane};
  const Judgement near = judge(problem, answer, near_only);
  EXPECT_TRUE(near.holds());
  ASSERT_EQ(near.checks.size(), 1u);
  EXPECT_EQ(check_name(near.checks[0].check), "near_is_clip_plane");
  Checks sides_only;
  sides_only.properties = {Property::side_rows_unchanged};
  const Judgement sides = judge(problem, answer, sides_only);
  ASSERT_NE(sides.violation(), nullptr);
  EXPECT_EQ(check_name(sides.violation()->check), "side_rows_unchanged");
}

TEST(Judge, aChangedSignOfZeroInTheSideRowsIsNotAViolation) {
  // A y-flipped frustum has zeros in rows 1, 2 and 4; an answer that wrote them back as +0 (or
  // -0) describes the same side planes.
  Matrix4<double> flipped = kFrustum;
  flipped.row(1) *= -1;
  const Problem<double> problem(flipped, kPlane, Convention::gl);
  const ObliqueResult<double> r = apply<double>(flipped, kPlane, Convention::gl);
  ASSERT_TRUE(r.ok()) << r.message();
  Answer<double> answer{r.status, r.projection};
  int flips = 0;
  for (int row : {0, 1, 3}) {
    for (int j = 0; j < 4; ++j) {
      if (answer.projection(row, j) == 0) {
        answer.projection(row, j) = -answer.projection(row, j);
        ++flips;
      }
    }
  }
  ASSERT_GT(flips, 0);
  EXPECT_TRUE(judge(problem, answer).holds());
  // A real change of a side row is still caught, however small.
  answer.projection(1, 1) = std::nextafter(answer.projection(1, 1), 0.0);
  const Judgement changed = judge(problem, answer);
  ASSERT_NE(changed.violation(), nullptr);
  EXPECT_EQ(check_name(changed.violation()->check), "side_rows_unchanged");
}

TEST(Judge, stopsAtTheFirstViolationUnlessEveryIsAsked) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Answer<double> answer = core_answer();
  answer.projection(0, 0) *= 2;
  const Judgement first = judge(problem, answer);
  ASSERT_NE(first.violation(), nullptr);
  EXPECT_EQ(first.violation(), &first.checks.back());
  Checks every;
  every.every = true;
  const Judgement all = judge(problem, answer, every);
  EXPECT_EQ(all.violation()->check, first.violation()->check);
  EXPECT_GT(all.checks.size(), first.checks.size());
}

TEST(Judge, rowThreeAccuracyAndTheUlpsPromiseAreCheckedWhenAsked) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Answer<double> answer = core_answer();
  answer.projection(2, 3) *= 1 + 1e-9;  // far beyond the bound of careful double arithmetic
  Checks none;
  none.properties.clear();
  EXPECT_TRUE(judge(problem, answer, none).holds());
  Checks accuracy = none;
  accuracy.row3_accuracy = true;
  const Judgement j = judge(problem, answer, accuracy);
  ASSERT_NE(j.violation(), nullptr);
  EXPECT_EQ(check_name(j.violation()->check), "row3_accuracy");
  EXPECT_GT(j.violation()->ratio, 1);

  Answer<double> one_ulp = core_answer();
  one_ulp.projection(2, 3) = std::nextafter(one_ulp.projection(2, 3), 0.0);
  Checks ulps = none;
  ulps.max_ulps = 2;
  const double measured = problem.ulps_from_exact(one_ulp.projection);
  EXPECT_EQ(judge(problem, one_ulp, ulps).holds(), measured <= 2) << measured;
  ulps.max_ulps = 0;
  const Judgement strict = judge(problem, one_ulp, ulps);
  ASSERT_NE(strict.violation(), nullptr);
  EXPECT_EQ(check_name(strict.violation()->check), "accurate_ulps");
}

// oracle::not_judged(): what the input is decides whether an implementation is judged on it.
TEST(NotJudged, anInputWithinRoundingOfTheFarCornerIsLeftOutOnlyForWhatCannotRefuse) {
  // The case a correct engine without statuses was flagged on (wrong side: C . Q rounds to < 0
  // in its double arithmetic): C passes, within rounding, through the far corner of a frustum.
  Matrix4<double> m;
  m << 1.0 / 3, 0, 0, 0, 0, 2.0 / 3, 0, 0, 0, 0, -3, -4, 0, 0, -1, 0;
  const Vector4<double> plane(0, 0.5547001962252291, 0.8320502943378437, -4.919510551012827e-17);
  const Problem<double> problem(m, plane, Convention::gl);
  const FilteredProblem<double> filtered(m, plane, Convention::gl);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  const std::string why = "inputs undecidable in double (C . Q within rounding of 0)";
  EXPECT_EQ(not_judged(problem, StatusContract::answers_only), why);
  EXPECT_EQ(not_judged(filtered, StatusContract::answers_only), why);
  EXPECT_EQ(not_judged(problem, StatusContract::any_refusal), "");
  EXPECT_EQ(not_judged(problem, StatusContract::exact), "");
  // A list of refusals: judged when one the input allows is in it.
  EXPECT_EQ(not_judged(problem, StatusContract::exact, {Status::camera_not_behind_plane}), why);
  EXPECT_EQ(not_judged(problem, StatusContract::exact, {Status::plane_misses_view_volume}), "");
  // In long double the same input is decidable: the rule depends on the precision.
  const Problem<long double> wide(m.cast<long double>(), plane.cast<long double>(), Convention::gl);
  EXPECT_EQ(not_judged(wide, StatusContract::answers_only), "");
}

TEST(NotJudged, inputsWithoutAnAnswerAreLeftOutWhereTheirStatusIsMissing) {
  const Vector4<double> in_front(0.0, 0.0, -1.0, 2.0);  // camera_not_behind_plane
  const Problem<double> problem(kFrustum, in_front, Convention::gl);
  EXPECT_EQ(not_judged(problem, StatusContract::answers_only), "inputs without an answer");
  EXPECT_EQ(not_judged(problem, StatusContract::exact, {Status::plane_misses_view_volume}),
            "inputs needing status camera_not_behind_plane");
  EXPECT_EQ(not_judged(problem, StatusContract::exact, {Status::camera_not_behind_plane}), "");
  EXPECT_EQ(not_judged(problem, StatusContract::any_refusal), "");
  // An ordinary input is judged under every contract.
  const Problem<double> ordinary(kFrustum, kPlane, Convention::gl);
  for (StatusContract contract :
       {StatusContract::exact, StatusContract::any_refusal, StatusContract::answers_only})
    EXPECT_EQ(not_judged(ordinary, contract), "");
  EXPECT_EQ(not_judged(ordinary, StatusContract::exact, {Status::camera_not_behind_plane}), "");
}

// Property 1 and what no rasterizer sees: a component far below the plane's norm may be lost
// (an implementation that scales C by a power of two loses it), a visible change may not.
template <class T>
void near_plane_allowance() {
  const Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 10, Convention::gl);
  const T tiny = std::numeric_limits<T>::min() * 64;  // a component ~1e-36 (float) of the plane
  const Vector4<T> plane(tiny, T(0.5), T(-1), T(-2));
  const ObliqueResult<T> r = apply<T>(m, plane, Convention::gl);
  ASSERT_TRUE(r.ok()) << r.message();
  const Problem<T> problem(m, plane, Convention::gl);
  const FilteredProblem<T> filtered(m, plane, Convention::gl);
  Checks near_only;
  near_only.properties = {Property::near_is_clip_plane};
  ASSERT_TRUE(judge(problem, Answer<T>{r.status, r.projection}, near_only).holds());
  // Dropped: near'_1 = M'_31 + M'_41 = 0 instead of lambda tiny.
  Answer<T> dropped{Status::ok, r.projection};
  dropped.projection(2, 0) = T(0);
  Checks all;
  all.every = true;
  for (const Judgement& j : {judge(problem, dropped, all), judge(filtered, dropped, all)}) {
    for (const Finding& f : j.checks)
      EXPECT_TRUE(f.holds) << check_name(f.check) << ": " << residual_text(f);
  }
  // A change of that coefficient a rasterizer sees, 8 u lambda max|C|: a violation.
  const T lambda = r.projection(2, 1) / plane(1);  // near'_2 = M'_32 (M_42 = 0) = lambda C_2
  Answer<T> moved{Status::ok, r.projection};
  moved.projection(2, 0) = 8 * std::numeric_limits<T>::epsilon() / 2 * lambda * T(2);
  for (const Judgement& j : {judge(problem, moved, near_only), judge(filtered, moved, near_only)}) {
    ASSERT_NE(j.violation(), nullptr);
    EXPECT_EQ(check_name(j.violation()->check), "near_is_clip_plane");
  }
}

TEST(NearPlane, aComponentFarBelowThePlanesNormMayBeLostButNotVisiblyChanged) {
  near_plane_allowance<float>();
  near_plane_allowance<double>();
  near_plane_allowance<long double>();
}

// A [0, 1] row 3 formed in T from the GL one, (M'_3(gl) + M_4) / 2 (the same near plane: an
// engine that builds the GL row and converts), is judged by what its rounding does: the GL row's
// |M_4| term carried through the conversion (tolerance.h, kConversionRoundings). Its entry where
// M_4 is not 0 may be many ulps of the row's largest entry off where lambda C is small (an
// orthographic box whose far corner lies far along C: the w entry, M_4w = 1), and still holds; a
// change of that entry well past the allowance, 64 u (|M_4| + lambda max|C|), is seen by a
// rasterizer and fails.
template <class T>
void zero_one_row_from_gl(bool box) {
  auto make = [box](Convention k) {
    return box ? orthographic<T>(T(-10), T(10), T(-10), T(10), T(0.1), T(1000), k)
               : frustum<T>(T(-0.0577), T(0.0577), T(-0.0577), T(0.0577), T(0.1), T(100), k);
  };
  const Matrix4<T> m = make(Convention::zero_one), m_gl = make(Convention::gl);
  ASSERT_EQ(m.row(3), m_gl.row(3));
  const int entry = box ? 3 : 2;  // where M_4 is not 0
  Checks near_only;
  near_only.properties = {Property::near_is_clip_plane};
  const T u = std::numeric_limits<T>::epsilon() / 2;
  int judged = 0;
  for (const T tilt : {T(0), T(0.01), T(0.1), T(0.5)}) {
    for (const T h : {T(0.05), T(0.5), T(1.6), T(5), T(20)}) {
      const Vector4<T> plane(T(0.3) * tilt, T(1), -tilt, -h);
      const ObliqueResult<T> gl = apply<T>(m_gl, plane, Convention::gl);
      if (!gl.ok()) continue;
      Matrix4<T> converted = m;
      for (int j = 0; j < 4; ++j)
        converted(2, j) = (gl.projection(2, j) + m(3, j)) * T(0.5);  // in T, as the engine does
      const Problem<T> problem(m, plane, Convention::zero_one);
      if (problem.exact_status() != Status::ok) continue;
      ++judged;
      const Judgement held = judge(problem, Answer<T>{Status::ok, converted}, near_only);
      EXPECT_TRUE(held.holds()) << (box ? "box" : "frustum") << ", tilt " << tilt << ", h " << h
                                << ": " << residual_text(*held.violation());
      // A change a rasterizer sees: 64 u (|M_4| + lambda max|C|) more in that entry (past its own
      // allowance and what a change of lambda within the other entries' can absorb).
      T row_max = 0;
      for (int j = 0; j < 4; ++j) row_max = std::max(row_max, std::abs(converted(2, j)));
      Matrix4<T> moved = converted;
      moved(2, entry) += 64 * u * (std::abs(m(3, entry)) + row_max);
      const Judgement seen = judge(problem, Answer<T>{Status::ok, moved}, near_only);
      ASSERT_NE(seen.violation(), nullptr) << "tilt " << tilt << ", h " << h;
      EXPECT_EQ(check_name(seen.violation()->check), "near_is_clip_plane");
    }
  }
  EXPECT_GE(judged, 15);
}

TEST(NearPlane, aZeroOneRowConvertedFromTheGlRowHoldsAndAVisibleChangeDoesNot) {
  for (const bool box : {false, true}) {
    zero_one_row_from_gl<float>(box);
    zero_one_row_from_gl<double>(box);
  }
}

// Every check has its own name, read back to itself; a property's check is the property's.
TEST(Findings, everyCheckHasOneNameReadBackToItself) {
  std::set<std::string> names;
  for (int i = 0; i <= static_cast<int>(Check::protocol); ++i) {
    const Check c = static_cast<Check>(i);
    const std::string name(check_name(c));
    EXPECT_NE(name, "unknown") << i;
    EXPECT_TRUE(names.insert(name).second) << name << " names two checks";
    EXPECT_EQ(parse_check(name), c) << name;
  }
  EXPECT_EQ(parse_check("near_is_clip_plan"), std::nullopt);
  for (Property p : all_properties) {
    EXPECT_EQ(property_of(check_of(p)), p);
    EXPECT_EQ(check_name(check_of(p)), property_name(p));
  }
  EXPECT_EQ(property_of(Check::row3_accuracy), std::nullopt);
}

// The words are made from the finding's numbers, when written: a violated no_clipping at a corner
// says the value and the bound it holds, and its JSON numbers are the same numbers.
TEST(Findings, theWordsComeFromTheNumbers) {
  Finding f;
  f.check = Check::no_clipping;
  f.shows = Shows::below_at_corner;
  f.residual = -3.5;
  f.bound = 0.25;
  f.ratio = 14;
  EXPECT_EQ(relation_text(f),
            "far' . p >= -bound at every vertex p of the view volume with C . p >= 0");
  EXPECT_EQ(residual_text(f), "far' . p = -3.5 at a corner");
  EXPECT_EQ(bound_text(f), "-0.25");
  f.shows = Shows::below_at_edge_crossing;
  f.residual = -0.5;
  EXPECT_EQ(residual_text(f), "far' . p = -0.5 at an edge crossing of C");
  const auto numbers = finding_numbers(f);
  ASSERT_EQ(numbers.size(), 2u);
  EXPECT_EQ(numbers[0], std::make_pair(std::string("residual"), -0.5));
  EXPECT_EQ(numbers[1], std::make_pair(std::string("bound"), 0.25));
  Finding status;
  status.check = Check::status;
  status.shows = Shows::statuses;
  status.answered = Status::ok;
  status.exact = Status::camera_not_behind_plane;
  status.allowed = {Status::camera_not_behind_plane, Status::invalid_input};
  EXPECT_EQ(sides_text(status, "  "),
            "  expected: camera_not_behind_plane or invalid_input\n  got:      ok\n");
  EXPECT_EQ(relation_text(status), "an input without an answer is refused");
  EXPECT_TRUE(finding_numbers(status).empty());
}

// A check that is a yes or a no has no ratio, not a large number standing for one.
TEST(Findings, aYesOrNoCheckHasNoRatio) {
  const Problem<double> problem(kFrustum, kPlane, Convention::gl);
  Answer<double> changed = core_answer();
  changed.projection(0, 0) += 1;
  Checks sides;
  sides.properties = {Property::side_rows_unchanged};
  const Judgement j = judge(problem, changed, sides);
  ASSERT_NE(j.violation(), nullptr);
  EXPECT_EQ(j.violation()->check, Check::side_rows_unchanged);
  EXPECT_FALSE(j.violation()->ratio.has_value());
  EXPECT_EQ(j.violation()->shows, Shows::entry);
  EXPECT_EQ(j.violation()->row, 1);
  EXPECT_EQ(j.violation()->column, 1);
  EXPECT_EQ(j.violation()->value, changed.projection(0, 0));
  EXPECT_EQ(j.violation()->reference, kFrustum(0, 0));
}

}  // namespace
}  // namespace oblique::oracle
