// The checker's own mutation test: for each property, a class of wrong answers built from the
// core's correct answers on generated cases (mistakes/wrong_answers.h), and each property,
// judged alone, must reject every member of its class, in the exact checker and the filtered one.
#include "oblique/mistakes/wrong_answers.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "oblique/cases/generators.h"
#include "oblique/oblique.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"
#include "oblique/projection.h"

namespace oblique::oracle {
namespace {

using cases::Case;

/// Judges `projection` with `which` alone (an ok answer, the exact status contract), with the
/// exact checker or the filtered one.
template <class AnyProblem, class T>
Judgement judge_alone(const AnyProblem& problem, const Matrix4<T>& projection, Property which) {
  Checks checks;
  checks.properties = {which};
  return judge(problem, Answer<T>{Status::ok, projection}, checks);
}

TEST(CheckerMutation, nearPlaneWithOneSignFlippedIsRejected) {
  // glFrustum(-1, 1, -1, 1, 1, 10), C = (0.25, 0.5, -1, -2): near'_x with its sign flipped. A
  // later component's upper bound on lambda once replaced the negative one this entry gives.
  const Matrix4<double> m = frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, Convention::gl);
  const Vector4<double> c(0.25, 0.5, -1.0, -2.0);
  const Problem<double> problem(m, c, Convention::gl);
  const ObliqueResult<double> r = apply<double>(m, c, Convention::gl);
  ASSERT_TRUE(r.ok()) << r.message();
  Matrix4<double> wrong = r.projection;
  wrong(2, 0) = -wrong(2, 0) - 2 * m(3, 0);  // near'_x = M'_31 + M_41 -> -near'_x
  EXPECT_TRUE(judge_alone(problem, r.projection, Property::near_is_clip_plane).holds());
  const Judgement j = judge_alone(problem, wrong, Property::near_is_clip_plane);
  ASSERT_NE(j.violation(), nullptr);
  EXPECT_EQ(check_name(j.violation()->check), "near_is_clip_plane");
}

template <class T>
class CheckerMutationTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(CheckerMutationTyped, Scalars);

/// Every member of every class, from the core's answers on `count` generated cases of `gen`.
template <class T>
void every_member_is_rejected(const rc::Gen<Case<T>>& gen, int count, std::uint64_t seed,
                              std::map<Property, int>& members) {
  rc::Random random(seed);
  int rejected_wrongly = 0;
  for (int i = 0; i < count; ++i) {
    const Case<T> c = gen(random.split(), i % 101).value();
    const Problem<T> problem(c.matrix, c.plane, c.convention);
    if (problem.exact_status() != Status::ok) continue;
    const ObliqueResult<T> r = apply<T>(c.matrix, c.plane, c.convention);
    if (!r.ok()) continue;
    const std::vector<Status> acceptable = problem.acceptable_statuses();
    if (std::find(acceptable.begin(), acceptable.end(), Status::ok) == acceptable.end()) continue;
    const FilteredProblem<T> filtered(c.matrix, c.plane, c.convention);
    for (const auto& mutant : mistakes::wrong_answers::mutants(problem, r.projection, c.plane)) {
      const Property p = mutant.what.catches;
      ++members[p];
      const Judgement j = judge_alone(problem, mutant.projection, p);
      const Finding* violation = j.violation();
      const Judgement jf = judge_alone(filtered, mutant.projection, p);
      const Finding* filtered_violation = jf.violation();
      EXPECT_TRUE(filtered_violation != nullptr && filtered_violation->check == check_of(p))
          << "the filtered checker accepts a member of " << property_name(p) << "'s class";
      if (violation != nullptr && violation->check == check_of(p)) continue;
      ++rejected_wrongly;
      ADD_FAILURE() << property_name(p) << " accepts a member of its class (entry "
                    << mutant.what.detail << ") on case " << i << " of seed " << seed << ": "
                    << cases::family_name(c.family) << " " << convention_name(c.convention) << " "
                    << cases::place_name(c.place);
    }
  }
  EXPECT_EQ(rejected_wrongly, 0) << "members accepted by the property of their class";
}

TYPED_TEST(CheckerMutationTyped, eachPropertyAloneRejectsItsClass) {
  using T = TypeParam;
  std::map<Property, int> members;
  every_member_is_rejected<T>(cases::valid_case<T>(), 600, 20261130, members);
  every_member_is_rejected<T>(cases::valid_case_of<T>(cases::Family::infinite), 200, 20261131,
                              members);
  // The classes are not empty: each held the property to many wrong answers.
  for (Property p : all_properties) {
    EXPECT_GE(members[p], 50) << property_name(p) << ": too few members";
    std::cout << property_name(p) << ": " << members[p] << " members\n";
  }
}

}  // namespace
}  // namespace oblique::oracle
