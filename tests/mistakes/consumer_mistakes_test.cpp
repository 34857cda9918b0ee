// The consumer mistakes' diagnosis (mistakes/consumer_mistakes.h): each wrong function of the
// catalogue, asked through a consumer round, is named as itself wherever it is caught (in float
// and double), and a right answer judged wrong is no cause.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>

#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/projection.h"

namespace {

using oblique::Convention;
using oblique::Matrix4;
using oblique::Vector4;
using oblique::mistakes::ConsumerMistake;
using oblique::oracle::ConsumerFinding;

template <class T>
class ConsumerMistakes : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ConsumerMistakes, Scalars);

/// Consumer rounds of `consumers` on tilted planes before a few cameras, in every convention,
/// with seeded picks: each violated finding's likely cause.
template <class T>
std::vector<std::string> causes_of_violations(const oblique::Consumers<T>& consumers) {
  std::vector<std::string> out;
  std::mt19937 engine(20261206);
  const oblique::oracle::Pick pick = [&engine](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi - 1)(engine);
  };
  const oblique::oracle::Settle settle = [&out](const ConsumerFinding& f, const std::string&,
                                                bool) {
    if (f.judged && !f.holds) out.push_back(f.likely_cause);
  };
  for (int round = 0; round < 40; ++round) {
    for (Convention k : {Convention::gl, Convention::zero_one, Convention::reversed_z}) {
      const Matrix4<T> m = oblique::perspective<T>(T(1.1), T(1.5), T(0.5), T(100), k);
      const Vector4<T> c(T(0.2) + T(0.01) * T(round), T(0.3), T(-1), T(-3));
      oblique::oracle::consumer_round<T>(m, c, k, consumers, pick, settle,
                                         oblique::mistakes::explain_consumer<T>);
    }
  }
  return out;
}

TYPED_TEST(ConsumerMistakes, eachWrongFunctionIsNamedAsItself) {
  using T = TypeParam;
  for (ConsumerMistake m : oblique::mistakes::all_consumer_mistakes) {
    const std::string name(oblique::mistakes::consumer_mistake_entry(m).name);
    const std::vector<std::string> causes =
        causes_of_violations(oblique::mistakes::mistaken_consumers<T>(m));
    int named = 0;
    for (const std::string& c : causes) {
      // Named alone or with entries the inputs cannot tell apart from it; none where its answer is
      // as close to the right one (a violation of precision, no formula's); never another alone.
      if (!c.empty()) {
        EXPECT_NE(c.find(name), std::string::npos) << name << ": " << c;
      }
      named += c == name;
    }
    if (causes.empty() && (m == ConsumerMistake::plane_flipped_for_mirrors ||
                           m == ConsumerMistake::plane_through_view))
      continue;  // shows only on some passes: caught or not in these rounds
    ASSERT_FALSE(causes.empty()) << name << ": never caught";
    EXPECT_GT(named, 0) << name << ": never named alone";
  }
}

TYPED_TEST(ConsumerMistakes, theRightAnswerIsNoCause) {
  using T = TypeParam;
  const oblique::Consumers<T> right = oblique::oracle::reference_consumers<T>();
  std::mt19937 engine(7);
  const oblique::oracle::Pick pick = [&engine](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi - 1)(engine);
  };
  int explained = 0;
  for (Convention k : {Convention::gl, Convention::zero_one, Convention::reversed_z}) {
    const Matrix4<T> m = oblique::perspective<T>(T(1.1), T(1.5), T(0.5), T(100), k);
    const Vector4<T> c(T(0.2), T(0.3), T(-1), T(-3));
    // Every right answer handed to the explanation as if it had been judged wrong.
    for (const auto& ask :
         oblique::oracle::consumer_asks<T>(m, c, k, right, pick, [](auto&&...) {})) {
      ConsumerFinding f;
      f.check = oblique::oracle::ConsumerCheck::view_position;
      f.judged = true;
      f.holds = false;
      oblique::mistakes::explain_consumer<T>(ask, ask.call(right), f);
      ++explained;
      EXPECT_EQ(f.likely_cause, "") << oblique::protocol::consumer_kind_name(ask.kind);
    }
  }
  EXPECT_GT(explained, 0);
}

// A cause carried from a run's first failing case to its shrunk one says so, in the line and in
// the report; a cause named on the case itself does not.
TEST(ConsumerMistakes, aCauseNamedBeforeShrinkingIsSaidSo) {
  using namespace oblique::mistakes;
  const std::string carried = std::string("linearises_with_near_far") + kNamedBeforeShrinking;
  const std::string line = consumer_cause_line(carried);
  // The effect first, then the mechanism and where it was named.
  EXPECT_EQ(line.rfind("likely cause: linearises_with_near_far: your linear depths are those of "
                       "the camera's own near and far planes",
                       0),
            0u)
      << line;
  EXPECT_NE(line.find("(linear depth from the near and far planes (zparams), named on the first "
                      "failing case"),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("; fix: "), std::string::npos) << line;
  const std::string md = consumer_cause_markdown(carried);
  EXPECT_NE(md.find("**`linearises_with_near_far`"), std::string::npos) << md;
  EXPECT_NE(md.find("Named on the run's first failing case"), std::string::npos) << md;
  const std::string own = consumer_cause_line("linearises_with_near_far");
  EXPECT_EQ(own.find("first failing case"), std::string::npos) << own;
  EXPECT_EQ(consumer_cause_markdown("linearises_with_near_far").find("first failing case"),
            std::string::npos);
}

// The zparams shortcut reads n and f along the camera's view axis, as _ZBufferParams do: a
// left-handed camera (M43 = +1, looking down +z) linearises as the right-handed one of the same n
// and f, in every convention.
TEST(ConsumerMistakes, theZparamsShortcutReadsNearAndFarAlongTheViewAxis) {
  using oblique::mistakes::ConsumerMistake;
  const auto zparams =
      oblique::mistakes::mistaken_consumers<double>(ConsumerMistake::linearises_with_near_far)
          .linear_depth;
  const double n = 0.5, f = 40;
  for (Convention k : oblique::all_conventions) {
    const Matrix4<double> right = oblique::frustum<double>(-0.4, 0.4, -0.3, 0.3, n, f, k);
    Matrix4<double> left = right;
    left.col(2) = -right.col(2);  // z flipped: M43 = +1
    for (double depth : {0.0, 0.25, 0.9, 1.0}) {
      oblique::oracle::DepthSample<double> s;
      s.convention = k;
      s.depth = depth;
      const double forward = k == Convention::reversed_z ? 1 - depth : depth;
      const double expected = n * f / (f - forward * (f - n));
      for (const Matrix4<double>* m : {&right, static_cast<const Matrix4<double>*>(&left)}) {
        s.original = *m;
        s.projection = *m;
        EXPECT_NEAR(zparams(s), expected, 1e-12 * expected)
            << oblique::convention_name(k) << (m == &left ? " left-handed" : " right-handed")
            << " d = " << depth;
      }
    }
  }
}

TEST(ConsumerMistakes, everyEntryHasOneNameReadBackToItself) {
  std::set<std::string> names;
  for (ConsumerMistake m : oblique::mistakes::all_consumer_mistakes) {
    const auto& e = oblique::mistakes::consumer_mistake_entry(m);
    EXPECT_TRUE(names.insert(std::string(e.name)).second) << e.name;
    EXPECT_EQ(oblique::mistakes::parse_consumer_mistake(e.name), m);
    EXPECT_FALSE(e.explanation.empty());
    EXPECT_FALSE(e.fix.empty());
    EXPECT_NE(oblique::mistakes::consumer_cause_markdown(std::string(e.name)).find(e.name),
              std::string::npos);
  }
}

}  // namespace
