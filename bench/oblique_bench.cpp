// oblique_bench: nanoseconds per call of each method in each scalar type, on one generated
// workload (the property suite's generators, fixed seed), and a batch throughput figure.
//
//   ./build/release/bench/oblique_bench                       # every benchmark
//   ./build/release/bench/oblique_bench --benchmark_filter=double
//
// Names: oblique/<method>/<scalar> (per call, over 1024 cases in turn) and
// oblique_batch/<method>/<scalar> (1024 calls per iteration, items per second).
// Compare figures as ratios within one run: the machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/properties/generators.h"

namespace {

using oblique::Convention;
using oblique::Method;
using oblique::generators::Case;
using oblique::generators::Family;

/// 1024 valid cases of the perspective-shape families (so every method applies), fixed seed.
template <class T>
const std::vector<Case<T>>& workload() {
  static const std::vector<Case<T>> cases = [] {
    const std::vector<Family> families{Family::perspective, Family::off_axis, Family::infinite,
                                       Family::y_flipped, Family::jittered};
    const auto gen =
        oblique::generators::valid_case_in<T>(families, oblique::generators::every_convention());
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
  for (Method method : {Method::closed_form, Method::general, Method::accurate}) {
    const std::string name = std::string(oblique::method_name(method)) + "/" + scalar;
    benchmark::RegisterBenchmark(("oblique/" + name).c_str(),
                                 [method](benchmark::State& s) { per_call<T>(s, method); });
    benchmark::RegisterBenchmark(("oblique_batch/" + name).c_str(),
                                 [method](benchmark::State& s) { batch<T>(s, method); });
  }
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
