#include "oblique/projection.h"

#include <gtest/gtest.h>

#include <limits>

#include "oblique/oracle/exact.h"
#include "printers.h"

namespace oblique {
namespace {

// The lecture slides' glFrustum(-4, 4, -3, 3, 5, 80): entries 5/4, 5/3, -85/75, -800/75.
TEST(Projection, slidesGlFrustumMatrix) {
  const Matrix4<double> m = frustum<double>(-4, 4, -3, 3, 5, 80, Convention::gl);
  Matrix4<double> expected;
  expected << 5.0 / 4, 0, 0, 0, 0, 5.0 / 3, 0, 0, 0, 0, -85.0 / 75, -800.0 / 75, 0, 0, -1, 0;
  EXPECT_EQ(m, expected);
}

// The slides' glFrustum(-30, 30, -20, 20, 1, 1000) example maps its corners to the clip cube.
TEST(Projection, slidesCornersReachTheClipCube) {
  const Matrix4<double> m = frustum<double>(-30, 30, -20, 20, 1, 1000, Convention::gl);
  const Vector4<double> near_corner(30, 20, -1, 1), far_corner(30000, 20000, -1000, 1);
  const Vector4<double> a = m * near_corner, b = m * far_corner;
  EXPECT_DOUBLE_EQ(a.x() / a.w(), 1);
  EXPECT_DOUBLE_EQ(a.z() / a.w(), -1);
  EXPECT_DOUBLE_EQ(b.y() / b.w(), 1);
  EXPECT_DOUBLE_EQ(b.z() / b.w(), 1);
}

template <class T>
class Builders : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(Builders, Scalars);

/// Clip-space depth z/w of a camera-space point, in exact arithmetic.
template <class T>
oracle::exact::Rational ndc_depth(const Matrix4<T>& m, const Vector4<T>& p) {
  const oracle::exact::Mat mx = oracle::exact::to_rational(m);
  const oracle::exact::Vec clip = oracle::exact::mul(mx, oracle::exact::to_rational(p));
  return clip[2] / clip[3];
}

// Near and far planes land on each convention's depth range, to within the builders' roundings.
TYPED_TEST(Builders, nearAndFarLandOnTheDepthRange) {
  using T = TypeParam;
  const T n = T(0.5), f = T(300);
  const oracle::exact::Rational tolerance =
      oracle::exact::Rational(16) * oracle::exact::to_rational(std::numeric_limits<T>::epsilon());
  struct Expected {
    Convention convention;
    int at_near, at_far;
  };
  for (const Expected e : {Expected{Convention::gl, -1, 1}, Expected{Convention::zero_one, 0, 1},
                           Expected{Convention::reversed_z, 1, 0}}) {
    for (const Matrix4<T>& m : {frustum<T>(-1, 2, -1, 1, n, f, e.convention),
                                perspective<T>(T(1), T(1.5), n, f, e.convention),
                                orthographic<T>(-1, 2, -1, 1, n, f, e.convention)}) {
      const oracle::exact::Rational at_near = ndc_depth<T>(m, Vector4<T>(T(0.1), T(0.2), -n, 1));
      const oracle::exact::Rational at_far = ndc_depth<T>(m, Vector4<T>(T(0.1), T(0.2), -f, 1));
      EXPECT_LE(oracle::exact::abs(at_near - e.at_near), tolerance)
          << convention_name(e.convention);
      EXPECT_LE(oracle::exact::abs(at_far - e.at_far), tolerance) << convention_name(e.convention);
    }
    // Infinite: the near plane as above, depth -> the far value as z -> -infinity (w = 0 limit).
    const Matrix4<T> inf = infinite_frustum<T>(-1, 2, -1, 1, n, e.convention);
    EXPECT_LE(oracle::exact::abs(ndc_depth<T>(inf, Vector4<T>(0, 0, -n, 1)) - e.at_near),
              tolerance);
    const Vector4<T> direction = inf * Vector4<T>(0, 0, -1, 0);
    EXPECT_EQ(direction.z(), e.at_far * direction.w()) << convention_name(e.convention);
  }
}

TYPED_TEST(Builders, perspectiveShapeIsRecognised) {
  using T = TypeParam;
  for (Convention c : all_conventions) {
    EXPECT_TRUE(has_perspective_shape(frustum<T>(-1, 2, -1, 1, 1, 10, c)));
    EXPECT_TRUE(has_perspective_shape(infinite_perspective<T>(1, 1, 1, c)));
    EXPECT_FALSE(has_perspective_shape(orthographic<T>(-1, 2, -1, 1, 1, 10, c)));
  }
  Matrix4<T> rotated = frustum<T>(-1, 1, -1, 1, 1, 10, Convention::gl);
  rotated(0, 1) = T(1e-30);
  EXPECT_FALSE(has_perspective_shape(rotated));
}

}  // namespace
}  // namespace oblique
