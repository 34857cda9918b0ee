// checker_bench: the checker's cost per judged answer, exact (Problem + judge(), GMP) against
// filtered (FilteredProblem + judge(), oracle/filtered.h), on the property suite's mix: 1024
// generated cases of every family, convention and hard place (fixed seed), each with the core's
// answer, judged with every property (the suite's checks) or with the core's checks (row 3's
// accuracy and the ulps promise too, as fuzz_oblique judges the core).
//
//   ./build/release/bench/checker_bench
//
// Compare figures as ratios within one run: the machine is shared and noisy.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <vector>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/implementations.h"
#include "oblique/oblique.h"
#include "oblique/oracle/filtered.h"

namespace {

using oblique::Answer;
using oblique::cases::Case;
using oblique::cases::Checks;
using oblique::oracle::FilteredProblem;
using oblique::oracle::Problem;

template <class T>
struct Judged {
  Case<T> c;
  Answer<T> answer;
};

/// 1024 cases of the suite's valid-case generator with the core's answers (ok or not), fixed seed.
template <class T>
const std::vector<Judged<T>>& workload() {
  static const std::vector<Judged<T>> cases = [] {
    const auto gen = oblique::cases::valid_case<T>();
    rc::Random random(20261130);
    std::vector<Judged<T>> out;
    for (int i = 0; out.size() < 1024; ++i) {
      const Case<T> c = gen(random.split(), i % 101).value();
      const auto r = oblique::apply<T>(c.matrix, c.plane, c.convention);
      out.push_back(Judged<T>{c, Answer<T>{r.status, r.projection}});
    }
    return out;
  }();
  return cases;
}

/// What fuzz_oblique asks of the core's auto method: every property, row 3's accuracy and the
/// method's own ulps promise.
template <class T>
Checks core_checks() {
  return oblique::mistakes::known_implementations<T>()[0].checks(true);
}

/// How many of the workload's answers the filter judges alone, and where it gives up on the rest
/// (source lines of filtered.h / certified.h), printed before the timings.
template <class T>
void report_coverage(const char* scalar) {
  int decided = 0;
  std::map<int, int> undecided;
  for (const Judged<T>& j : workload<T>()) {
    const FilteredProblem<T> problem(j.c.matrix, j.c.plane, j.c.convention);
    if (problem.filtered_judgement(j.answer, core_checks<T>()))
      ++decided;
    else
      ++undecided[problem.undecided_at()];
  }
  std::printf(
      "%s: the filter judges %d of %zu answers alone; left to exact arithmetic at (line: count):",
      scalar, decided, workload<T>().size());
  for (const auto& [line, count] : undecided) std::printf(" %d: %d", line, count);
  std::printf("\n");
}

template <class Checker, class T>
void judge_each(benchmark::State& state, const Checks& checks) {
  const auto& cases = workload<T>();
  std::size_t i = 0;
  for (auto _ : state) {
    const Judged<T>& j = cases[i++ % cases.size()];
    const Checker problem(j.c.matrix, j.c.plane, j.c.convention);
    auto judgement = oblique::oracle::judge(problem, j.answer, checks);
    benchmark::DoNotOptimize(judgement);
  }
}

template <class T>
void exact_suite(benchmark::State& state) {
  judge_each<Problem<T>, T>(state, Checks{});
}
template <class T>
void filtered_suite(benchmark::State& state) {
  judge_each<FilteredProblem<T>, T>(state, Checks{});
}
template <class T>
void exact_core(benchmark::State& state) {
  judge_each<Problem<T>, T>(state, core_checks<T>());
}
template <class T>
void filtered_core(benchmark::State& state) {
  judge_each<FilteredProblem<T>, T>(state, core_checks<T>());
}

template <class T>
void register_all(const char* scalar) {
  const std::string s = scalar;
  benchmark::RegisterBenchmark(("checker/exact/properties/" + s).c_str(), exact_suite<T>);
  benchmark::RegisterBenchmark(("checker/filtered/properties/" + s).c_str(), filtered_suite<T>);
  benchmark::RegisterBenchmark(("checker/exact/core_checks/" + s).c_str(), exact_core<T>);
  benchmark::RegisterBenchmark(("checker/filtered/core_checks/" + s).c_str(), filtered_core<T>);
}

}  // namespace

int main(int argc, char** argv) {
  register_all<float>("float");
  register_all<double>("double");
  register_all<long double>("long_double");
  workload<float>();
  workload<double>();
  workload<long double>();
  report_coverage<float>("float");
  report_coverage<double>("double");
  report_coverage<long double>("long double");
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
