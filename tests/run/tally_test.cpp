// The run's tally and the gate a pass goes through (oblique/run/tally.h): every way in counts
// with it and says its unjudged claims with it, so each of the gate's answers is checked here.
#include "oblique/run/tally.h"

#include <gtest/gtest.h>

#include "oblique/cases/case_builder.h"

namespace oblique::run {
namespace {

const Kind kPerspective{"family", "perspective"};
const Kind kInfinite{"family", "infinite"};
const Kind kGl{"convention", "gl"};

// "Judged in part only" is a share beyond chance: a handful of cases with two left out is no
// pattern, a hundred thousand with an eighth left out is. (The engine suite's default 100 cases
// gave "jittered 2 of 13" and failed OBLIQUE_STRICT=1 on correct code.)
TEST(LeftOut, aShareCountsOnlyBeyondChance) {
  EXPECT_FALSE(left_out_beyond(0, 100));
  EXPECT_FALSE(left_out_beyond(1, 1));          // one case is no pattern
  EXPECT_FALSE(left_out_beyond(2, 13));         // 15% seen, 2% at least
  EXPECT_FALSE(left_out_beyond(15, 100));       // 15% seen, 7% at least
  EXPECT_TRUE(left_out_beyond(25, 100));        // 25% seen, 13.7% at least
  EXPECT_TRUE(left_out_beyond(13899, 111575));  // 12.5% of a long run, 12.1% at least
  EXPECT_FALSE(left_out_beyond(5213, 102889));  // 5% of a long run
  EXPECT_TRUE(left_out_beyond(2, 2));
  EXPECT_FALSE(left_out_beyond(30, 100, 0.5));
  EXPECT_TRUE(left_out_beyond(80, 100, 0.5));
}

TEST(Tally, countsEachCaseOnEachOfItsKinds) {
  Tally t;
  t.made({kPerspective, kGl});
  t.judged({kPerspective, kGl});
  t.judged({kInfinite, kGl}, 3);
  t.left_out({kPerspective, kGl}, "within rounding of no answer");
  t.left_out({kPerspective}, "no answer", /*claimed=*/false, 2);
  t.refused({kInfinite}, "upright_only");
  t.refused({kInfinite}, "upright_only");
  t.not_applicable({kInfinite}, "an unbounded kept region");
  EXPECT_EQ(t.judged(), 4);
  EXPECT_EQ(t.left_out(), 3);
  const Counts p = t.of(kPerspective);
  EXPECT_EQ(p.made, 1);
  EXPECT_EQ(p.judged, 1);
  EXPECT_EQ(p.left_out, 3);
  EXPECT_EQ(p.unclaimed, 2);
  const Counts i = t.of(kInfinite);
  EXPECT_EQ(i.judged, 3);
  EXPECT_EQ(i.refused, 2);
  EXPECT_EQ(i.not_applicable, 1);
  EXPECT_EQ(t.of(kGl).judged, 4);
  EXPECT_EQ(t.of({"family", "x_flipped"}).judged, 0);
  EXPECT_EQ(counts_text(t.by("family")), "infinite 3, perspective 1");
  EXPECT_EQ(counts_text(t.by("family", &Counts::refused)), "infinite 2");
  EXPECT_EQ(counts_text(t.reasons()), "no answer 2, within rounding of no answer 1");
  EXPECT_EQ(t.refusers(), std::vector<std::string>{"upright_only"});
  EXPECT_EQ(t.met("convention").size(), 1u);
  EXPECT_EQ(counts_text({}), "none");
}

TEST(Tally, aCaseHasItsFamilyConventionAndPlaceOrDefect) {
  cases::Case<double> c{};
  c.family = cases::Family::infinite;
  c.convention = Convention::zero_one;
  c.place = cases::Place::scaled;
  std::vector<Kind> k = kinds_of(c);
  ASSERT_EQ(k.size(), 3u);
  EXPECT_EQ(k[0], (Kind{"family", "infinite"}));
  EXPECT_EQ(k[1], (Kind{"convention", "zero_one"}));
  EXPECT_EQ(k[2], (Kind{"place", "scaled"}));
  c.defect = cases::Defect::singular;
  k = kinds_of(c);
  EXPECT_EQ(k[2], (Kind{"defect", "singular"}));
}

// Each way the gate can find a claimed kind with nothing judged says why, in its own words, and
// what to change; a kind with one case judged passes whatever else became of its cases.
TEST(Gate, saysWhyEachClaimedKindHadNothingJudged) {
  Advice advice;
  advice.judge_left_out = "list the statuses";
  advice.applicable = "add a surface it applies to";
  const Kind drawn_none{"family", "x_flipped"}, refused{"family", "y_flipped"},
      left{"family", "jittered"}, both{"family", "off_axis"}, inapplicable{"property", "corners"};
  Tally t;
  t.judged({kPerspective, kGl});
  t.left_out({kPerspective}, "beyond a bound", true, 40);  // judged once: no gap
  t.refused({refused}, "upright_only");
  t.refused({refused}, "upright_only");
  t.left_out({left}, "within rounding of no answer", true, 3);
  t.refused({both}, "upright_only");
  t.left_out({both}, "within rounding of no answer");
  t.not_applicable({inapplicable}, "an unbounded kept region", 4);
  const std::vector<std::string> lines =
      unjudged(t, {kPerspective, kGl, drawn_none, refused, left, both, inapplicable}, 7, advice);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0],
            "the contract claims family x_flipped, and no case of it was judged: none was drawn in "
            "7 cases: raise --cases or --time-limit, or leave x_flipped out of the contract");
  EXPECT_EQ(lines[1],
            "the contract claims family y_flipped, and no case of it was judged: all 2 refused by "
            "accepts (upright_only): widen accepts, or leave y_flipped out of the contract");
  EXPECT_EQ(lines[2],
            "the contract claims family jittered, and no case of it was judged: all 3 left out "
            "(why, over the run: beyond a bound 40, within rounding of no answer 4): list the "
            "statuses, or leave jittered out of the contract");
  EXPECT_NE(lines[3].find("off_axis, and no case of it was judged: 1 refused by accepts, 1 left "
                          "out (why, over the run: "),
            std::string::npos)
      << lines[3];
  EXPECT_EQ(lines[4],
            "the contract claims property corners, and no case of it was judged: it applies to "
            "none of the 4 cases (an unbounded kept region 4): leave corners out of the "
            "contract, or add a surface it applies to");
  // The way in's words: who claims, what is counted, how to stop claiming a kind.
  advice.claimant = "the scene names";
  advice.unit = "answer";
  advice.none_drawn = "no pass was rendered";
  advice.more = "move the camera";
  advice.leave_out = [](const Kind& k) { return "leave " + k.name + " out of \"consumers\""; };
  EXPECT_EQ(unjudged(t, {{"consumer", "culling"}}, 0, advice).front(),
            "the scene names consumer culling, and no answer of it was judged: no pass was "
            "rendered: move the camera, or leave culling out of \"consumers\"");
  EXPECT_TRUE(unjudged(t, {kPerspective, kGl}, 7, advice).empty());
}

TEST(Gate, namesKindsJudgedInPartOnlyCountingWhatTheContractClaims) {
  Tally t;
  t.judged({kPerspective}, 70);
  t.left_out({kPerspective}, "beyond a bound", true, 30);
  t.judged({kInfinite}, 70);
  t.left_out({kInfinite}, "no answer", /*claimed=*/false, 30);  // not a gap in what it claims
  EXPECT_EQ(partly_judged(t, {kPerspective, kInfinite}), "family perspective 30 of 100");
  EXPECT_EQ(partly_judged(t, {kPerspective}, kLeftOutWarning, false), "perspective 30 of 100");
  EXPECT_EQ(partly_judged(t, {kPerspective}, 0.5), "");
  EXPECT_EQ(partly_judged(t, {kInfinite}), "");
  EXPECT_NE(partly_judged_warning("perspective 30 of 100", true).find("[--strict: not a pass]"),
            std::string::npos);
}

}  // namespace
}  // namespace oblique::run
