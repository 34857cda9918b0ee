// What the consumer judges share (oracle/consumer_judging.h, internal to the oracle library),
// each faster form against the exact one it stands for: solve_error()'s bound computed in
// certified intervals (solve_bound_of()) holds the exact bound and exists exactly where it does;
// axis_sign_of() from those ranges gives axis_sign()'s answer; through_lu_bound() is the two
// products it replaces.
#include "consumer_judging.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>

#include "oblique/cases/generators.h"
#include "oblique/oblique.h"

namespace oblique::oracle::consumer_judging {
namespace {

template <class T>
class ConsumerJudging : public ::testing::Test {};
using Precisions = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(ConsumerJudging, Precisions);

/// The original and oblique matrices of generated cases (every family, convention and place).
template <class T>
std::vector<std::pair<Matrix4<T>, Convention>> matrices(int wanted) {
  const auto gen = cases::valid_case<T>();
  rc::Random random(20261207);
  std::vector<std::pair<Matrix4<T>, Convention>> out;
  for (int i = 0; static_cast<int>(out.size()) < wanted && i < 8 * wanted; ++i) {
    const cases::Case<T> g = gen(random.split(), i % 101).value();
    out.emplace_back(g.matrix, g.convention);
    const ObliqueResult<T> r = apply<T>(g.matrix, g.plane, g.convention);
    if (r.status == Status::ok) out.emplace_back(r.projection, g.convention);
  }
  return out;
}

TYPED_TEST(ConsumerJudging, theSolveBoundsRangesHoldTheExactBound) {
  using T = TypeParam;
  const int wanted = std::is_same_v<T, long double> ? 40 : 200;
  int ranged = 0, exists = 0;
  for (const auto& [m, convention] : matrices<T>(wanted)) {
    for (const int bits :
         {oracle::tolerance::precision_bits<T>(),
          oracle::tolerance::precision_bits<T>() - oracle::tolerance::kGpuLostBits}) {
      const std::shared_ptr<const std::optional<Mat>> exact = solve_error_of(m, bits);
      const std::shared_ptr<const SolveBound> bound = solve_bound_of(m, bits);
      ASSERT_EQ(bound->exists, exact->has_value());
      if (!bound->exists) continue;
      ++exists;
      if (!bound->ranged) continue;
      ++ranged;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          const Rational& s = (**exact)[i][j];
          EXPECT_LE(Rational(bound->range[i][j].lo), s) << i << ", " << j;
          EXPECT_GE(Rational(bound->range[i][j].hi), s) << i << ", " << j;
          // Tight: a few roundings of the exact bound, not a looser one.
          EXPECT_LE(bound->range[i][j].hi - bound->range[i][j].lo,
                    1e-12 * bound->range[i][j].hi + 1e-300);
        }
      }
      const std::shared_ptr<const Inverse> inv = inverse_of(m);
      EXPECT_EQ(axis_sign_of(m, convention, bits), axis_sign(*inv->inv, convention, *exact));
    }
  }
  EXPECT_GT(exists, wanted);
  EXPECT_GT(ranged, exists * 3 / 4);  // the intervals decide most
}

TYPED_TEST(ConsumerJudging, theInverseIsTheExactOne) {
  using T = TypeParam;
  int singular = 0, inverted = 0;
  const int wanted = std::is_same_v<T, long double> ? 40 : 200;
  for (const auto& [m, convention] : matrices<T>(wanted)) {
    (void)convention;
    const std::shared_ptr<const Inverse> fast = inverse_of(m);
    const std::optional<Mat> exact = oracle::exact::inverse(oracle::exact::to_rational(m));
    ASSERT_EQ(fast->inv.has_value(), exact.has_value());
    if (exact) {
      EXPECT_EQ(*fast->inv, *exact);
      ++inverted;
    }
  }
  // Singular matrices, and entries far apart in magnitude.
  Matrix4<T> m = Matrix4<T>::Identity();
  m(0, 1) = std::ldexp(T(3), std::numeric_limits<T>::min_exponent + 2);
  m(2, 3) = std::ldexp(T(5), std::numeric_limits<T>::max_exponent - 4);
  m(3, 2) = T(-1);
  m(3, 3) = T(0);
  for (int k = 0; k < 2; ++k) {
    const std::optional<Mat> exact = oracle::exact::inverse(oracle::exact::to_rational(m));
    const std::shared_ptr<const Inverse> fast = inverse_of(m);
    ASSERT_EQ(fast->inv.has_value(), exact.has_value());
    if (exact) {
      EXPECT_EQ(*fast->inv, *exact);
    }
    singular += !exact;
    m.row(1) = m.row(0) * T(2);  // then singular
  }
  EXPECT_GE(inverted, wanted);
  EXPECT_EQ(singular, 1);
}

TEST(ConsumerJudging, throughLuBoundIsTheTwoProducts) {
  std::mt19937_64 engine(7);
  std::uniform_int_distribution<int> pick(-40, 40);
  for (int round = 0; round < 50; ++round) {
    Mat a, m, b;
    for (Mat* x : {&a, &m, &b})
      for (auto& row : *x)
        for (auto& e : row) {
          e = Rational(pick(engine), pick(engine) == 0 ? 1 : 7 + round);
          e.canonicalize();  // (gmpxx leaves n / d as given)
        }
    EXPECT_EQ(through_lu_bound(oracle::exact::mul(a, Vec{1, 1, 1, 1}), m, b),
              mul(mul(a, lu_bound(m)), b));
  }
}

}  // namespace
}  // namespace oblique::oracle::consumer_judging
