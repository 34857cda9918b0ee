// The accurate method's route for ordinary requests (the plane's scaling read from exponent
// fields, the near plane's test decided by signs where that is provable: apply() with
// Method::accurate) gives what its general route gives (plane_scale(), the full near-plane test:
// detail::apply_checked() told the request is not ordinary), bit for bit, on generated cases of
// every family and convention, on the generator's invalid inputs, and on perspective cases with
// special values put in the plane; and where the fast path's certificate fails (C close to the
// far corner, so that N = K (C . Q) is not resolved in one pass), the refinement answers ok.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "oblique/cases/generators.h"
#include "oblique/definitions.h"  // detail::apply_checked(), detail::accurate() (declared compiled)
#include "oblique/oblique.h"
#include "printers.h"
#include "same_bits.h"

namespace oblique {
namespace {

template <class T>
class AccurateOrdinary : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(AccurateOrdinary, Scalars);

using test::same_bits;

struct Tally {
  long compared = 0;
  long by_ordinary_path = 0;  ///< ordinary requests (ordinary_input()), the route under test
};

template <class T>
void expect_same(const Matrix4<T>& m, const Vector4<T>& c, Convention convention, Tally& tally) {
  const detail::OrdinaryInput input = detail::ordinary_input(m, c);
  const ObliqueResult<T> now = apply<T>(m, c, convention, Method::accurate);
  const ObliqueResult<T> full =
      detail::apply_checked<T>(m, c, convention, Method::accurate, detail::Entries::unchecked);
  ++tally.compared;
  tally.by_ordinary_path += input.ordinary;
  const bool same = now.status == full.status && now.detail == full.detail &&
                    now.method == full.method && same_bits(now.projection, full.projection) &&
                    same_bits(now.far_corner, full.far_corner);
  ASSERT_TRUE(same) << convention_name(convention) << ": now " << status_code(now.status) << " ("
                    << now.message() << "), accurate() " << status_code(full.status) << " ("
                    << full.message() << ")\nM =\n"
                    << m << "\nC = " << c.transpose() << "\nnow M' =\n"
                    << now.projection << "\naccurate() M' =\n"
                    << full.projection << "\nnow Q = " << now.far_corner.transpose()
                    << "\naccurate() Q = " << full.far_corner.transpose();
}

/// Generated cases per type; OBLIQUE_ACCURATE_ORDINARY_CASES, where set, for every type (the
/// compiler-flag variants of tests/CMakeLists.txt run fewer).
template <class T>
int case_count() {
  static const char* const setting = std::getenv("OBLIQUE_ACCURATE_ORDINARY_CASES");
  if (setting != nullptr && std::atoi(setting) > 0) return std::atoi(setting);
  return std::is_same_v<T, double> ? 60000 : 20000;
}

TYPED_TEST(AccurateOrdinary, generatedCasesOfEveryFamilyAndConvention) {
  using T = TypeParam;
  const auto gen = cases::valid_case<T>();
  rc::Random random(17101);
  Tally tally;
  for (int i = 0; i < case_count<T>(); ++i) {
    const cases::Case<T> c = gen(random.split(), i % 101).value();
    expect_same(c.matrix, c.plane, c.convention, tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Both paths were exercised: most perspective-shape requests go the ordinary way, and the
  // rest (other families, hard places) through accurate().
  EXPECT_GT(tally.by_ordinary_path, tally.compared / 10);
  EXPECT_LT(tally.by_ordinary_path, tally.compared);
}

TYPED_TEST(AccurateOrdinary, generatedInvalidInputs) {
  using T = TypeParam;
  const auto gen = cases::invalid_case<T>();
  rc::Random random(17102);
  Tally tally;
  for (int i = 0; i < case_count<T>() / 2; ++i) {
    const cases::Case<T> c = gen(random.split(), i % 101).value();
    expect_same(c.matrix, c.plane, c.convention, tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(tally.compared, 0);
}

// Planes scaled across the exponent range and with components spanning many binades (stiff in
// W, or scaled otherwise than by 2^-e): the path must leave those to accurate().
TYPED_TEST(AccurateOrdinary, planesAcrossTheExponentRange) {
  using T = TypeParam;
  using limits = std::numeric_limits<T>;
  Tally tally;
  const Vector4<T> base(T(0.3), T(-0.2), T(-1), T(-2));
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = perspective<T>(T(1.0471975511965976), T(1.5), T(0.1), T(1000), convention);
    // Every third exponent in float and double, about 300 across long double's range (each
    // long double request here that accurate() answers exactly costs milliseconds).
    const int step = std::max(3, (limits::max_exponent - limits::min_exponent) / 300);
    for (int k = limits::min_exponent - 2; k <= limits::max_exponent; k += step) {
      expect_same<T>(m, Vector4<T>(base * std::ldexp(T(1), k)), convention, tally);
      if (::testing::Test::HasFatalFailure()) return;
      for (int small = 0; small < 4; ++small) {
        Vector4<T> c = base;
        c(small) = std::ldexp(c(small), -k - limits::digits);
        expect_same<T>(m, c, convention, tally);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GT(tally.by_ordinary_path, 0);
  EXPECT_LT(tally.by_ordinary_path, tally.compared);
}

// The certificate can fail: a plane through (almost) the far corner leaves N unresolved in one
// pass; the refinement then answers, the same on both routes: ok where C . Q > 0, and
// plane_misses_view_volume where the nudge took C onto or past the corner.
TYPED_TEST(AccurateOrdinary, planesThroughAlmostTheFarCorner) {
  using T = TypeParam;
  const Convention convention = Convention::gl;
  const Matrix4<T> m = perspective<T>(T(1.0471975511965976), T(1.5), T(0.1), T(1000), convention);
  // Q for C = (1, 1, -1, w): the far corner is ((1 - B/K) / A, (1 - E/K) / D, 1/K, (1 - G/K) / H)
  // in homogeneous form; C . Q = 0 for w = -(Q_x + Q_y - Q_z) / Q_w, and w nudged by a few ulps
  // keeps C . Q positive but far below |C||Q|.
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  const T qx = (T(1) - B / K) / A, qy = (T(1) - E / K) / D, qz = T(1) / K, qw = (T(1) - G / K) / H;
  const T w0 = -(qx + qy - qz) / qw;
  Tally tally;
  int ok = 0;
  for (int step = -8; step <= 8; ++step) {
    T w = w0;
    for (int j = 0; j < std::abs(step); ++j) w = std::nextafter(w, step > 0 ? T(-10) : T(10));
    const Vector4<T> c(T(1), T(1), T(-1), w);
    const detail::OrdinaryInput input = detail::ordinary_input(m, c);
    ASSERT_TRUE(input.ordinary);
    const ObliqueResult<T> r = apply<T>(m, c, convention, Method::accurate);
    EXPECT_TRUE(r.ok() || r.status == Status::plane_misses_view_volume) << r.message();
    ok += r.ok();
    expect_same<T>(m, c, convention, tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(ok, 8);
}

}  // namespace
}  // namespace oblique
