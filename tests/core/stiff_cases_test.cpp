// Stiff inputs: tiny near planes, huge far/near ratios, infinite far planes, planes grazing the
// eye or the far corner. Every method must give the right status, the five properties, and a
// third row within the conditioning bound of the exact (rational) answer; the accurate method,
// every entry within 2 ulp of the exact answer rounded.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "printers.h"

namespace oblique {
namespace {

template <class T>
class StiffCases : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(StiffCases, Scalars);

template <class T>
void expect_correct(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                    const std::string& what) {
  const oracle::Problem<T> problem(m, c, convention);
  ASSERT_EQ(problem.exact_status(), Status::ok) << what;
  for (Method method :
       {Method::automatic, Method::closed_form, Method::general, Method::accurate}) {
    if (method == Method::closed_form && !has_perspective_shape(m)) continue;
    const auto result = apply<T>(m, c, convention, method);
    ASSERT_EQ(result.status, Status::ok) << what << " " << convention_name(convention) << " "
                                         << method_name(method) << ": " << result.message();
    const auto verdicts = problem.check(result.projection);
    for (const auto& v : verdicts.items) {
      EXPECT_TRUE(!v.applies || v.holds)
          << what << " " << convention_name(convention) << " " << method_name(method) << ": "
          << cases::property_name(v.property()) << " " << oracle::residual_text(v) << " vs "
          << oracle::bound_text(v);
    }
    const auto closeness = problem.compare_row3(result.projection);
    EXPECT_TRUE(closeness.within) << what << " " << convention_name(convention) << " "
                                  << method_name(method) << ": row 3 entry "
                                  << closeness.worst_entry << " at " << closeness.ratio
                                  << " of its bound (kappa " << problem.kappa().get_d() << ")";
    if (method == Method::accurate) {
      EXPECT_LE(problem.ulps_from_exact(result.projection), oracle::tolerance::kAccurateUlps)
          << what << " " << convention_name(convention) << ": the accurate method";
    }
  }
}

const double kFovy = 1.0471975511965976;  // 60 degrees

TYPED_TEST(StiffCases, tinyNearPlaneAndHugeFarOverNear) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    for (double far_over_near : {1e3, 1e6, 1e9, 1e12}) {
      const T n = T(1e-6);
      const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), n, T(far_over_near) * n, convention);
      expect_correct<T>(m, Vector4<T>(T(0.3), T(-0.2), T(-1), T(-2e-6)), convention,
                        "f/n=" + std::to_string(far_over_near));
    }
    const Matrix4<T> inf = infinite_perspective<T>(T(kFovy), T(1.5), T(1e-6), convention);
    expect_correct<T>(inf, Vector4<T>(T(0.3), T(-0.2), T(-1), T(-2e-6)), convention, "infinite");
  }
}

// |C_w| from 1e-3 down to 1e-12 (1e-30 for the wider types) of |N|: the plane almost through the
// eye.
TYPED_TEST(StiffCases, planeAlmostThroughTheEye) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), T(0.1), T(1000), convention);
    const Matrix4<T> inf = infinite_perspective<T>(T(kFovy), T(1.5), T(0.1), convention);
    for (int exponent = 3; exponent <= 30; exponent += 3) {
      const T w = -std::pow(T(10), T(-exponent));
      if (w == T(0)) break;
      const Vector4<T> c(T(0.6), T(0.28), T(-0.75), w);
      expect_correct<T>(m, c, convention, "C_w=" + std::to_string(double(w)));
      expect_correct<T>(inf, c, convention, "infinite C_w=" + std::to_string(double(w)));
    }
  }
}

// C . Q = delta |N| |Q|: the plane almost through the far corner, with delta down to about the
// square root of epsilon (kappa ~ 1 / delta).
TYPED_TEST(StiffCases, planeAlmostThroughTheFarCorner) {
  using T = TypeParam;
  using W = long double;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = frustum<T>(T(-0.4), T(0.6), T(-0.3), T(0.5), T(0.5), T(200), convention);
    // Q for the corner (+1, +1, far face), from the closed form in long double.
    const DepthRange range = clip_depth_range(convention);
    const W z_far = convention == Convention::reversed_z ? range.z_low : range.z_high;
    const W A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3),
            K = m(3, 2);
    const W qx = (1 - B / K) / A, qy = (1 - E / K) / D, qz = 1 / K, qw = (z_far - G / K) / H;
    const W nx = 0.125, ny = 0.25, nz = -1;
    const W q_norm = std::sqrt(qx * qx + qy * qy + qz * qz);
    for (W delta = 1e-2L; delta >= std::sqrt(W(std::numeric_limits<T>::epsilon())); delta /= 10) {
      const W cw = (delta * q_norm - (nx * qx + ny * qy + nz * qz)) / qw;
      expect_correct<T>(m, Vector4<T>(T(nx), T(ny), T(nz), T(cw)), convention,
                        "delta=" + std::to_string(double(delta)));
    }
  }
}

// Planes almost parallel to the view axis and almost the standard near plane.
TYPED_TEST(StiffCases, planesNearlyAlongTheAxisAndNearlyStandard) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), T(0.1), T(1000), convention);
    for (T tilt : {T(1e-2), T(1e-4), T(1e-6)}) {
      expect_correct<T>(m, Vector4<T>(T(1), T(0), -tilt, T(-0.5) * tilt), convention, "axis");
      expect_correct<T>(m, Vector4<T>(tilt, -tilt, T(-1), T(-0.1) * (1 + tilt)), convention,
                        "standard");
    }
  }
}

// Plane scale does not matter: the same plane scaled by 2^-40..2^40 and by 1e-8..1e8.
TYPED_TEST(StiffCases, planeScaleIsIrrelevant) {
  using T = TypeParam;
  const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), T(0.1), T(1000), Convention::gl);
  const Vector4<T> c(T(0.3), T(-0.2), T(-1), T(-2));
  const auto reference = apply<T>(m, c, Convention::gl);
  ASSERT_TRUE(reference.ok());
  for (int k = -40; k <= 40; k += 8) {
    const auto scaled = apply<T>(m, Vector4<T>(std::ldexp(T(1), k) * c), Convention::gl);
    ASSERT_TRUE(scaled.ok());
    EXPECT_EQ(scaled.projection, reference.projection) << "2^" << k;
  }
  for (T s : {T(1e-8), T(1e8)}) {
    expect_correct<T>(m, Vector4<T>(s * c), Convention::gl, "scaled");
  }
}

}  // namespace
}  // namespace oblique
