// The checker as users see it (oblique/oracle/checker.h): a header without GMP or the
// checker's own headers, and on generated cases the same statuses, the same reasons to leave an
// input out and the same judgements, finding by finding, as the filtered checker's judge() and
// the exact one's, for the core's answers and for answers with row 3 wrong.
#include "oblique/oracle/checker.h"

#if defined(__GNU_MP__) || defined(__GMP_PLUSPLUS__)
#error "oblique/oracle/checker.h includes GMP; it should only declare the checker"
#endif

#include <gtest/gtest.h>

#include <cstdint>

#include "oblique/cases/generators.h"
#include "oblique/oblique.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"
#include "oblique/projection.h"

namespace oblique::oracle {
namespace {

void expect_same(const Judgement& got, const Judgement& want, const std::string& where) {
  ASSERT_EQ(got.checks.size(), want.checks.size()) << where;
  for (std::size_t i = 0; i < got.checks.size(); ++i) {
    const Finding& a = got.checks[i];
    const Finding& b = want.checks[i];
    const std::string name(check_name(a.check));
    EXPECT_EQ(name, check_name(b.check)) << where << ", check " << i;
    EXPECT_EQ(a.holds, b.holds) << where << ", " << name;
    EXPECT_EQ(relation_text(a), relation_text(b)) << where << ", " << name;
    EXPECT_EQ(a.answered, b.answered) << where << ", " << name;
    EXPECT_EQ(a.allowed, b.allowed) << where << ", " << name;
  }
}

template <class T>
class CheckerTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(CheckerTest, Scalars);

TYPED_TEST(CheckerTest, judgesAsTheFilteredAndTheExactChecker) {
  using T = TypeParam;
  rc::Random random(20261202);
  int violations = 0;
  for (int i = 0; i < 300; ++i) {
    const cases::Case<T> c = cases::valid_case<T>()(random.split(), i % 101).value();
    const Checker<T> checker(c.matrix, c.plane, c.convention);
    const FilteredProblem<T> filtered(c.matrix, c.plane, c.convention);
    const Problem<T> exact(c.matrix, c.plane, c.convention);
    const std::string where = "case " + std::to_string(i);
    EXPECT_EQ(checker.exact_status(), exact.exact_status()) << where;
    EXPECT_EQ(checker.acceptable_statuses(), exact.acceptable_statuses()) << where;
    for (StatusContract contract :
         {StatusContract::exact, StatusContract::any_refusal, StatusContract::answers_only}) {
      EXPECT_EQ(checker.not_judged(contract), not_judged(exact, contract)) << where;
    }
    const ObliqueResult<T> r = apply<T>(c.matrix, c.plane, c.convention);
    Answer<T> answer{r.status, r.projection};
    expect_same(checker.judge(answer), judge(filtered, answer), where);
    expect_same(checker.judge(answer), judge(exact, answer), where);
    if (!r.ok()) continue;
    answer.projection.row(2) *= T(2);  // a far plane that no longer passes through Q
    const Judgement wrong = checker.judge(answer);
    expect_same(wrong, judge(exact, answer), where + ", row 3 doubled");
    violations += wrong.violation() != nullptr;
  }
  // The wrong answers are found wrong (the comparison above is not between empty judgements).
  EXPECT_GT(violations, 100);
}

TEST(Checker, namesTheFirstViolation) {
  const Matrix4<double> m = frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, Convention::gl);
  const Vector4<double> c(0.25, 0.5, -1.0, -2.0);
  const Checker<double> checker(m, c, Convention::gl);
  const ObliqueResult<double> r = apply<double>(m, c, Convention::gl);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(checker.judge(Answer<double>{Status::ok, r.projection}).holds());
  Matrix4<double> wrong = r.projection;
  wrong.row(2) = -wrong.row(2);
  const Judgement j = checker.judge(Answer<double>{Status::ok, wrong});
  ASSERT_NE(j.violation(), nullptr);
  EXPECT_EQ(check_name(j.violation()->check), "near_is_clip_plane");
  // Refusing an input that has an answer breaks the exact status contract.
  const Judgement refused = checker.judge(Answer<double>{Status::singular_projection, m});
  ASSERT_NE(refused.violation(), nullptr);
  EXPECT_EQ(check_name(refused.violation()->check), "status");
}

}  // namespace
}  // namespace oblique::oracle
