// The filtered checker (oracle/filtered.h) against the exact one (problem.h), on the same
// generated cases and answers: every disagreement fails.
//
// Differential.filteredAgreesWithExact judges, per case (float, double and long double in turn;
// four valid cases in five, one invalid), the core's answer with the core's checks (row 3's
// accuracy and the ulps promise), one perturbation of it (an ulp move, a sign flip, swapped rows, a
// refusal), one member of a wrong-answer class (wrong_answers.h) and one other implementation (a
// printed recipe or a planted mutant: signs from C, the wrong face, ...), with both checkers, and
// compares statuses, acceptable statuses and every finding (kind, holds, relation, statuses).
// Every seventh case is first moved by powers of two to the ends of its type's range (and, for
// long double, beyond double's), where the filter's scaling and its intervals for entries below
// double's normal range are what decides.
// Which cases: OBLIQUE_DIFFERENTIAL_SLICE (seed offset) and OBLIQUE_DIFFERENTIAL_CASES (count), set
// by CTest per slice (tests/CMakeLists.txt).
#include "oblique/oracle/filtered.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/implementations.h"
#include "oblique/mistakes/wrong_answers.h"
#include "oblique/oblique.h"
#include "oblique/projection.h"

namespace oblique::oracle {

using mistakes::known_implementations;
namespace {

using cases::Case;

struct Tally {
  long cases = 0, judgements = 0, filtered = 0, statuses_filtered = 0, disagreements = 0;
  std::map<int, long> undecided_at;  ///< where the filter gave up on an answer that holds
};

std::string describe(const Judgement& j) {
  std::string out;
  for (const Finding& f : j.checks) {
    out += "  " + std::string(check_name(f.check)) + (f.holds ? " holds" : " FAILS") + " [" +
           relation_text(f) + "] " + residual_text(f) + " / " + bound_text(f) + "\n";
  }
  return out.empty() ? "  (no findings)\n" : out;
}

bool same(const Judgement& a, const Judgement& b) {
  if (a.checks.size() != b.checks.size()) return false;
  for (std::size_t i = 0; i < a.checks.size(); ++i) {
    const Finding &x = a.checks[i], &y = b.checks[i];
    if (x.check != y.check || x.holds != y.holds || relation_text(x) != relation_text(y) ||
        x.answered != y.answered || x.allowed != y.allowed)
      return false;
  }
  return true;
}

template <class T>
void compare(const Case<T>& c, const Problem<T>& exact, const FilteredProblem<T>& filtered,
             const Answer<T>& outcome, const Checks& checks, const std::string& what,
             Tally& tally) {
  ++tally.judgements;
  const Judgement expected = judge(exact, outcome, checks);
  const std::optional<Judgement> fast = filtered.filtered_judgement(outcome, checks);
  if (fast) ++tally.filtered;
  if (!fast && expected.holds()) ++tally.undecided_at[filtered.undecided_at()];
  const Judgement got = fast ? *fast : judge(filtered, outcome, checks);
  if (same(expected, got)) return;
  ++tally.disagreements;
  std::ostringstream os;
  os << cases::family_name(c.family) << " " << convention_name(c.convention) << " "
     << cases::place_name(c.place) << "\nM =";
  for (int i = 0; i < 16; ++i) os << " " << protocol::format_number(c.matrix(i / 4, i % 4));
  os << "\nC =";
  for (int i = 0; i < 4; ++i) os << " " << protocol::format_number(c.plane(i));
  ADD_FAILURE() << "filtered and exact checkers disagree (" << protocol::scalar_name<T>() << ", "
                << what << ", status " << status_code(outcome.status) << ")\n"
                << os.str() << "\nexact:\n"
                << describe(expected) << "filtered" << (fast ? " (decided)" : "") << ":\n"
                << describe(got);
}

template <class T>
Answer<T> perturbed(const Answer<T>& answer, int which, const Matrix4<T>& m) {
  Answer<T> out = answer;
  Matrix4<T>& p = out.projection;
  const int entry = which / 9 % 4;
  T& x = p(2, entry);
  auto ulps = [&](int k) {
    for (int i = 0; i < std::abs(k); ++i)
      x = std::nextafter(
          x, k > 0 ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
  };
  switch (which % 9) {
    case 0: ulps(1); break;
    case 1: ulps(-1); break;
    case 2: ulps(3); break;
    case 3: ulps(-16); break;
    case 4: x = -x; break;                   // a sign flip in row 3
    case 5: p.row(2).swap(p.row(3)); break;  // rows 3 and 4 swapped
    case 6: p.row(0).swap(p.row(1)); break;  // rows 1 and 2 swapped
    case 7: p(entry == 2 ? 0 : 1, entry) = -m(entry == 2 ? 0 : 1, entry); break;  // a side sign
    case 8: {  // a refusal instead of the answer
      const Status refusals[] = {Status::plane_misses_view_volume, Status::out_of_range,
                                 Status::singular_projection, Status::camera_not_behind_plane};
      out.status = refusals[which / 9 % 4];
      break;
    }
  }
  return out;
}

/// Every seventh case moved, by powers of two, to where the filter scales its inputs: M or C (or
/// both, apart) with the largest entry near T's overflow or underflow, long doubles beyond double's
/// range both ways. Entries pushed below T's range round (a different input, judged all the same).
template <class T>
void move_to_the_ends(Case<T>& c, std::uint64_t index) {
  if (index % 7 != 3) return;
  constexpr int emax = std::numeric_limits<T>::max_exponent;
  constexpr int emin = std::numeric_limits<T>::min_exponent;
  const int which = int(index / 7 % 6), jitter = int(index / 42 % 5);
  auto top = [](const auto& v) {
    const T largest = v.cwiseAbs().maxCoeff();
    return largest == T(0) ? 0 : std::ilogb(largest);
  };
  // The exponent the largest entry gets: near overflow, near the smallest normal, and (long
  // double) beyond double's range, above and below.
  const bool wide = std::is_same_v<T, long double>;
  const int high = emax - 2 - jitter, low = emin + 8 + jitter;
  const int beyond_high = wide ? 1100 + 900 * jitter : high,
            beyond_low = wide ? -1100 - 900 * jitter : low;
  auto move = [&](auto& v, int exponent) {
    const int shift = exponent - top(v);
    for (Eigen::Index i = 0; i < v.size(); ++i) v.data()[i] = std::ldexp(v.data()[i], shift);
  };
  switch (which) {
    case 0: move(c.matrix, high); break;
    case 1: move(c.matrix, low); break;
    case 2: move(c.plane, high); break;
    case 3: move(c.plane, low); break;
    case 4:
      move(c.matrix, beyond_high);
      move(c.plane, beyond_low);
      break;
    case 5:
      move(c.matrix, beyond_low);
      move(c.plane, beyond_high);
      break;
  }
}

template <class T>
void one_case(std::uint64_t index, rc::Random& random, Tally& tally) {
  const bool invalid = index % 5 == 4;
  Case<T> c = invalid ? cases::invalid_case<T>()(random.split(), int(index % 101)).value()
                      : cases::valid_case<T>()(random.split(), int(index % 101)).value();
  move_to_the_ends(c, index);
  ++tally.cases;
  const Problem<T> exact(c.matrix, c.plane, c.convention);
  const FilteredProblem<T> filtered(c.matrix, c.plane, c.convention);
  if (filtered.statuses_decided()) ++tally.statuses_filtered;
  EXPECT_EQ(filtered.exact_status(), exact.exact_status());
  EXPECT_EQ(filtered.acceptable_statuses(), exact.acceptable_statuses());

  const auto known = known_implementations<T>();
  const Implementation<T>& core = known[0];  // core_auto
  const Answer<T> answer = core.run(c.matrix, c.plane, c.convention);
  compare(c, exact, filtered, answer, core.checks(true), "core answer", tally);
  if (answer.status == Status::ok) {
    const int which = int(index / 5 % 36);
    compare(c, exact, filtered, perturbed(answer, which, c.matrix), core.checks(true),
            "perturbation " + std::to_string(which % 9), tally);
    Checks defaults;
    if (exact.exact_status() == Status::ok) {
      const auto wrong = mistakes::wrong_answers::mutants(exact, answer.projection, c.plane);
      if (!wrong.empty()) {
        const auto& w = wrong[index % wrong.size()];
        Checks alone;
        alone.properties = {w.what.catches};
        compare(c, exact, filtered, Answer<T>{Status::ok, w.projection},
                index % 2 ? alone : defaults,
                "wrong answer for " + std::string(property_name(w.what.catches)), tally);
      }
    }
  }
  // Another implementation, in turn: the other methods, the recipes, the planted mutants.
  const Implementation<T>& other = known[1 + index % (known.size() - 1)];
  if (other.accepts(c.convention, c.matrix)) {
    const Answer<T> o = other.run(c.matrix, c.plane, c.convention);
    Checks checks = other.checks(other.name.rfind("core_", 0) == 0);
    if (index % 3 == 0) checks.statuses = StatusContract::any_refusal;
    compare(c, exact, filtered, o, checks, other.name, tally);
  }
}

long from_env(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

TEST(Differential, filteredAgreesWithExact) {
  const long slice = from_env("OBLIQUE_DIFFERENTIAL_SLICE", 0);
  const long cases = from_env("OBLIQUE_DIFFERENTIAL_CASES", 300);
  rc::Random random(20261130 + static_cast<std::uint64_t>(slice) * 7919);
  Tally tally;
  for (long i = 0; i < cases; ++i) {
    const std::uint64_t index = static_cast<std::uint64_t>(i);
    switch (i % 3) {
      case 0: one_case<float>(index, random, tally); break;
      case 1: one_case<double>(index, random, tally); break;
      case 2: one_case<long double>(index, random, tally); break;
    }
  }
  std::cout << "slice " << slice << ": " << tally.cases << " cases, statuses decided by the filter "
            << tally.statuses_filtered << "; " << tally.judgements << " judgements, "
            << tally.filtered << " decided by the filter, " << tally.disagreements
            << " disagreements\nwhere the filter left a holding judgement to exact arithmetic "
               "(line: count):";
  for (const auto& [line, count] : tally.undecided_at) std::cout << " " << line << ": " << count;
  std::cout << "\n";
  EXPECT_EQ(tally.disagreements, 0);
}

TEST(Filtered, decidesTheCoresAnswerOnAPlainFrustum) {
  const Matrix4<double> m = frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0, Convention::gl);
  const Vector4<double> c(0.25, 0.5, -1.0, -2.0);
  const FilteredProblem<double> problem(m, c, Convention::gl);
  ASSERT_TRUE(problem.statuses_decided());
  EXPECT_EQ(problem.exact_status(), Status::ok);
  const ObliqueResult<double> r = apply<double>(m, c, Convention::gl);
  Checks checks;
  checks.row3_accuracy = true;
  checks.max_ulps = 2;
  const std::optional<Judgement> j =
      problem.filtered_judgement(Answer<double>{r.status, r.projection}, checks);
  ASSERT_TRUE(j.has_value());
  EXPECT_TRUE(j->holds());
  EXPECT_EQ(j->checks.size(), 7u);
  // The sign-flip repro: the filter does not decide it, the exact checker rejects it.
  Matrix4<double> wrong = r.projection;
  wrong(2, 0) = -wrong(2, 0) - 2 * m(3, 0);
  const Judgement rejected = judge(problem, Answer<double>{Status::ok, wrong}, checks);
  ASSERT_NE(rejected.violation(), nullptr);
  EXPECT_EQ(check_name(rejected.violation()->check), "near_is_clip_plane");
}

// A plain frustum and plane moved by powers of two (M and C apart): far beyond double's range in
// long double, to near double's overflow and underflow in double. The filter's scaling decides
// the statuses and the core's answer alone, with the exact checker's findings.
template <class T>
void expect_decided_at_scale(int m_shift, int c_shift) {
  SCOPED_TRACE(std::string(protocol::scalar_name<T>()) + " M 2^" + std::to_string(m_shift) +
               ", C 2^" + std::to_string(c_shift));
  const Matrix4<T> m = frustum(T(-1), T(1), T(-0.75), T(0.75), T(1), T(100), Convention::gl) *
                       std::ldexp(T(1), m_shift);
  const Vector4<T> c = Vector4<T>(T(0.25), T(0.5), T(-1), T(-2)) * std::ldexp(T(1), c_shift);
  const Problem<T> exact(m, c, Convention::gl);
  const FilteredProblem<T> filtered(m, c, Convention::gl);
  ASSERT_TRUE(filtered.statuses_decided()) << "gave up at line " << filtered.undecided_at();
  EXPECT_EQ(filtered.exact_status(), exact.exact_status());
  EXPECT_EQ(filtered.acceptable_statuses(), exact.acceptable_statuses());
  const ObliqueResult<T> r = apply<T>(m, c, Convention::gl);
  ASSERT_EQ(r.status, Status::ok);
  Checks checks;
  checks.row3_accuracy = true;
  checks.max_ulps = oracle::tolerance::kAccurateUlps;
  const Answer<T> outcome{r.status, r.projection};
  const std::optional<Judgement> fast = filtered.filtered_judgement(outcome, checks);
  ASSERT_TRUE(fast.has_value()) << "gave up at line " << filtered.undecided_at();
  const Judgement expected = judge(exact, outcome, checks);
  EXPECT_TRUE(same(expected, *fast)) << "exact:\n"
                                     << describe(expected) << "filtered:\n"
                                     << describe(*fast);
}

TEST(Filtered, decidesMagnitudesAtTheEndsOfTheRange) {
  for (int shift : {3000, -3000, 12000, -12000}) {
    expect_decided_at_scale<long double>(shift, 0);
    expect_decided_at_scale<long double>(0, shift);
  }
  // (M 2^12000 with C 2^-12000 is left to GMP: the underflow unit's term in C . Q's bound, scaled
  // alike, is beyond double's range.)
  expect_decided_at_scale<long double>(3000, -3000);
  expect_decided_at_scale<long double>(-3000, 3000);
  for (int shift : {900, -900}) {
    expect_decided_at_scale<double>(shift, 0);
    expect_decided_at_scale<double>(0, shift);
  }
  expect_decided_at_scale<float>(100, -100);
}

TEST(Certified, exactZerosStayExactAndUndecidedSignsThrow) {
  using certified::Num;
  const Num a = certified::exactly(0.1), b = certified::exactly(-0.1);
  EXPECT_EQ(certified::sign(a + b), 0);
  const Num third = certified::constant(1) / certified::constant(3);
  EXPECT_THROW(certified::sign(third * certified::constant(3) - certified::constant(1)),
               certified::Undecided);
  EXPECT_LT(certified::lower(third), 1.0 / 3);
  EXPECT_GT(certified::upper(third), 1.0 / 3);
}

// The integers behind the filter's exact signs (exact.h): each entry is its integer times
// 2^exponent exactly, and the Laplace determinant equals the product of the pivots of an exact
// elimination, on entries from 2^-1074 to 2^1023 and on singular matrices.
template <class T>
oracle::exact::Rational elimination_determinant(oracle::exact::Mat m) {
  oracle::exact::Rational det = 1;
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    while (pivot < 4 && m[pivot][col] == 0) ++pivot;
    if (pivot == 4) return 0;
    if (pivot != col) {
      std::swap(m[pivot], m[col]);
      det = -det;
    }
    det *= m[col][col];
    for (int row = col + 1; row < 4; ++row) {
      const oracle::exact::Rational f = m[row][col] / m[col][col];
      for (int j = col; j < 4; ++j) m[row][j] -= f * m[col][j];
    }
  }
  return det;
}

template <class T>
void expect_integers_and_determinant(const Matrix4<T>& m) {
  std::array<T, 16> entries;
  for (int i = 0; i < 16; ++i) entries[static_cast<std::size_t>(i)] = m(i / 4, i % 4);
  int e = 0;
  const std::array<oracle::exact::Integer, 16> integers = oracle::exact::to_integers(entries, e);
  oracle::exact::IntegerMat a;
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(oracle::exact::Rational(integers[static_cast<std::size_t>(i)]) *
                  oracle::exact::power_of_two(e),
              oracle::exact::to_rational(entries[static_cast<std::size_t>(i)]))
        << i;
    a[i / 4][i % 4] = integers[static_cast<std::size_t>(i)];
  }
  const oracle::exact::Rational expected =
      elimination_determinant<T>(oracle::exact::to_rational(m));
  EXPECT_EQ(
      oracle::exact::Rational(oracle::exact::determinant(a)) * oracle::exact::power_of_two(4L * e),
      expected);
}

TEST(ExactIntegers, entriesAndDeterminantsAreExact) {
  std::mt19937_64 random(5);
  const auto pick = [&random](int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random);
  };
  for (int n = 0; n < 200; ++n) {
    Matrix4<double> d;
    Matrix4<long double> l;
    Matrix4<float> f;
    for (int i = 0; i < 16; ++i) {
      const int k = pick(-1000, 1000);
      d(i / 4, i % 4) = pick(0, 5) == 0 ? 0.0 : std::ldexp(k, pick(-1074, 1000));
      l(i / 4, i % 4) = std::ldexp(static_cast<long double>(k) / 3, pick(-200, 200));
      f(i / 4, i % 4) = std::ldexp(static_cast<float>(k) / 7, pick(-140, 100));
    }
    if (n % 4 == 0) d.row(3) = d.row(1) * 2.0;  // singular: determinant 0
    expect_integers_and_determinant(d);
    expect_integers_and_determinant(l);
    expect_integers_and_determinant(f);
  }
}

}  // namespace
}  // namespace oblique::oracle
