// The accurate method (accurate/accurate.h) on its own claims: every entry of M'_3 the correctly
// rounded exact answer (rational oracle, oracle::Problem) where its perspective fast path
// certifies it, within oracle::tolerance::kAccurateUlps everywhere; the fast path and the refining
// path give the same matrix; the closed form and the general method hand it what they cannot
// settle.
#include "oblique/detail/accurate/accurate.h"
#include "oblique/definitions.h"  // detail::apply_checked(), detail::accurate() (declared compiled)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "oblique/detail/equilibrated_solver.h"
#include "oblique/oblique.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "printers.h"

namespace oblique {
namespace {

/// The accurate method on its own (detail::accurate()), scaled as apply() scales the plane.
template <class T>
ObliqueResult<T> accurate_method(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                                 bool perspective_shape) {
  return detail::accurate(m, c, convention, detail::Shape(perspective_shape), plane_scale(c),
                          detail::Entries::unchecked);
}

template <class T>
class AccurateMethod : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(AccurateMethod, Scalars);

const double kFovy = 1.0471975511965976;  // 60 degrees

static_assert(std::is_same_v<detail::AccurateWorkingType<float>::type, double>);
static_assert(std::is_same_v<detail::AccurateWorkingType<double>::type, double>);
static_assert(std::is_same_v<detail::AccurateWorkingType<long double>::type, long double>);

/// Ordinary clip planes with the camera behind them, including one close to the standard near
/// plane (the a C_z + 1 cancellation of the GL formula) and one almost through the eye.
template <class T>
std::vector<Vector4<T>> planes() {
  return {Vector4<T>(T(0.3), T(-0.2), T(-1), T(-2)), Vector4<T>(T(0.6), T(0.28), T(-0.75), T(-1)),
          Vector4<T>(T(0), T(0), T(-1), T(-0.1000001)),
          Vector4<T>(T(-0.125), T(0.5), T(-0.25), T(-1e-3)), Vector4<T>(T(1), T(2), T(-3), T(-4))};
}

template <class T>
std::vector<Matrix4<T>> perspective_matrices(Convention convention) {
  return {perspective<T>(T(kFovy), T(1.5), T(0.1), T(1000), convention),
          perspective<T>(T(kFovy), T(0.75), T(1), T(3), convention),
          frustum<T>(T(-0.3), T(0.5), T(-0.2), T(0.1), T(0.25), T(64), convention),
          infinite_perspective<T>(T(kFovy), T(1.5), T(0.1), convention)};
}

std::string describe(Convention convention, int matrix, int plane) {
  return std::string(convention_name(convention)) + " matrix " + std::to_string(matrix) +
         " plane " + std::to_string(plane);
}

// The fast path's answer, where it gives one, is the exact answer correctly rounded: each entry
// is accepted only when its whole error interval rounds to one value.
TYPED_TEST(AccurateMethod, fastPathIsCorrectlyRounded) {
  using T = TypeParam;
  using W = typename detail::AccurateWorkingType<T>::type;
  int answered = 0;
  for (Convention convention : all_conventions) {
    const auto matrices = perspective_matrices<T>(convention);
    const auto cs = planes<T>();
    for (std::size_t i = 0; i < matrices.size(); ++i) {
      for (std::size_t j = 0; j < cs.size(); ++j) {
        const Matrix4<T>& m = matrices[i];
        const Vector4<T>& c = cs[j];
        const oracle::Problem<T> problem(m, c, convention);
        if (problem.exact_status() != Status::ok) continue;
        const Vector4<W> c_w = c.template cast<W>();
        const ScaledPlane<W> scaled = scale_plane(c_w, plane_scale(c));
        const W sign_x = W(detail::sign(c.x()) * detail::sign(m(0, 0)));
        const W sign_y = W(detail::sign(c.y()) * detail::sign(m(1, 1)));
        const W sign_z = W(detail::sign(c.w()) * detail::sign(m(2, 3)));
        const Vector4<W> corner = detail::clip_corner(sign_x, sign_y, sign_z, convention);
        const auto fast = detail::perspective_row3_dispatched<T>(scaled, m, corner, convention);
        if (!fast) continue;
        ++answered;
        const oracle::exact::Vec row3 = problem.exact_row3();
        for (int k = 0; k < 4; ++k) {
          EXPECT_EQ(oracle::exact::ulp_distance(fast->row3(k), row3[k]), 0.0)
              << describe(convention, int(i), int(j)) << " entry " << k;
        }
        // And the accurate method returns it.
        const ObliqueResult<T> r = accurate_method(m, c, convention, true);
        ASSERT_TRUE(r.ok()) << r.message();
        EXPECT_EQ(Vector4<T>(r.projection.row(2).transpose()), fast->row3)
            << describe(convention, int(i), int(j));
      }
    }
  }
  // Most of these ordinary inputs are the fast path's: it must not have gone quiet.
  EXPECT_GE(answered, 40);
}

// The refining path (the equilibrated LU, refined corner, exact products) on the same
// perspective inputs, and the fast path, give the same matrix: both round the exact answer.
TYPED_TEST(AccurateMethod, fastPathAndRefiningPathAgree) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    const auto matrices = perspective_matrices<T>(convention);
    const auto cs = planes<T>();
    for (std::size_t i = 0; i < matrices.size(); ++i) {
      for (std::size_t j = 0; j < cs.size(); ++j) {
        const ObliqueResult<T> fast = accurate_method(matrices[i], cs[j], convention, true);
        const ObliqueResult<T> refined = accurate_method(matrices[i], cs[j], convention, false);
        ASSERT_EQ(fast.status, refined.status) << describe(convention, int(i), int(j));
        EXPECT_EQ(fast.method, Method::accurate);
        EXPECT_EQ(refined.method, Method::accurate);
        if (!fast.ok()) continue;
        EXPECT_EQ(fast.projection, refined.projection) << describe(convention, int(i), int(j));
      }
    }
  }
}

// Matrices without the perspective shape take the refining path; its promise is
// oracle::tolerance::kAccurateUlps of the correctly rounded answer, which it keeps here.
TYPED_TEST(AccurateMethod, generalMatricesWithinPromisedUlps) {
  using T = TypeParam;
  for (Convention convention : all_conventions) {
    Matrix4<T> rotated = perspective<T>(T(kFovy), T(1.5), T(0.1), T(100), convention);
    Matrix4<T> rotation = Matrix4<T>::Identity();
    rotation.template topLeftCorner<2, 2>() << T(0.6), T(-0.8), T(0.8), T(0.6);
    rotated = Matrix4<T>(rotated * rotation);
    const std::vector<Matrix4<T>> matrices = {
        orthographic<T>(T(-2), T(3), T(-1), T(1.5), T(0.5), T(50), convention), rotated};
    const auto cs = planes<T>();
    for (std::size_t i = 0; i < matrices.size(); ++i) {
      for (std::size_t j = 0; j < cs.size(); ++j) {
        const oracle::Problem<T> problem(matrices[i], cs[j], convention);
        const ObliqueResult<T> r = accurate_method(matrices[i], cs[j], convention, false);
        ASSERT_EQ(r.status, problem.exact_status()) << describe(convention, int(i), int(j));
        if (!r.ok()) continue;
        EXPECT_LE(problem.ulps_from_exact(r.projection), oracle::tolerance::kAccurateUlps)
            << describe(convention, int(i), int(j));
      }
    }
  }
}

/// A general matrix whose far corner Q is dominated by one component j: rows 2 to 4 share the
/// entry v in column j, so where rows 2 to 4 of the corner Q' are 1 (as in every case the filter
/// below keeps), Q_j = 1 / v and the other components come only from row 1, whose huge
/// M11 = 2^e makes Q_x tiny, and through column x the others (`fuzz_oblique`'s find, kept as
/// fuzz/regressions/fuzz_oblique/crash-accurate-small-corner-components, is one). Then C . Q and
/// M4 . Q = 1 are both nearly C_j Q_j, so the entry M4_j - a C_j of row 3 cancels down to what
/// Q's small components contribute, weighted by C (one of whose components is large) and M4.
/// Each solve of the refinement is accurate relative to Q's largest component (componentwise to
/// |M^-1| |M| |x|), not to the small ones, so those converge far slower than Q as a whole.
template <class T>
struct SmallCornerComponents {
  Matrix4<T> m;
  Vector4<T> c;
  Convention convention;
  int j;  ///< the dominant component
};

template <class T>
std::vector<SmallCornerComponents<T>> small_corner_component_cases(int count) {
  constexpr int p = std::numeric_limits<T>::digits;
  std::mt19937_64 random(23);
  const auto pick = [&random](int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random);
  };
  const auto dyadic = [&pick](int low_eighths, int high_eighths) {  // k / 8, nonzero
    int k = 0;
    while (k == 0) k = pick(low_eighths, high_eighths);
    return T(k) / T(8);
  };
  std::vector<SmallCornerComponents<T>> out;
  while (static_cast<int>(out.size()) < count) {
    SmallCornerComponents<T> s;
    s.convention = all_conventions[pick(0, 2)];
    s.j = pick(1, 3);
    const T v = (s.j == 3 ? T(-1) : T(pick(0, 1) ? 1 : -1)) * dyadic(8, 64);
    // M11 = 2^e (1 + k / 16) with e up to 2p - 8: within the core's magnitude spread of 2p binades.
    s.m(0, 0) = std::ldexp(T(16 + pick(0, 15)) / T(16), pick(p / 2, 2 * p - 8));
    for (int col = 1; col < 4; ++col) s.m(0, col) = dyadic(-64, 64);
    for (int row = 1; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) s.m(row, col) = col == s.j ? v : dyadic(-64, 64);
    }
    // C_j of v's sign (C_j Q_j > 0), or (a quarter of the cases, j = y or z) zero, so that C . Q
    // itself rests on the small components (fuzz_oblique's second find,
    // crash-accurate-corner-dot-on-small-components); C_w < 0; one other component huge.
    for (int i = 0; i < 4; ++i) s.c(i) = dyadic(-64, 64);
    s.c(s.j) = (v > T(0) ? T(1) : T(-1)) * dyadic(8, 64);
    const bool dot_on_small = s.j != 3 && pick(0, 3) == 0;
    if (dot_on_small) s.c(s.j) = T(0);
    s.c(3) = -std::abs(s.c(3));
    // ... on a small component of Q that M11 does not make smaller still: y, z or w.
    const int big = 1 + (s.j + pick(0, 1)) % 3;
    s.c(big) = std::ldexp(s.c(big), pick(p / 4, 2 * p - 16));
    const oracle::Problem<T> problem(s.m, s.c, s.convention);
    if (problem.exact_status() != Status::ok) continue;
    // Of the class: the entry cancels by 2^20 or more, or C . Q rests on the small components.
    const oracle::exact::Rational entry = oracle::exact::abs(problem.exact_row3()[s.j]);
    if (!dot_on_small && !(entry * oracle::exact::power_of_two(20) <
                           oracle::exact::abs(oracle::exact::to_rational(s.m(3, s.j)))))
      continue;
    out.push_back(s);
  }
  return out;
}

/// Judges the accurate method on each case: an answer within kAccurateUlps of the exact one, or a
/// refusal rounding allows (a numerically singular M). Returns how many were answered.
template <class T>
int expect_accurate_answers(const std::vector<SmallCornerComponents<T>>& cases) {
  int answered = 0;
  for (const auto& s : cases) {
    const oracle::Problem<T> problem(s.m, s.c, s.convention);
    const ObliqueResult<T> r = apply<T>(s.m, s.c, s.convention, Method::accurate);
    if (!r.ok()) {
      const std::vector<Status> acceptable = problem.acceptable_statuses();
      EXPECT_NE(std::find(acceptable.begin(), acceptable.end(), r.status), acceptable.end())
          << r.message();
      continue;
    }
    ++answered;
    EXPECT_LE(problem.ulps_from_exact(r.projection), oracle::tolerance::kAccurateUlps)
        << std::setprecision(std::numeric_limits<T>::max_digits10) << convention_name(s.convention)
        << " j " << s.j << "\nM =\n"
        << s.m << "\nC = " << s.c.transpose();
  }
  return answered;
}

// The class above: the accurate method must not take the error of Q's small components to be
// as small as the refinement's progress on Q as a whole.
TYPED_TEST(AccurateMethod, smallComponentsOfTheFarCornerAreResolved) {
  EXPECT_GE(expect_accurate_answers(small_corner_component_cases<TypeParam>(200)), 150);
}

// A plane with one component 2^e times the others against a matrix with one entry 2^f times the
// rest (fuzz/regressions/fuzz_oblique/crash-accurate-stalled-transposed-solve is one): the
// refined solve for C' stalls far above eps, and the error bound of its signs, which assumes a
// backward stable solve, no longer holds. Only the cases where the solve stalls are kept.
template <class T>
std::vector<SmallCornerComponents<T>> stalled_transposed_solve_cases(int count) {
  constexpr int p = std::numeric_limits<T>::digits;
  std::mt19937_64 random(29);
  const auto pick = [&random](int low, int high) {
    return std::uniform_int_distribution<int>(low, high)(random);
  };
  const auto dyadic = [&pick] { return T(pick(-64, 64)) / T(8); };
  std::vector<SmallCornerComponents<T>> out;
  for (int draws = 0; static_cast<int>(out.size()) < count && draws < 200 * count; ++draws) {
    SmallCornerComponents<T> s;
    s.convention = all_conventions[pick(0, 2)];
    for (int i = 0; i < 16; ++i) s.m(i / 4, i % 4) = dyadic();
    s.j = pick(0, 3);
    const int huge_row = pick(0, 3), lone_row = (huge_row + pick(1, 3)) % 4;
    s.m(huge_row, s.j) = std::ldexp(T(16 + pick(0, 15)) / T(16), pick(p / 2, p));
    for (int k = 0; k < 4; ++k) s.m(lone_row, k) = k == s.j ? T(2) : T(0);  // a row of one entry
    for (int i = 0; i < 4; ++i) s.c(i) = dyadic();
    s.c(3) = -std::abs(s.c(3)) - T(0.125);
    const int big = s.j == 3 ? pick(0, 2) : s.j;
    s.c(big) = std::ldexp(s.c(big) == T(0) ? T(1) : s.c(big), pick(p, 2 * p - 16));
    const detail::EquilibratedSolver<T> solver(s.m);
    if (solver.failure() != detail::EquilibratedSolver<T>::Failure::none) continue;
    T backward_error = T(0);
    solver.solve_transposed_unscaled(s.c, &backward_error);
    if (!(backward_error > detail::backward_error_limit<T>())) continue;
    if (oracle::Problem<T>(s.m, s.c, s.convention).exact_status() != Status::ok) continue;
    out.push_back(s);
  }
  return out;
}

// The class above: the accurate method settles the signs exactly where the solve stalled.
TYPED_TEST(AccurateMethod, signsFromAStalledSolveAreSettled) {
  EXPECT_GE(expect_accurate_answers(stalled_transposed_solve_cases<TypeParam>(100)), 50);
}

// A matrix spanning more binades than double holds (fuzz/regressions/fuzz_oblique/
// crash-accurate-cancelling-row3-w-wide-row1): Q's refinement cannot cancel across M's 2^71 in
// twice double's precision, and a row-3 entry cancelling to 2^-65 of its terms came out 10 times
// too small. It is answered exactly now, within the promised ulps.
TEST(AccurateMethodDouble, aMatrixSpanningMoreBinadesThanDoubleIsAnsweredExactly) {
  Matrix4<double> m;
  m << 0, -0x1.24242c2440344p+70, -0x1.bp+1, -0x1.18p+2, -0x1.18p+2, 0x1.24p+4, -0x1.18p+2,
      -0x1.18p+2, 0x1p-1, 0x1.0ac0442p+39, -0x1.18p+2, -0x1.38p+2, 0x1.3p+4, 0x1.5cp+3, -0x1.28p+2,
      -0x1.18p+2;
  const Vector4<double> c(-0x1.18p+2, -0x1.18p+2, -0x1.18p+2, -0x1.18p+2);
  const Convention convention = Convention::reversed_z;
  const oracle::Problem<double> problem(m, c, convention);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  const ObliqueResult<double> r = apply<double>(m, c, convention, Method::accurate);
  ASSERT_EQ(r.status, Status::ok) << r.detail;
  EXPECT_LE(problem.ulps_from_exact(r.projection), oracle::tolerance::kAccurateUlps)
      << r.projection;
}

// A stiff plane (components spanning more than 2p binades): the general method hands it to the
// accurate method, which settles it exactly. (The closed form hands over only a plane whose
// scaling lost bits.)
TYPED_TEST(AccurateMethod, stiffPlanesAreHandedToItAndSettled) {
  using T = TypeParam;
  const T tiny = std::ldexp(T(1), -3 * std::numeric_limits<T>::digits);
  const Vector4<T> c(tiny, T(0.25), T(-1), T(-0.5));
  for (Convention convention : all_conventions) {
    const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), T(0.1), T(100), convention);
    const oracle::Problem<T> problem(m, c, convention);
    ASSERT_EQ(problem.exact_status(), Status::ok);
    for (Method method : {Method::general, Method::accurate}) {
      const ObliqueResult<T> r = apply<T>(m, c, convention, method);
      ASSERT_TRUE(r.ok()) << method_name(method) << ": " << r.message();
      EXPECT_EQ(r.method, Method::accurate) << method_name(method);
      EXPECT_LE(problem.ulps_from_exact(r.projection), oracle::tolerance::kAccurateUlps)
          << method_name(method);
    }
  }
}

// The refusals are the general method's, in the same order, reported as the accurate method's.
TYPED_TEST(AccurateMethod, refusals) {
  using T = TypeParam;
  const Matrix4<T> m = perspective<T>(T(kFovy), T(1.5), T(0.1), T(100), Convention::gl);
  const ObliqueResult<T> in_front =
      accurate_method(m, Vector4<T>(T(0), T(0), T(-1), T(0.5)), Convention::gl, true);
  EXPECT_EQ(in_front.status, Status::camera_not_behind_plane);
  EXPECT_EQ(in_front.method, Method::accurate);
  EXPECT_EQ(in_front.projection, m);
  Matrix4<T> singular = m;
  singular.row(1).setZero();
  const ObliqueResult<T> zero_row =
      accurate_method(singular, Vector4<T>(T(0), T(0), T(-1), T(-0.5)), Convention::gl, false);
  EXPECT_EQ(zero_row.status, Status::singular_projection);
  EXPECT_EQ(zero_row.projection, singular);
  // The plane behind the view volume: C . Q <= 0.
  const ObliqueResult<T> misses =
      accurate_method(m, Vector4<T>(T(0), T(0), T(1), T(-1000)), Convention::gl, true);
  EXPECT_EQ(misses.status, Status::plane_misses_view_volume);
}

// RefinedCorner: each word is the solve of the residual left by the words before it, so a
// system whose answer needs two words gets it, and an exact answer leaves no error.
TEST(RefinedCorner, addsWordsFromExactResiduals) {
  Matrix4<double> m = Matrix4<double>::Identity();
  m(0, 0) = 3;  // x = 1 / 3 takes more than one word
  const Vector4<double> rhs(1, 1, 1, 1);
  const auto solve = [&m](const Vector4<double>& b) {
    return Vector4<double>(m.partialPivLu().solve(b));
  };
  detail::RefinedCorner<double, decltype(solve)> q(m, rhs, solve);
  ASSERT_EQ(q.count(), 1);
  EXPECT_GT(q.remaining_error(Vector4<double>::Ones(), 1e-16), 0.0);
  ASSERT_TRUE(q.add_word());
  EXPECT_EQ(q.count(), 2);
  // 1/3 = x_0 + x_1 to about 2^-106: 3 (x_0 + x_1) - 1 is below 2^-100.
  const oracle::exact::Rational sum =
      oracle::exact::to_rational(q.word(0)(0)) + oracle::exact::to_rational(q.word(1)(0));
  EXPECT_LT(oracle::exact::abs(oracle::exact::Rational(3) * sum - 1),
            oracle::exact::power_of_two(-100));
  // Components 1 to 3 were exact: their corrections are zero.
  for (int i = 1; i < 4; ++i) EXPECT_EQ(q.word(1)(i), 0.0);
  const Vector4<double> weights(0, 1, 1, 1);
  EXPECT_EQ(q.remaining_error(weights, 1e-16), 0.0);
  for (int k = 2; k < detail::kMaxCornerWords; ++k) ASSERT_TRUE(q.add_word());
  EXPECT_FALSE(q.add_word());  // no room beyond kMaxCornerWords
}

}  // namespace
}  // namespace oblique
