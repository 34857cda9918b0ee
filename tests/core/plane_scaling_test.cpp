// plane_scaling.h and plane.h on hand-picked planes, subnormal components and extreme spreads:
// the shift plane_scale chooses, whether scale_plane lost bits, and when a plane is stiff.
#include "oblique/detail/plane_scaling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "oblique/plane.h"

namespace oblique {
namespace {

template <class T>
class PlaneScaling : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(PlaneScaling, Scalars);

template <class T>
T two_to(int k) {
  return std::ldexp(T(1), k);
}

// An ordinary plane: the largest component to [1/2, 1).
TYPED_TEST(PlaneScaling, ordinaryPlaneLargestToHalfOne) {
  using T = TypeParam;
  const Vector4<T> c(T(0.75), T(0), T(-0.1), T(-3));
  const PlaneScale scale = plane_scale(c);
  EXPECT_EQ(scale.shift, -2);         // 3 = 0.75 2^2
  EXPECT_EQ(scale.spread, 2 - (-3));  // frexp exponents of 3 and 0.1
  EXPECT_FALSE(scale.below_normal);
  EXPECT_EQ(plane_scale_shift(c), -2);
  const ScaledPlane<T> scaled = scale_plane(c, scale);
  EXPECT_EQ(scaled.shift, -2);
  EXPECT_FALSE(scaled.lossy);
  EXPECT_EQ(scaled.c_hat, Vector4<T>(T(0.1875), T(0), T(-0.025), T(-0.75)));
  EXPECT_FALSE(stiff_plane(scale, scaled));
  // The zero plane and a single component.
  EXPECT_EQ(plane_scale(Vector4<T>::Zero()).shift, 0);
  EXPECT_EQ(plane_scale(Vector4<T>(T(0), T(0), T(0), T(-8))).shift, -4);
  EXPECT_EQ(plane_scale(Vector4<T>(T(0), T(0), T(0), T(-8))).spread, 0);
}

// A subnormal component beside ordinary ones: the shift keeps it normal instead (its bits may
// carry C . Q), and nothing is lost.
TYPED_TEST(PlaneScaling, subnormalComponentKeptNormal) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  const T sub = limits::denorm_min() * T(5);
  const Vector4<T> c(T(1), T(0), sub, T(-0.5));
  const PlaneScale scale = plane_scale(c);
  int low_exponent = 0;
  std::frexp(sub, &low_exponent);
  EXPECT_EQ(scale.shift, limits::min_exponent - low_exponent);
  EXPECT_EQ(scale.spread, 1 - low_exponent);
  EXPECT_FALSE(scale.below_normal);
  const ScaledPlane<T> scaled = scale_plane(c, scale);
  EXPECT_FALSE(scaled.lossy);
  EXPECT_GE(std::abs(scaled.c_hat(2)), limits::min());
  EXPECT_EQ(std::ldexp(scaled.c_hat(2), -scale.shift), sub);  // exact
  EXPECT_EQ(scaled.c_hat(0), std::ldexp(T(1), scale.shift));
  // Spread beyond 2p binades: stiff, though nothing was lost.
  EXPECT_GT(scale.spread, max_magnitude_spread<T>());
  EXPECT_TRUE(stiff_plane(scale, scaled));
}

// Keeping the smallest component normal would push the largest beyond 2^(max_exponent / 2):
// the largest goes to [1/2, 1) and the smallest below the normal range, losing its bits.
TYPED_TEST(PlaneScaling, extremeSpreadLosesBits) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  const Vector4<T> c(limits::max(), T(0), T(0), -limits::min() * T(0.75));
  const PlaneScale scale = plane_scale(c);
  EXPECT_EQ(scale.shift, -limits::max_exponent);
  EXPECT_TRUE(scale.below_normal);
  const ScaledPlane<T> scaled = scale_plane(c, scale);
  EXPECT_TRUE(scaled.lossy);
  EXPECT_TRUE(stiff_plane(scale, scaled));
}

// A float plane's scale applied in double (the accurate method's working type): every
// component normal in double, nothing lost where float would lose it.
TEST(PlaneScaling, floatScaleInDouble) {
  const Vector4<float> c(std::numeric_limits<float>::max(), 0.0f, 0.0f,
                         -std::numeric_limits<float>::min() * 0.75f);
  const PlaneScale scale = plane_scale(c);
  ASSERT_TRUE(scale.below_normal);
  EXPECT_TRUE(scale_plane(c, scale).lossy);
  const ScaledPlane<double> wide = scale_plane(Vector4<double>(c.cast<double>()), scale);
  EXPECT_FALSE(wide.lossy);
  EXPECT_EQ(std::ldexp(wide.c_hat(3), -scale.shift), double(c(3)));
}

TYPED_TEST(PlaneScaling, stiffAtMoreThanTwicePrecision) {
  using T = TypeParam;
  constexpr int kLimit = max_magnitude_spread<T>();
  for (int spread : {kLimit - 1, kLimit, kLimit + 1}) {
    const Vector4<T> c(T(0.5), T(0), T(0), -two_to<T>(-spread - 1));  // frexp exponents 0, -spread
    const PlaneScale scale = plane_scale(c);
    EXPECT_EQ(scale.spread, spread);
    EXPECT_EQ(stiff_plane(scale, scale_plane(c, scale)), spread > kLimit) << spread;
  }
}

// (double only: GCC 12 warns about Eigen's comma initialiser for float vectors here.)
TEST(PlaneScaling, planeFromNormalAndPoint) {
  using T = double;
  const Eigen::Matrix<T, 3, 1> normal(T(0), T(0), T(-1)), point(T(1), T(2), T(-0.5));
  const Vector4<T> plane = plane_from_normal_and_point(normal, point);
  EXPECT_EQ(plane, Vector4<T>(T(0), T(0), T(-1), T(-0.5)));
  EXPECT_EQ(plane.dot(Vector4<T>(T(7), T(-3), T(-0.5), T(1))), T(0));  // on the plane
  EXPECT_GT(plane.dot(Vector4<T>(T(0), T(0), T(-2), T(1))), T(0));     // the side normal faces
  EXPECT_LT(plane.dot(Vector4<T>(T(0), T(0), T(0), T(1))), T(0));      // the eye
}

}  // namespace
}  // namespace oblique
