// oblique_bench: nanoseconds per call of each method in each scalar type, on one generated
// workload (the property suite's generators, fixed seed), and a batch throughput figure.
//
//   ./build/release/bench/oblique_bench                       # every benchmark
//   ./build/release/bench/oblique_bench --benchmark_filter=double
//
// Names: oblique/<method>/<scalar> (per call, over 1024 cases in turn) and
// oblique_batch/<method>/<scalar> (1024 calls per iteration, items per second). Two reference
// variants run on the same cases: oblique/listing_5_1 (Lengyel's Listing 5.1 as printed: gl
// only, no checks) and oblique/naive (naive_closed_form below: every convention, no checks).
// oblique_1m/<variant>/<scalar> processes one million matrices (the workload tiled, grouped by
// convention) per iteration, items per second: copy_floor (copying the matrices), naive, and
// closed_form (apply_batch over the whole array, writing matrices and statuses).
// Compare figures as ratios within one run: the machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "oblique/batch.h"
#include "oblique/cases/generators.h"
#include "oblique/cases/seeded_recipes.h"
#include "oblique/oblique.h"

namespace {

using oblique::Convention;
using oblique::Matrix4;
using oblique::Method;
using oblique::Status;
using oblique::Vector4;
using oblique::cases::Case;
using oblique::cases::Family;

/// 1024 valid cases of the perspective-shape families (so every method applies), fixed seed.
template <class T>
const std::vector<Case<T>>& workload() {
  static const std::vector<Case<T>> cases = [] {
    const std::vector<Family> families{Family::perspective, Family::off_axis, Family::infinite,
                                       Family::y_flipped, Family::jittered};
    const auto gen = oblique::cases::valid_case_in<T>(families, oblique::cases::every_convention());
    rc::Random random(20261123);
    std::vector<Case<T>> out;
    for (int i = 0; out.size() < 1024; ++i) {
      const Case<T> c = gen(random.split(), i % 101).value();
      if (oblique::apply<T>(c.matrix, c.plane, c.convention).ok()) out.push_back(c);
    }
    return out;
  }();
  return cases;
}

/// The closed form as an engine writes it, the reference the core's closed form is measured
/// against: every convention, the corner's signs from C' (for the perspective shape
/// sgn C'_x = sgn C_x sgn A, sgn C'_y = sgn C_y sgn D, sgn C'_z = sgn C_w sgn H), Q from the
/// closed form (oblique.h), a = (z_high - z_low) / (C . Q) and M'_3 = s (a C - t M_4) (paper
/// Eq. 20 generalised); no checks, no scaling, no status.
template <class T>
Matrix4<T> naive_closed_form(Matrix4<T> m, const Vector4<T>& c, Convention convention) {
  using oblique::cases::sgn;
  const oblique::DepthRange range = oblique::clip_depth_range(convention);
  const oblique::RowCombination near = oblique::near_rows(convention);
  const T A = m(0, 0), B = m(0, 2), D = m(1, 1), E = m(1, 2), G = m(2, 2), H = m(2, 3), K = m(3, 2);
  const T z = sgn(c.w()) * sgn(H) > T(0) ? T(range.z_high) : T(range.z_low);
  const Vector4<T> q((sgn(c.x()) * sgn(A) - B / K) / A, (sgn(c.y()) * sgn(D) - E / K) / D, T(1) / K,
                     (z - G / K) / H);
  const T a = T(range.z_high - range.z_low) / c.dot(q);
  m.row(2) = (T(near.m3) * (a * c - T(near.m4) * m.row(3).transpose())).transpose();
  return m;
}

template <class T>
void listing_5_1_per_call(benchmark::State& state) {
  const auto& cases = workload<T>();
  std::size_t i = 0;
  for (auto _ : state) {
    const Case<T>& c = cases[i++ % cases.size()];
    auto result = oblique::cases::listing_5_1<T>(c.matrix, c.plane);
    benchmark::DoNotOptimize(result);
  }
}

template <class T>
void naive_per_call(benchmark::State& state) {
  const auto& cases = workload<T>();
  std::size_t i = 0;
  for (auto _ : state) {
    const Case<T>& c = cases[i++ % cases.size()];
    auto result = naive_closed_form<T>(c.matrix, c.plane, c.convention);
    benchmark::DoNotOptimize(result);
  }
}

/// One million requests: the workload tiled, grouped by convention (a batch has one).
template <class T>
struct Million {
  std::vector<Matrix4<T>> matrices;
  std::vector<Vector4<T>> planes;
  std::size_t begin[4] = {};  ///< convention i's requests are [begin[i], begin[i + 1])
  std::vector<Matrix4<T>> out;
  std::vector<Status> statuses;
};

template <class T>
Million<T>& million_requests() {
  static Million<T> requests = [] {
    constexpr std::size_t count = std::size_t(1) << 20;
    const auto& cases = workload<T>();
    Million<T> out;
    out.matrices.reserve(count);
    out.planes.reserve(count);
    for (std::size_t ci = 0; ci < 3; ++ci) {
      out.begin[ci] = out.matrices.size();
      for (std::size_t i = 0; i < count; ++i) {
        const Case<T>& c = cases[i % cases.size()];
        if (c.convention != oblique::all_conventions[ci]) continue;
        out.matrices.push_back(c.matrix);
        out.planes.push_back(c.plane);
      }
    }
    out.begin[3] = out.matrices.size();
    out.out.resize(out.matrices.size());
    out.statuses.resize(out.matrices.size());
    return out;
  }();
  return requests;
}

template <class T>
void million_copy_floor(benchmark::State& state) {
  Million<T>& r = million_requests<T>();
  for (auto _ : state) {
    std::copy(r.matrices.begin(), r.matrices.end(), r.out.begin());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * r.matrices.size()));
}

template <class T>
void million_naive(benchmark::State& state) {
  Million<T>& r = million_requests<T>();
  for (auto _ : state) {
    for (std::size_t ci = 0; ci < 3; ++ci) {
      for (std::size_t i = r.begin[ci]; i < r.begin[ci + 1]; ++i)
        r.out[i] = naive_closed_form<T>(r.matrices[i], r.planes[i], oblique::all_conventions[ci]);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * r.matrices.size()));
}

template <class T>
void million_closed_form(benchmark::State& state) {
  Million<T>& r = million_requests<T>();
  for (auto _ : state) {
    for (std::size_t ci = 0; ci < 3; ++ci) {
      const std::size_t begin = r.begin[ci], count = r.begin[ci + 1] - begin;
      oblique::apply_batch<T>(r.matrices.data() + begin, r.planes.data() + begin, count,
                              oblique::all_conventions[ci], Method::closed_form,
                              r.out.data() + begin, r.statuses.data() + begin);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * r.matrices.size()));
}

template <class T>
void per_call(benchmark::State& state, Method method) {
  const auto& cases = workload<T>();
  std::size_t i = 0;
  for (auto _ : state) {
    const Case<T>& c = cases[i++ % cases.size()];
    auto result = oblique::apply<T>(c.matrix, c.plane, c.convention, method);
    benchmark::DoNotOptimize(result);
  }
}

template <class T>
void batch(benchmark::State& state, Method method) {
  const auto& cases = workload<T>();
  for (auto _ : state) {
    for (const Case<T>& c : cases) {
      auto result = oblique::apply<T>(c.matrix, c.plane, c.convention, method);
      benchmark::DoNotOptimize(result);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * cases.size()));
}

template <class T>
void register_scalar(const char* scalar) {
  workload<T>();  // generated before any timing
  const std::string s(scalar);
  benchmark::RegisterBenchmark(("oblique/listing_5_1/" + s).c_str(), listing_5_1_per_call<T>);
  benchmark::RegisterBenchmark(("oblique/naive/" + s).c_str(), naive_per_call<T>);
  for (Method method : {Method::closed_form, Method::general, Method::accurate}) {
    const std::string name = std::string(oblique::method_name(method)) + "/" + scalar;
    benchmark::RegisterBenchmark(("oblique/" + name).c_str(),
                                 [method](benchmark::State& s) { per_call<T>(s, method); });
    benchmark::RegisterBenchmark(("oblique_batch/" + name).c_str(),
                                 [method](benchmark::State& s) { batch<T>(s, method); });
  }
  benchmark::RegisterBenchmark(("oblique_1m/copy_floor/" + s).c_str(), million_copy_floor<T>);
  benchmark::RegisterBenchmark(("oblique_1m/naive/" + s).c_str(), million_naive<T>);
  benchmark::RegisterBenchmark(("oblique_1m/closed_form/" + s).c_str(), million_closed_form<T>);
}

}  // namespace

int main(int argc, char** argv) {
  register_scalar<float>("float");
  register_scalar<double>("double");
  register_scalar<long double>("long_double");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
