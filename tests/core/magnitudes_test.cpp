// magnitudes.h on hand-picked inputs, subnormals and extreme spreads included: exponents,
// magnitude_spread and its fast test magnitude_spread_exceeds, scaling by 2^k, finiteness; the
// exponent-bit helpers against the libm calls they replace.
#include "oblique/numeric/magnitudes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "oblique/plane.h"

namespace oblique {
namespace {

template <class T>
class Magnitudes : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(Magnitudes, Scalars);

template <class T>
T two_to(int k) {
  return std::ldexp(T(1), k);
}

TYPED_TEST(Magnitudes, magnitudeExponentOfTheLargestEntry) {
  using T = TypeParam;
  EXPECT_EQ(magnitude_exponent(Vector4<T>(T(0.75), T(-0.5), T(0), T(0.1))), 0);
  EXPECT_EQ(magnitude_exponent(Vector4<T>(T(0.25), T(-1), T(0), T(0.1))), 1);  // 1 = 1/2 2^1
  EXPECT_EQ(magnitude_exponent(Vector4<T>(T(0), T(0), T(0), T(-3))), 2);
  EXPECT_EQ(magnitude_exponent(Vector4<T>::Zero()), 0);
  const T denorm = std::numeric_limits<T>::denorm_min();
  int expected = 0;
  std::frexp(denorm, &expected);
  EXPECT_EQ(magnitude_exponent(Vector4<T>(T(0), denorm, T(0), T(0))), expected);
  EXPECT_EQ(magnitude_exponent(Vector4<T>(std::numeric_limits<T>::max(), T(1), T(0), T(0))),
            std::numeric_limits<T>::max_exponent);
}

TYPED_TEST(Magnitudes, spreadCountsBinadesBetweenNonzeroEntries) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  Matrix4<T> m = Matrix4<T>::Zero();
  EXPECT_EQ(magnitude_spread(m), 0);  // no nonzero entry
  m(1, 2) = T(-5);
  EXPECT_EQ(magnitude_spread(m), 0);  // one
  m(3, 0) = two_to<T>(-10);
  EXPECT_EQ(magnitude_spread(m), 12);  // ilogb(5) = 2, ilogb(2^-10) = -10
  m(3, 0) = T(1.75) * two_to<T>(-10);
  EXPECT_EQ(magnitude_spread(m), 12);  // floors of log2: the significands do not count
  m(0, 0) = -limits::max();
  m(2, 2) = limits::denorm_min();
  EXPECT_EQ(magnitude_spread(m), std::ilogb(limits::max()) - std::ilogb(limits::denorm_min()));
  EXPECT_EQ(magnitude_spread(Vector4<T>(limits::min(), T(0), -limits::min(), T(0))), 0);
}

// magnitude_spread_exceeds<L> is magnitude_spread > L, at and around the boundaries its fast
// tests use (high against low 2^L and low 2^(L + 1)), for a subnormal low, and where low 2^L
// overflows.
TYPED_TEST(Magnitudes, spreadExceedsAgreesWithSpread) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  constexpr int kLimit = max_magnitude_spread<T>();
  const T lows[] = {T(1),
                    T(0.75),
                    limits::min(),
                    limits::denorm_min(),
                    T(3) * limits::denorm_min(),
                    two_to<T>(limits::max_exponent - kLimit - 1)};
  const int offsets[] = {-2, -1, 0, 1, 2};
  for (const T low : lows) {
    for (const int offset : offsets) {
      for (const T significand : {T(1), T(1.5), T(2) - limits::epsilon()}) {
        const T high = std::ldexp(low * significand, kLimit + offset);
        if (!std::isfinite(high) || high == T(0)) continue;
        const Vector4<T> v(high, T(0), -low, T(0));
        EXPECT_EQ(magnitude_spread_exceeds<kLimit>(v), magnitude_spread(v) > kLimit)
            << "low " << double(low) << " offset " << offset << " significand "
            << double(significand);
      }
    }
  }
  // low 2^L overflows (to infinity): still compared right.
  const Vector4<T> huge(limits::max(), two_to<T>(limits::max_exponent - kLimit + 2), T(0), T(0));
  EXPECT_EQ(magnitude_spread_exceeds<kLimit>(huge), magnitude_spread(huge) > kLimit);
  EXPECT_FALSE(magnitude_spread_exceeds<kLimit>(Vector4<T>::Zero()));
}

TEST(Magnitudes, maxSpreadIsTwiceThePrecision) {
  EXPECT_EQ(max_magnitude_spread<float>(), 48);
  EXPECT_EQ(max_magnitude_spread<double>(), 106);
  EXPECT_EQ(max_magnitude_spread<long double>(), 2 * std::numeric_limits<long double>::digits);
}

// v 2^k: exact while entries stay normal, and what ldexp gives otherwise (one rounding into
// the subnormal range, overflow to infinity), also for k beyond the range of a factor 2^k.
TYPED_TEST(Magnitudes, scaledByPowerOfTwoIsLdexp) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  const Vector4<T> v(T(0.1), T(-3), limits::min() * T(1.5), limits::max() / T(3));
  const int shifts[] = {0,
                        7,
                        -7,
                        limits::min_exponent - 2,
                        limits::min_exponent - 1,
                        limits::max_exponent - 1,
                        limits::max_exponent,
                        limits::max_exponent + 5,
                        2 * limits::min_exponent - limits::digits,
                        -limits::max_exponent - 40};
  for (const int k : shifts) {
    const Vector4<T> scaled = scaled_by_power_of_two(v, k);
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(scaled(i), std::ldexp(v(i), k)) << "k " << k << " entry " << i;
    }
  }
  // A subnormal scaled up is exact.
  const Vector4<T> tiny(limits::denorm_min(), T(0), T(-5) * limits::denorm_min(), T(0));
  const Vector4<T> up = scaled_by_power_of_two(tiny, limits::digits + 10);
  EXPECT_EQ(std::ldexp(up(0), -(limits::digits + 10)), limits::denorm_min());
  EXPECT_EQ(up(2), T(-5) * up(0));
}

TYPED_TEST(Magnitudes, allFinite) {
  using T = TypeParam;
  Matrix4<T> m = Matrix4<T>::Identity();
  m(0, 3) = std::numeric_limits<T>::denorm_min();
  m(1, 2) = -std::numeric_limits<T>::max();
  EXPECT_TRUE(all_finite(m));
  m(2, 1) = std::numeric_limits<T>::infinity();
  EXPECT_FALSE(all_finite(m));
  m(2, 1) = std::numeric_limits<T>::quiet_NaN();
  EXPECT_FALSE(all_finite(m));
}

/// Values across the whole range of T: every binade's power of two and a value inside it, both
/// signs, the subnormals' binades, zero, the extremes.
template <class T>
std::vector<T> across_the_range() {
  using limits = std::numeric_limits<T>;
  std::vector<T> out{limits::max(),        -limits::max(),        limits::min(),
                     limits::denorm_min(), -limits::denorm_min(), T(1) - limits::epsilon() / T(2)};
  for (int k = limits::min_exponent - limits::digits; k < limits::max_exponent; ++k) {
    const T p = std::ldexp(T(1), k);
    out.push_back(p);
    out.push_back(-p);
    out.push_back(p * T(1.6180339887498949));
    out.push_back(-p * (T(2) - limits::epsilon()));
  }
  return out;
}

TYPED_TEST(Magnitudes, frexpExponentIsFrexps) {
  using T = TypeParam;
  for (const T x : across_the_range<T>()) {
    int expected = 0;
    std::frexp(x, &expected);
    ASSERT_EQ(frexp_exponent(x), expected) << static_cast<long double>(x);
  }
}

TYPED_TEST(Magnitudes, powerOfTwoIsLdexpOfOne) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  EXPECT_FALSE(normal_power_of_two<T>(limits::min_exponent - 2));
  EXPECT_FALSE(normal_power_of_two<T>(limits::max_exponent));
  for (int k = limits::min_exponent - 1; k < limits::max_exponent; ++k) {
    ASSERT_TRUE(normal_power_of_two<T>(k));
    const T expected = std::ldexp(T(1), k);
    const T got = power_of_two<T>(k);
    ASSERT_EQ(got, expected) << k;
    ASSERT_EQ(std::signbit(got), false);
  }
}

// times_power_of_two(x, k) is std::ldexp(x, k) everywhere: exact scalings, overflow to
// infinity, gradual underflow with its rounding, and k beyond a normal 2^k.
TYPED_TEST(Magnitudes, timesPowerOfTwoIsLdexp) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  const std::vector<T> values = across_the_range<T>();
  const int ks[] = {0,
                    1,
                    -1,
                    limits::digits,
                    -limits::digits - 1,
                    limits::max_exponent - 1,
                    limits::max_exponent,
                    limits::min_exponent - 1,
                    limits::min_exponent - 2,
                    limits::min_exponent - limits::digits,
                    2 * limits::max_exponent,
                    2 * limits::min_exponent - limits::digits};
  for (const int k : ks) {
    for (std::size_t i = 0; i < values.size(); i += 3) {
      const T expected = std::ldexp(values[i], k);
      const T got = times_power_of_two(values[i], k);
      ASSERT_TRUE(got == expected && std::signbit(got) == std::signbit(expected))
          << static_cast<long double>(values[i]) << " k " << k;
    }
  }
}

TYPED_TEST(Magnitudes, biasedExponentReadsTheField) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  if constexpr (ExponentBits<T>::known) {
    constexpr unsigned all_ones = ExponentBits<T>::all_ones;
    EXPECT_EQ(biased_exponent(T(1)), unsigned(ExponentBits<T>::bias));
    EXPECT_EQ(biased_exponent(T(-0.75)), unsigned(ExponentBits<T>::bias - 1));
    EXPECT_EQ(biased_exponent(T(0)), 0u);
    EXPECT_EQ(biased_exponent(T(-0.0)), 0u);
    EXPECT_EQ(biased_exponent(limits::denorm_min()), 0u);
    EXPECT_EQ(biased_exponent(limits::min()), 1u);
    EXPECT_EQ(biased_exponent(limits::max()), all_ones - 1);
    EXPECT_EQ(biased_exponent(limits::infinity()), all_ones);
    EXPECT_EQ(biased_exponent(-limits::infinity()), all_ones);
    EXPECT_EQ(biased_exponent(limits::quiet_NaN()), all_ones);
  }
}

}  // namespace
}  // namespace oblique
