#include "oblique/oblique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iomanip>
#include <limits>
#include <random>
#include <vector>

#include "families.h"
#include "oblique/detail/equilibrated_solver.h"
#include "oblique/oracle/problem.h"
#include "printers.h"

namespace oblique {
namespace {

template <class T>
class ObliqueTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(ObliqueTest, Scalars);

// The paper's Eq. 16: C = (0, 0, -1, -d) moves the near plane to d and keeps the far plane;
// d = n gives M back. With n = 1, f = 2 every step is exact, so "back" means bit for bit.
TYPED_TEST(ObliqueTest, standardNearPlaneGivesTheMatrixBackExactly) {
  using T = TypeParam;
  const Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 2, Convention::gl);
  const auto result = apply<T>(m, Vector4<T>(0, 0, -1, -1), Convention::gl, Method::closed_form);
  ASSERT_TRUE(result.ok()) << result.message();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_EQ(result.projection(i, j), m(i, j)) << i << "," << j;
  }
}

// Eq. 16 for every convention: the oblique matrix for C = (0, 0, -1, -d) is frustum(..., d, f).
TYPED_TEST(ObliqueTest, parallelPlaneMovesTheNearPlaneAndKeepsTheFarPlane) {
  using T = TypeParam;
  const T n = 5, f = 80, d = 12;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = frustum<T>(-4, 4, -3, 3, n, f, convention);
    for (Method method : {Method::closed_form, Method::general}) {
      const auto result = apply<T>(m, Vector4<T>(0, 0, -1, -d), convention, method);
      ASSERT_TRUE(result.ok()) << result.message();
      // The frustum with near plane d has the same side planes only after rescaling rows 1, 2
      // (they depend on n); compare the third rows, which must agree to a few roundings.
      const Matrix4<T> expected =
          frustum<T>(-4 * d / n, 4 * d / n, -3 * d / n, 3 * d / n, d, f, convention);
      const T tolerance = 16 * std::numeric_limits<T>::epsilon();
      for (int j = 0; j < 4; ++j) {
        EXPECT_NEAR(result.projection(2, j), expected(2, j),
                    tolerance * std::abs(expected(2, j)) + tolerance)
            << convention_name(convention) << " " << method_name(method) << " entry " << j;
      }
    }
  }
}

TYPED_TEST(ObliqueTest, autoPicksTheClosedFormOnlyForThePerspectiveShape) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    for (const auto& family : testing::fixed_families<T>(convention)) {
      const auto result = apply<T>(family.matrix, family.plane, convention);
      ASSERT_TRUE(result.ok()) << family.family << ": " << result.message();
      EXPECT_EQ(result.method,
                has_perspective_shape(family.matrix) ? Method::closed_form : Method::general)
          << family.family;
    }
  }
  const Matrix4<T> ortho = orthographic<T>(-1, 1, -1, 1, 1, 10, Convention::gl);
  const auto refused =
      apply<T>(ortho, Vector4<T>(0, 0, -1, -2), Convention::gl, Method::closed_form);
  EXPECT_EQ(refused.status, Status::invalid_input);
  EXPECT_NE(refused.message().find("perspective shape"), std::string_view::npos);
}

// The five properties on one fixed case of every family, convention and method.
TYPED_TEST(ObliqueTest, everyFamilyHasTheFiveProperties) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    for (const auto& family : testing::fixed_families<T>(convention)) {
      const oracle::Problem<T> problem(family.matrix, family.plane, convention);
      ASSERT_EQ(problem.exact_status(), Status::ok) << family.family;
      for (Method method : all_methods) {
        if (method == Method::closed_form && !has_perspective_shape(family.matrix)) continue;
        const auto result = apply<T>(family.matrix, family.plane, convention, method);
        ASSERT_TRUE(result.ok()) << family.family << ": " << result.message();
        const oracle::Verdicts verdicts = problem.check(result.projection);
        for (const auto& v : verdicts.items) {
          EXPECT_TRUE(!v.applies || v.holds)
              << family.family << " " << convention_name(convention) << " " << method_name(method)
              << ": " << cases::property_name(v.property()) << " " << oracle::residual_text(v)
              << " vs " << oracle::bound_text(v);
        }
        EXPECT_EQ(verdicts[cases::Property::infinite_edge_parallel].applies,
                  family.family == "infinite")
            << family.family;
      }
    }
  }
}

TYPED_TEST(ObliqueTest, closedFormAndGeneralAgree) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    for (const auto& family : testing::fixed_families<T>(convention)) {
      if (!has_perspective_shape(family.matrix)) continue;
      const auto closed = apply<T>(family.matrix, family.plane, convention, Method::closed_form);
      const auto general = apply<T>(family.matrix, family.plane, convention, Method::general);
      ASSERT_TRUE(closed.ok() && general.ok()) << family.family;
      const T scale = closed.projection.row(2).cwiseAbs().maxCoeff();
      EXPECT_LE((closed.projection - general.projection).cwiseAbs().maxCoeff(),
                64 * std::numeric_limits<T>::epsilon() * scale)
          << family.family << " " << convention_name(convention);
    }
  }
}

TYPED_TEST(ObliqueTest, nonFiniteInputIsInvalid) {
  using T = TypeParam;
  const Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 10, Convention::gl);
  const Vector4<T> plane(0, 0, -1, -2);
  Matrix4<T> bad = m;
  bad(2, 3) = std::numeric_limits<T>::quiet_NaN();
  auto result = apply<T>(bad, plane, Convention::gl);
  EXPECT_EQ(result.status, Status::invalid_input);
  EXPECT_NE(result.message().find("NaN or infinite entry"), std::string_view::npos);
  result = apply<T>(m, Vector4<T>(0, std::numeric_limits<T>::infinity(), -1, -2), Convention::gl);
  EXPECT_EQ(result.status, Status::invalid_input);
  EXPECT_NE(result.message().find("clip plane"), std::string_view::npos);
}

TYPED_TEST(ObliqueTest, singularMatrixIsRefused) {
  using T = TypeParam;
  Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 10, Convention::gl);
  m(2, 3) = 0;  // the perspective shape with H = 0: rows 3 and 4 are parallel
  for (Method method : {Method::closed_form, Method::general}) {
    const auto result = apply<T>(m, Vector4<T>(0, 0, -1, -2), Convention::gl, method);
    EXPECT_EQ(result.status, Status::singular_projection) << method_name(method);
    EXPECT_NE(result.message().find("singular"), std::string_view::npos);
  }
  Matrix4<T> rank3 = Matrix4<T>::Identity();
  rank3.row(3) = rank3.row(0) + rank3.row(1);
  EXPECT_EQ(apply<T>(rank3, Vector4<T>(0, 0, -1, -2), Convention::gl).status,
            Status::singular_projection);
}

TYPED_TEST(ObliqueTest, cameraMustBeStrictlyBehindThePlane) {
  using T = TypeParam;
  const Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 10, Convention::zero_one);
  for (T w : {T(0), T(-0.0), T(2)}) {
    const auto result = apply<T>(m, Vector4<T>(0, 0, -1, w), Convention::zero_one);
    EXPECT_EQ(result.status, Status::camera_not_behind_plane) << w;
    EXPECT_NE(result.message().find("C_w >= 0"), std::string_view::npos);
  }
}

TYPED_TEST(ObliqueTest, planeBehindTheCameraMissesTheViewVolume) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 10, convention);
    // z >= 1 is behind the camera; so is z <= -20 beyond the far plane for the plane (0,0,-1,-20).
    for (const Vector4<T>& plane : {Vector4<T>(0, 0, 1, -1), Vector4<T>(0, 0, -1, -20)}) {
      for (Method method : {Method::closed_form, Method::general}) {
        const auto result = apply<T>(m, plane, convention, method);
        EXPECT_EQ(result.status, Status::plane_misses_view_volume)
            << convention_name(convention) << " " << method_name(method);
        EXPECT_NE(result.message().find("skipped"), std::string_view::npos);
      }
    }
  }
}

// A plane through the far corner Q within the subnormal range: a = 2 / (C . Q) exceeds the type.
TYPED_TEST(ObliqueTest, answerBeyondTheTypeIsOutOfRange) {
  using T = TypeParam;
  // A frustum scaled by 2^(emax - 4) (its far corner Q shrinks by as much) and a plane 2^-20 from
  // Q: a = 2 / (C . Q) is about 2^(emax + 17), so a C overflows although the input is benign.
  const Matrix4<T> m = std::ldexp(T(1), std::numeric_limits<T>::max_exponent - 4) *
                       frustum<T>(-1, 1, -1, 1, 1, 2, Convention::gl);
  const Vector4<T> plane(1, 0, 0, T(-2) + std::ldexp(T(1), -20));
  ASSERT_LE(magnitude_spread(m), max_magnitude_spread<T>());
  for (Method method : {Method::closed_form, Method::general}) {
    const auto result = apply<T>(m, plane, Convention::gl, method);
    EXPECT_EQ(result.status, Status::out_of_range) << method_name(method);
    EXPECT_NE(result.message().find("exceeds the range"), std::string_view::npos)
        << result.message();
  }
}

TYPED_TEST(ObliqueTest, matrixSpanningTooManyBinadesIsOutOfRange) {
  using T = TypeParam;
  const int limit = max_magnitude_spread<T>();
  Matrix4<T> m = frustum<T>(-1, 1, -1, 1, 1, 2, Convention::gl);  // entries 1 .. 4
  const Vector4<T> plane(0.5, 0, -1, -1.5);
  ASSERT_EQ(apply<T>(m, plane, Convention::gl).status, Status::ok);
  m(0, 1) = std::ldexp(T(1), -limit + 1);  // spread limit + 1 (4 = 2^2)
  EXPECT_EQ(magnitude_spread(m), limit + 1);
  const auto wide_matrix = apply<T>(m, plane, Convention::gl);
  EXPECT_EQ(wide_matrix.status, Status::out_of_range);
  EXPECT_NE(wide_matrix.message().find("binades"), std::string_view::npos);
  m(0, 1) = std::ldexp(T(1), -limit + 2);  // exactly at the limit: computed
  EXPECT_NE(apply<T>(m, plane, Convention::gl).status, Status::out_of_range);
  // A plane's spread is not limited (C_w far below |N| is the plane almost through the eye).
  const Vector4<T> wide_plane(std::ldexp(T(1), -(limit + limit / 2)), 0, -1, -1.5);
  EXPECT_EQ(
      apply<T>(frustum<T>(-1, 1, -1, 1, 1, 2, Convention::gl), wide_plane, Convention::gl).status,
      Status::ok);
}

// magnitude_spread_exceeds (the core's check, without ilogb where the ratio decides) agrees with
// magnitude_spread on spreads around the limit, significands at both ends of their binades,
// subnormals, zeros and values near overflow.
TYPED_TEST(ObliqueTest, spreadCheckAgreesWithTheSpread) {
  using T = TypeParam;
  constexpr int limit = max_magnitude_spread<T>();
  const T below_two = T(2) - std::numeric_limits<T>::epsilon();
  const T denorm = std::numeric_limits<T>::denorm_min();
  int checked = 0;
  for (T low_significand : {T(1), T(1.5), below_two}) {
    for (T high_significand : {T(1), T(1.5), below_two}) {
      for (int low_exponent : {std::numeric_limits<T>::min_exponent - 1, -3, 0, 7}) {
        for (int gap = limit - 2; gap <= limit + 2; ++gap) {
          const int high_exponent = low_exponent + gap;
          if (high_exponent >= std::numeric_limits<T>::max_exponent) continue;
          const Vector4<T> v(std::ldexp(low_significand, low_exponent), T(0),
                             -std::ldexp(high_significand, high_exponent), T(0));
          EXPECT_EQ(magnitude_spread_exceeds<limit>(v), magnitude_spread(v) > limit)
              << v.transpose() << " spread " << magnitude_spread(v);
          ++checked;
        }
      }
    }
  }
  const Vector4<T> subnormal_to_large(denorm, T(0), std::ldexp(T(1), limit - 60), T(0));
  EXPECT_EQ(magnitude_spread_exceeds<limit>(subnormal_to_large),
            magnitude_spread(subnormal_to_large) > limit);
  const Vector4<T> near_overflow(std::numeric_limits<T>::max(), T(1), T(0), T(0));
  EXPECT_EQ(magnitude_spread_exceeds<limit>(near_overflow),
            magnitude_spread(near_overflow) > limit);
  EXPECT_FALSE(magnitude_spread_exceeds<limit>(Vector4<T>::Zero().eval()));
  EXPECT_GT(checked, 100);
}

// Two rows alike but for one column j, whose two entries are 2^e times the others, and a column k
// that only those rows fill (fuzz/regressions/fuzz_oblique/crash-general-untrusted-sign-not-zero
// is one). The general method's error bound on C' = M^-T C, from a computed inverse, is then far
// above the error, and a component of C' well away from 0 can fall within it: its sign must be
// settled (by the accurate method), not taken as 0, which puts Q in the middle of an edge.
template <class T>
struct AlikeRows {
  Matrix4<T> m;
  Vector4<T> c;
  Convention convention;
};

template <class T>
std::vector<AlikeRows<T>> alike_rows_cases(int count) {
  constexpr int p = std::numeric_limits<T>::digits;
  std::mt19937_64 random(27);
  const auto pick = [&random](int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random);
  };
  const auto dyadic = [&pick] { return T(pick(-64, 64)) / T(8); };
  std::vector<AlikeRows<T>> out;
  while (static_cast<int>(out.size()) < count) {
    AlikeRows<T> s;
    s.convention = all_conventions[pick(0, 2)];
    for (int i = 0; i < 16; ++i) s.m(i / 4, i % 4) = dyadic();
    const int r = pick(0, 3), other = (r + pick(1, 3)) % 4, j = pick(0, 3);
    s.m.row(other) = s.m.row(r);
    const int e = pick(p + 8, p + 16);
    s.m(r, j) = std::ldexp(T(16 + pick(0, 15)) / T(16), e);
    s.m(other, j) = std::ldexp(T(16 + pick(0, 15)) / T(16), e);
    const int k = (j + pick(1, 3)) % 4;
    for (int i = 0; i < 4; ++i) {
      if (i != r && i != other) s.m(i, k) = T(0);
    }
    for (int i = 0; i < 4; ++i) s.c(i) = dyadic();
    s.c(3) = -std::abs(s.c(3)) - T(0.125);
    // Of the class: a nonzero component of C' (x, y or z) within the solver's bound.
    const detail::EquilibratedSolver<T> solver(s.m);
    if (solver.failure() != detail::EquilibratedSolver<T>::Failure::none) continue;
    const Vector4<T> y = solver.solve_transposed_unscaled(s.c);
    const Vector4<T> bound = solver.transposed_error_bound(y);
    bool of_the_class = false;
    for (int i = 0; i < 3; ++i) of_the_class |= y(i) != T(0) && std::abs(y(i)) <= bound(i);
    if (!of_the_class) continue;
    if (oracle::Problem<T>(s.m, s.c, s.convention).exact_status() != Status::ok) continue;
    out.push_back(s);
  }
  return out;
}

// In float, where fuzz_oblique found it: about 2% of the draws are of the class (60 of the 200
// answers broke a property before the fix). In double the same construction gives about one in
// 5,000, so the test would spend its time drawing.
TEST(GeneralMethod, settlesSignsItsBoundCannotVouchFor) {
  using T = float;
  int answered = 0;
  for (const auto& s : alike_rows_cases<T>(100)) {
    const oracle::Problem<T> problem(s.m, s.c, s.convention);
    const std::vector<Status> acceptable = problem.acceptable_statuses();
    for (Method method : {Method::automatic, Method::general}) {
      const ObliqueResult<T> result = apply<T>(s.m, s.c, s.convention, method);
      if (!result.ok()) {  // a refusal rounding allows (a numerically singular M)
        EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), result.status), acceptable.end())
            << method_name(method) << ": " << result.message();
        continue;
      }
      ++answered;
      for (const auto& v : problem.check(result.projection).items) {
        EXPECT_TRUE(!v.applies || v.holds)
            << convention_name(s.convention) << " " << method_name(method) << ": "
            << cases::property_name(v.property()) << " " << oracle::residual_text(v) << " vs "
            << oracle::bound_text(v) << std::setprecision(std::numeric_limits<T>::max_digits10)
            << "\nM =\n"
            << s.m << "\nC = " << s.c.transpose();
      }
    }
  }
  EXPECT_GE(answered, 150);
}

// Infinite perspective matrices whose far corner Q = (Q_x, Q_y, -1, 0) has tiny x and y (M11,
// M22 about 2^s) and planes whose C . Q = C_x Q_x + C_y Q_y rests on x and y components far
// smaller than C_w (fuzz/regressions/fuzz_oblique/crash-closed-form-dot-product-underflows is
// one): with C scaled so that C_w is about 1, the products c_hat_i Q_i fall below the normal
// range and the rounded C . Q keeps little or nothing of them (0: "the plane misses the view
// volume" for a plane that cuts it). Such a C . Q must be settled exactly, not taken as it came.
template <class T>
void expect_underflowing_dot_products_settled() {
  using limits = std::numeric_limits<T>;
  constexpr int p = limits::digits;
  std::mt19937_64 random(41);
  const auto pick = [&random](int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random);
  };
  int answered = 0, judged = 0;
  while (judged < 300) {
    const Convention convention = all_conventions[pick(0, 2)];
    const int s = pick(p + 4, 2 * p - 8);  // the matrix spans s binades (refused above 2p)
    const T half_width = std::ldexp(T(pick(8, 15)) / T(8), -s);
    const T shift_x = half_width * T(pick(-8, 8)) / T(8),
            shift_y = half_width * T(pick(-8, 8)) / T(8);
    const Matrix4<T> m =
        infinite_frustum<T>(shift_x - half_width, shift_x + half_width, shift_y - half_width,
                            shift_y + half_width, T(pick(1, 8)) / T(4), convention);
    // C_w = -2^kw; C_x, C_y about 2^(kw + e) so that C scaled by 2^-kw has them about 2^e and
    // C . Q is about 2^(e - s) after the scaling, below the normal range. Half the cases put 2^e
    // at the bottom of the normal range (the answer a C_w, about 2^(s - e), then overflows: only
    // out_of_range is right, as for the fuzz find), half where a C_w is representable.
    const int kw = pick(0, limits::max_exponent - 2);
    const int e = pick(0, 1) ? pick(limits::min_exponent - 1, limits::min_exponent + p)
                             : s + pick(2 - limits::max_exponent, limits::min_exponent + p - 1);
    const auto small = [&] { return std::ldexp(T(pick(-16, 16)) / T(8), kw + e); };
    const Vector4<T> c(small(), small(), T(0), -std::ldexp(T(pick(8, 15)) / T(8), kw));
    const oracle::Problem<T> problem(m, c, convention);
    if (problem.exact_status() != Status::ok) continue;
    ++judged;
    const std::vector<Status> acceptable = problem.acceptable_statuses();
    for (Method method : {Method::automatic, Method::closed_form, Method::general}) {
      const ObliqueResult<T> result = apply<T>(m, c, convention, method);
      if (!result.ok()) {  // a refusal rounding allows (an answer beyond the range)
        EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), result.status), acceptable.end())
            << convention_name(convention) << " " << method_name(method) << ": " << result.message()
            << std::setprecision(limits::max_digits10) << "\nM =\n"
            << m << "\nC = " << c.transpose();
        continue;
      }
      ++answered;
      for (const auto& v : problem.check(result.projection).items) {
        EXPECT_TRUE(!v.applies || v.holds)
            << convention_name(convention) << " " << method_name(method) << ": "
            << cases::property_name(v.property()) << " " << oracle::residual_text(v) << " vs "
            << oracle::bound_text(v) << std::setprecision(limits::max_digits10) << "\nM =\n"
            << m << "\nC = " << c.transpose();
      }
    }
  }
  EXPECT_GT(answered, 0);
}

TEST(ClosedForm, settlesADotProductBelowTheNormalRangeFloat) {
  expect_underflowing_dot_products_settled<float>();
}
TEST(ClosedForm, settlesADotProductBelowTheNormalRangeDouble) {
  expect_underflowing_dot_products_settled<double>();
}
TEST(ClosedForm, settlesADotProductBelowTheNormalRangeLongDouble) {
  expect_underflowing_dot_products_settled<long double>();
}

}  // namespace
}  // namespace oblique

namespace oblique {
namespace {

// The checker judges any matrix, a non-finite one included, without trapping (GMP would).
TEST(Checker, nonFiniteResultViolatesThePropertiesInsteadOfCrashing) {
  const Matrix4<double> m = frustum<double>(-1, 1, -1, 1, 1, 10, Convention::gl);
  const oracle::Problem<double> problem(m, Vector4<double>(0.5, 0, -1, -2), Convention::gl);
  Matrix4<double> bad = m;
  bad(2, 2) = std::numeric_limits<double>::quiet_NaN();
  const auto verdicts = problem.check(bad);
  EXPECT_FALSE(verdicts[cases::Property::near_is_clip_plane].holds);
  EXPECT_TRUE(verdicts[cases::Property::side_rows_unchanged].holds);
  EXPECT_FALSE(problem.compare_row3(bad).within);
}

}  // namespace
}  // namespace oblique
