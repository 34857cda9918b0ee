// apply_batch() gives what apply() gives, request by request, bit for bit: through its blocks of
// requests (detail::closed_form_lanes) as well as one by one, in both forms and in place, for
// every method and convention, on valid and invalid requests and on the edges of the blocks'
// path; and every lane a block answers is apply()'s answer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "oblique/batch.h"
#include "oblique/cases/generators.h"
#include "oblique/detail/batch_lanes.h"
#include "oblique/oblique.h"
#include "printers.h"
#include "same_bits.h"
#include "special_values.h"

namespace oblique {
namespace {

template <class T>
class ApplyBatch : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(ApplyBatch, Scalars);

using test::same_bits;

/// apply_batch() over the first n requests, both forms and in place, against apply() request by
/// request; nothing written past the count. Adds to `compared` and `ok` (apply()'s ok answers).
template <class T>
void expect_batch_is_apply(const std::vector<Matrix4<T>>& matrices,
                           const std::vector<Vector4<T>>& planes, std::size_t n,
                           Convention convention, Method method, long& compared, long& ok) {
  std::vector<Matrix4<T>> out(n + 1, Matrix4<T>::Constant(T(7)));
  std::vector<Status> statuses(n + 1, Status::invalid_input);
  std::vector<ObliqueResult<T>> results(n + 1);
  std::vector<Matrix4<T>> in_place(matrices.begin(), matrices.begin() + std::ptrdiff_t(n));
  std::vector<Status> in_place_statuses(n);
  apply_batch<T>(matrices.data(), planes.data(), n, convention, method, out.data(),
                 statuses.data());
  apply_batch<T>(matrices.data(), planes.data(), n, convention, method, results.data());
  apply_batch<T>(in_place.data(), planes.data(), n, convention, method, in_place.data(),
                 in_place_statuses.data());
  // Nothing written past the count.
  ASSERT_TRUE(same_bits(out[n], Matrix4<T>(Matrix4<T>::Constant(T(7)))));
  ASSERT_EQ(statuses[n], Status::invalid_input);
  for (std::size_t i = 0; i < n; ++i) {
    const ObliqueResult<T> one = apply<T>(matrices[i], planes[i], convention, method);
    ++compared;
    ok += one.ok();
    ASSERT_EQ(statuses[i], one.status) << i << " of " << n << " " << method_name(method);
    ASSERT_TRUE(same_bits(out[i], one.projection))
        << i << " of " << n << " " << method_name(method) << "\nM =\n"
        << matrices[i] << "\nC = " << planes[i].transpose() << "\nbatch M' =\n"
        << out[i] << "\napply M' =\n"
        << one.projection;
    ASSERT_EQ(in_place_statuses[i], one.status) << i << " " << method_name(method);
    ASSERT_TRUE(same_bits(in_place[i], one.projection)) << i << " " << method_name(method);
    ASSERT_EQ(results[i].status, one.status) << i << " " << method_name(method);
    ASSERT_EQ(results[i].detail, one.detail) << i << " " << method_name(method);
    ASSERT_EQ(results[i].method, one.method) << i << " " << method_name(method);
    ASSERT_TRUE(same_bits(results[i].projection, one.projection)) << i;
    ASSERT_TRUE(same_bits(results[i].far_corner, one.far_corner)) << i;
  }
}

// apply_batch, both forms and in place, against apply() request by request: valid and invalid
// generated cases of every family, each method, each convention.
TYPED_TEST(ApplyBatch, batchGivesWhatApplyGives) {
  using T = TypeParam;
  const auto valid = cases::valid_case<T>();
  const auto invalid = cases::invalid_case<T>();
  rc::Random random(17004);
  for (Convention convention : all_conventions) {
    std::vector<Matrix4<T>> matrices;
    std::vector<Vector4<T>> planes;
    for (int i = 0; i < 600; ++i) {
      const cases::Case<T> c = i % 3 == 2 ? invalid(random.split(), i % 101).value()
                                          : valid(random.split(), i % 101).value();
      matrices.push_back(c.matrix);
      planes.push_back(c.plane);
    }
    long compared = 0, ok = 0;
    for (Method method : all_methods) {
      expect_batch_is_apply(matrices, planes, matrices.size(), convention, method, compared, ok);
      if (::testing::Test::HasFatalFailure()) return;
    }
    EXPECT_GT(ok, 0);
  }
}

/// A mixed pool of requests for the batch's blocks (detail::closed_form_lanes): valid perspective
/// cases whose M43 is -1, 1, another power of two (up to the edges of the range where 1/M43 is
/// normal and just past them) or not a power of two; the generator's invalid inputs; special
/// values in every entry and plane component; planes scaled to the edges of the exponent range;
/// zeros of both signs in the entries outside the shape, in M13, M23, M33 and in the plane.
template <class T>
std::vector<cases::Case<T>> batch_pool(int size, std::uint64_t seed) {
  using limits = std::numeric_limits<T>;
  const auto valid = cases::valid_case_in<T>(
      {std::begin(cases::perspective_shape_families), std::end(cases::perspective_shape_families)},
      cases::every_convention());
  const auto invalid = cases::invalid_case<T>();
  const std::vector<T> specials = test::special_values<T>();
  const T k_values[] = {T(-1),
                        T(1),
                        T(-2),
                        T(0.5),
                        std::ldexp(T(-1), limits::max_exponent - 2),
                        std::ldexp(T(1), limits::max_exponent - 1),
                        std::ldexp(T(-1), limits::min_exponent - 1),
                        std::ldexp(T(1), limits::min_exponent - 2),
                        T(-0.75),
                        T(3)};
  const int exponent_edges[] = {limits::max_exponent - 1, limits::max_exponent - 2,
                                limits::min_exponent - 1, limits::min_exponent - 2,
                                limits::min_exponent - limits::digits};
  rc::Random random(seed);
  std::vector<cases::Case<T>> pool;
  for (int i = 0; i < size; ++i) {
    cases::Case<T> c = valid(random.split(), i % 101).value();
    const int pick = i % 11;
    if (pick == 1) c = invalid(random.split(), i % 101).value();
    if (pick == 2 || pick == 3) {
      const T special = specials[std::size_t(i / 11) % specials.size()];
      const int entry = (i / 3) % 20;
      if (entry < 16) {
        c.matrix(entry / 4, entry % 4) = special;
      } else {
        c.plane(entry - 16) = special;
      }
    }
    if (pick == 4) {
      const int k = exponent_edges[std::size_t(i / 11) % std::size(exponent_edges)];
      const int e = magnitude_exponent(c.plane);
      for (int j = 0; j < 4; ++j) c.plane(j) = std::ldexp(c.plane(j), k - e);
    }
    if (pick == 5) {
      const int which = (i / 11) % 12;
      const T zero = (i / 11) % 2 == 0 ? T(-0.0) : T(0);
      const int outside[][2] = {{0, 1}, {0, 3}, {1, 0}, {1, 3}, {2, 0},
                                {2, 1}, {3, 0}, {3, 1}, {3, 3}};
      if (which < 9) {
        c.matrix(outside[which][0], outside[which][1]) = zero;
      } else {
        c.matrix(which - 9, 2) = zero;  // M13, M23, M33
      }
      c.plane((i / 7) % 3) = zero;
    }
    if (pick == 6 || pick == 7) {
      // M43 set to a power of two or not: the blocks' 1/K.
      const T k = k_values[std::size_t(i / 11) % std::size(k_values)];
      c.matrix(3, 2) = k;
    }
    pool.push_back(c);
  }
  return pool;
}

// apply_batch against apply() request by request on the mixed pool, in each convention and
// method, both forms and in place, for counts around the block size (0, 1, a block less or
// more one, several blocks and a tail), with valid and invalid requests mixed inside blocks;
// and blocks made only of valid requests with one M43, a power of two or not.
TYPED_TEST(ApplyBatch, batchBlocksGiveWhatApplyGives) {
  using T = TypeParam;
  constexpr std::size_t w = std::size_t(detail::closed_form_lane_count<T>);
  std::vector<cases::Case<T>> pool = batch_pool<T>(int(40 * w) + 5, 17005);
  // Runs of the same M43 among ordinary requests: whole blocks on the power-of-two path.
  {
    const auto valid = cases::valid_case<T>();
    rc::Random random(17006);
    for (const T k : {T(-1), T(1), T(4), T(-0.75)}) {
      for (std::size_t i = 0; i < 3 * w; ++i) {
        cases::Case<T> c = valid(random.split(), int(i % 101)).value();
        c.matrix(3, 2) = k;
        pool.push_back(c);
      }
    }
  }
  long compared = 0, ok = 0;
  for (Convention convention : all_conventions) {
    std::vector<Matrix4<T>> matrices;
    std::vector<Vector4<T>> planes;
    for (const cases::Case<T>& c : pool) {
      matrices.push_back(c.matrix);
      planes.push_back(c.plane);
    }
    for (Method method : all_methods) {
      for (const std::size_t n :
           {std::size_t(0), std::size_t(1), w - 1, w, w + 1, 2 * w + 3, matrices.size()}) {
        expect_batch_is_apply(matrices, planes, n, convention, method, compared, ok);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GT(ok, compared / 4);
}

// The blocks' own answers (detail::closed_form_block, where apply_batch uses it): every lane
// the block answers is one apply() answers ok, with the same row 3 and far corner bit for bit;
// and the block answers over three quarters of what apply() answers ok in the pool, extreme as
// it is (so that the test above runs through it).
TYPED_TEST(ApplyBatch, batchBlockLanesAreApplysAnswers) {
  using T = TypeParam;
  if constexpr (detail::closed_form_lanes_available<T>()) {
    constexpr int w = detail::closed_form_lane_count<T>;
    const std::vector<cases::Case<T>> pool =
        batch_pool<T>(std::is_same_v<T, double> ? 40000 : 12000, 17007);
    long lanes_ok = 0, apply_ok = 0;
    for (Convention convention : all_conventions) {
      const detail::ConventionTable<T>& table = detail::convention_table<T>(convention);
      for (std::size_t i = 0; i + std::size_t(w) <= pool.size(); i += std::size_t(w)) {
        Matrix4<T> matrices[w];
        Vector4<T> planes[w];
        for (int k = 0; k < w; ++k) {
          matrices[k] = pool[i + std::size_t(k)].matrix;
          planes[k] = pool[i + std::size_t(k)].plane;
        }
        // The baseline build, and the AVX2 one where there is one and the processor has AVX2.
        for (const bool avx2 : {false, true}) {
          if (avx2 && !detail::closed_form_block_avx2_supported()) continue;
          detail::ClosedFormLanes<T, w> lanes;
          detail::closed_form_block_on<T, w, true>(avx2, matrices, planes, table, lanes);
          for (int k = 0; k < w; ++k) {
            const ObliqueResult<T> one =
                apply<T>(matrices[k], planes[k], convention, Method::closed_form);
            apply_ok += one.ok() && !avx2;
            if (lanes.fast[k] == T(0)) continue;
            lanes_ok += !avx2;
            ASSERT_EQ(one.status, Status::ok)
                << "M =\n"
                << matrices[k] << "\nC = " << planes[k].transpose() << "\n"
                << one.message();
            for (int j = 0; j < 4; ++j) {
              ASSERT_TRUE(same_bits(lanes.row3[j][k], one.projection(2, j)))
                  << j << "\nM =\n"
                  << matrices[k] << "\nC = " << planes[k].transpose();
              ASSERT_TRUE(same_bits(lanes.q[j][k], one.far_corner(j))) << j;
            }
          }
        }
      }
    }
    EXPECT_GT(lanes_ok, apply_ok * 3 / 4);
  } else {
    GTEST_SKIP() << "apply_batch answers this type request by request";
  }
}

}  // namespace
}  // namespace oblique
