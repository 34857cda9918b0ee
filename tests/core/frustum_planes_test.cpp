#include "oblique/references/frustum_planes.h"

#include <gtest/gtest.h>

#include "oblique/projection.h"

namespace oblique {
namespace {

// Planes are compared as directions: a == s b for some s > 0.
::testing::AssertionResult same_plane(const Vector4<double>& a, const Vector4<double>& b) {
  const double s = a.norm() / b.norm();
  if ((a - s * b).cwiseAbs().maxCoeff() <= 1e-14 * a.norm() && a.dot(b) > 0) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << a.transpose() << " is not a positive multiple of " << b.transpose();
}

// glFrustum(l, r, b, t, n, f): the six planes are x = l z / -n ... in every convention.
TEST(FrustumPlanes, extractedPlanesAreTheFrustumFaces) {
  const double l = -1, r = 2, b = -0.5, t = 1.5, n = 0.5, f = 40;
  for (Convention c : all_conventions) {
    for (const Matrix4<double>& m :
         {frustum(l, r, b, t, n, f, c), infinite_frustum(l, r, b, t, n, c)}) {
      const FrustumPlanes<double> planes = frustum_planes(m, c);
      // The left plane passes through the origin and (l, 0, -n) and keeps x > l z / -n.
      EXPECT_TRUE(same_plane(planes.left, Vector4<double>(n, 0, l, 0))) << convention_name(c);
      EXPECT_TRUE(same_plane(planes.right, Vector4<double>(-n, 0, -r, 0))) << convention_name(c);
      EXPECT_TRUE(same_plane(planes.bottom, Vector4<double>(0, n, b, 0))) << convention_name(c);
      EXPECT_TRUE(same_plane(planes.top, Vector4<double>(0, -n, -t, 0))) << convention_name(c);
      EXPECT_TRUE(same_plane(planes.near_plane, Vector4<double>(0, 0, -1, -n)))
          << convention_name(c);
    }
    EXPECT_TRUE(same_plane(far_plane(frustum(l, r, b, t, n, f, c), c), Vector4<double>(0, 0, 1, f)))
        << convention_name(c);
    // Infinite: the far "plane" is the plane at infinity, (0, 0, 0, w) with w > 0.
    const Vector4<double> at_infinity = far_plane(infinite_frustum(l, r, b, t, n, c), c);
    EXPECT_EQ(at_infinity.head<3>(), Eigen::Vector3d::Zero()) << convention_name(c);
    EXPECT_GT(at_infinity.w(), 0) << convention_name(c);
  }
}

TEST(FrustumPlanes, orthographicPlanes) {
  for (Convention c : all_conventions) {
    const FrustumPlanes<double> planes =
        frustum_planes(orthographic(-1.0, 3.0, -2.0, 2.0, 1.0, 9.0, c), c);
    EXPECT_TRUE(same_plane(planes.left, Vector4<double>(1, 0, 0, 1)));
    EXPECT_TRUE(same_plane(planes.right, Vector4<double>(-1, 0, 0, 3)));
    EXPECT_TRUE(same_plane(planes.near_plane, Vector4<double>(0, 0, -1, -1))) << convention_name(c);
    EXPECT_TRUE(same_plane(planes.far_plane, Vector4<double>(0, 0, 1, 9))) << convention_name(c);
  }
}

}  // namespace
}  // namespace oblique
