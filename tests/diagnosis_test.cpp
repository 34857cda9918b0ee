// The diagnosis (diagnosis.h) names each catalogued mistake as itself and as no other, a pair of
// mistakes as the pair, and nothing for a correct answer with noise or for a mistake the
// catalogue does not know.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"
#include "oblique/oracle/checker.h"

namespace {

using namespace oblique;
using namespace oblique::oracle;
using namespace oblique::mistakes;

template <class T>
Observation<T> observe(const Implementation<T>& impl, const Matrix4<T>& m, const Vector4<T>& c,
                       Convention convention) {
  const Answer<T> outcome = impl.run(m, c, convention);
  const Checker<T> checker(m, c, convention);
  Checks checks;
  checks.statuses = StatusContract::any_refusal;
  Observation<T> o{m, c, convention, outcome.status, outcome.projection, false};
  o.wrong = checker.judge(outcome, checks).violation() != nullptr;
  return o;
}

/// The first generated case (valid, or with one defect) `impl` answers wrongly, diagnosed with
/// `impl` asked again; ran == false when none of `cases` showed a wrong answer.
template <class T>
Diagnosis first_finding_diagnosed(const Implementation<T>& impl, int cases = 4000) {
  const auto valid = cases::valid_case<T>();
  const auto invalid = cases::invalid_case<T>();
  rc::Random random(26001);
  for (int i = 0; i < cases; ++i) {
    const cases::Case<T> c = i % 4 == 3 ? invalid(random.split(), i % 101).value()
                                        : valid(random.split(), i % 101).value();
    if (!all_finite(c.matrix) || !all_finite(c.plane)) continue;
    const Observation<T> o = observe(impl, c.matrix, c.plane, c.convention);
    if (!o.wrong) continue;
    const Probe<T> probe = [&impl](const Matrix4<T>& m, const Vector4<T>& p, Convention k,
                                   cases::Family) {
      return std::optional<Observation<T>>(observe(impl, m, p, k));
    };
    return diagnose<T>({o}, probe);
  }
  return Diagnosis{};
}

template <class T>
class Diagnose : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(Diagnose, Scalars);

TYPED_TEST(Diagnose, everyMistakeIsItselfAndNoOther) {
  using T = TypeParam;
  for (Mistake m : all_mistakes) {
    const std::string name(mistake_entry(m).name);
    const Diagnosis d = first_finding_diagnosed(mistaken_implementation<T>({m}));
    EXPECT_TRUE(d.ran) << name << ": no wrong answer found";
    EXPECT_EQ(d.causes, std::vector<std::vector<Mistake>>{{m}})
        << name << ": " << likely_cause_line(d);
    EXPECT_GT(d.wrong_where_it_differs, 0) << name;
  }
}

TYPED_TEST(Diagnose, twoMistakesTogetherAreThePair) {
  using T = TypeParam;
  const std::vector<Mistake> pair{Mistake::no_camera_guard, Mistake::sign_by_division};
  const Diagnosis d = first_finding_diagnosed(mistaken_implementation<T>(pair));
  ASSERT_TRUE(d.ran);
  ASSERT_EQ(d.causes.size(), 1u) << likely_cause_line(d);
  EXPECT_EQ(d.causes[0], pair) << likely_cause_line(d);
}

// A correct answer one ulp off in row 3, even if a checker took it for wrong, is no mistake.
TYPED_TEST(Diagnose, aCorrectAnswerWithNoiseIsNeverDiagnosed) {
  using T = TypeParam;
  const auto valid = cases::valid_case<T>();
  rc::Random random(26002);
  int diagnosed = 0;
  for (int i = 0; i < 300; ++i) {
    const cases::Case<T> c = valid(random.split(), i % 101).value();
    const ObliqueResult<T> r = apply<T>(c.matrix, c.plane, c.convention);
    Observation<T> o{c.matrix, c.plane, c.convention, r.status, r.projection, true};
    if (r.status == Status::ok) {
      for (int j = 0; j < 4; ++j)
        o.projection(2, j) = std::nextafter(o.projection(2, j), j % 2 ? T(1e30) : T(-1e30));
    }
    const Diagnosis d = diagnose<T>({o});
    if (!d.causes.empty()) {
      ++diagnosed;
      ADD_FAILURE() << likely_cause_line(d) << "\n"
                    << likely_cause_markdown(d) << "\nM =\n"
                    << c.matrix << "\nC = " << c.plane.transpose() << " "
                    << convention_name(c.convention) << " " << status_code(r.status);
    }
  }
  EXPECT_EQ(diagnosed, 0);
}

// a = 3 / (C . Q): a wrong scale no catalogued mistake gives.
TYPED_TEST(Diagnose, anUnlistedMistakeIsNoKnownMistake) {
  using T = TypeParam;
  Implementation<T> impl;
  impl.name = "three_halves_scale";
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = apply<T>(m, c, convention);
    Answer<T> out{r.status, r.projection};
    if (r.status == Status::ok) {
      const RowCombination near = near_rows(convention);
      const Vector4<T> m4 = m.row(3).transpose();
      const Vector4<T> ac = (T(near.m3) * r.projection.row(2).transpose() + T(near.m4) * m4);
      out.projection.row(2) = (T(near.m3) * (T(1.5) * ac - T(near.m4) * m4)).transpose();
    }
    return out;
  };
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  EXPECT_EQ(likely_cause_line(d), "likely cause: no known mistake reproduces these answers");
}

TEST(Mistakes, everyEntryHasOneNameReadBackToItself) {
  for (Mistake m : all_mistakes) {
    const MistakeEntry& e = mistake_entry(m);
    EXPECT_EQ(e.mistake, m);
    EXPECT_EQ(parse_mistake(e.name), m) << e.name;
    EXPECT_FALSE(e.title.empty() || e.explanation.empty() || e.fix.empty() || e.shows.empty());
  }
  EXPECT_FALSE(parse_mistake("no_such_mistake"));
}

}  // namespace
