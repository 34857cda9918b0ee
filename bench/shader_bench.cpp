// shader_bench: a user's depth function on the GPU path (oblique::shader, llvmpipe), in parts
// and whole: the dispatch alone (requests answered a second) and answered and judged, the way
// `oblique verify --shader` plans rounds (64 pixels of each oblique matrix, rounds of the
// default contract, every convention). Reports requests a second (items_per_second, real
// time); the target (issue 47) is 100,000 judged a second on this 2-core machine. Judged on 1
// and on 2 threads, as verify's --threads divide it.
#include <benchmark/benchmark.h>

#include <atomic>
#include <random>
#include <thread>

#include "oblique/cases/generators.h"
#include "oblique/oracle/consumers.h"
#include "oblique/shader/shader_runner.h"

namespace {

using oblique::Consumers;
using oblique::protocol::ConsumerKind;

constexpr int kRounds = 8192;
constexpr int kRoundsPerCase = 64;

oblique::shader::ShaderRunner* runner(benchmark::State& state) {
  static const auto opened =
      oblique::shader::ShaderRunner::open({{std::string(OBLIQUE_SHADERS) + "/depth_right.glsl",
                                            "view_position",
                                            oblique::shader::Language::glsl,
                                            ConsumerKind::view_position,
                                            {}}});
  if (!opened) {
    state.SkipWithError(opened.error().c_str());
    return nullptr;
  }
  return opened->get();
}

/// kRounds view_position asks of the default contract in every convention, each case asked
/// kRoundsPerCase times (other pixels).
const std::vector<oblique::oracle::ConsumerAsk<float>>& asks() {
  static const std::vector<oblique::oracle::ConsumerAsk<float>> planned = [] {
    const oblique::Contract contract =
        oblique::resolved(oblique::Contract{}, oblique::cases::every_convention(),
                          oblique::cases::StatusContract::any_refusal, true);
    const auto cases = oblique::cases::valid_case_for<float>(contract);
    rc::Random random(20261206);
    std::mt19937_64 engine(7);
    Consumers<float> asking;
    asking.view_position = [](const oblique::oracle::DepthSample<float>&) {
      return oblique::Vector3<float>::Zero().eval();
    };
    std::vector<oblique::oracle::ConsumerAsk<float>> out;
    oblique::cases::Case<float> c;
    for (int i = 0; i < kRounds; ++i) {
      if (i % kRoundsPerCase == 0) c = cases(random.split(), i / kRoundsPerCase % 101).value();
      const oblique::oracle::Pick pick = [&](int lo, int hi) {
        return std::uniform_int_distribution<int>(lo, hi - 1)(engine);
      };
      for (auto& a : oblique::oracle::consumer_asks<float>(
               c.matrix, c.plane, c.convention, asking, pick,
               [](const oblique::oracle::ConsumerFinding&, const std::string&, bool) {}))
        out.push_back(std::move(a));
    }
    return out;
  }();
  return planned;
}

std::vector<const oblique::oracle::ConsumerAsk<float>*> pointers() {
  std::vector<const oblique::oracle::ConsumerAsk<float>*> out;
  for (const auto& a : asks()) out.push_back(&a);
  return out;
}

void shader_dispatch(benchmark::State& state) {
  auto* r = runner(state);
  if (!r) return;
  const auto batch = pointers();
  for (auto _ : state) benchmark::DoNotOptimize(oblique::shader::answer_asks(*r, batch));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(batch.size()));
}
BENCHMARK(shader_dispatch)->Unit(benchmark::kMillisecond);

/// The batch answered, then judged on `threads` threads (verify's --threads), each a slice.
void shader_judged(benchmark::State& state) {
  auto* r = runner(state);
  if (!r) return;
  const auto batch = pointers();
  const auto threads = static_cast<std::size_t>(state.range(0));
  std::atomic<long> judged{0};
  for (auto _ : state) {
    const auto answers = oblique::shader::answer_asks(*r, batch);
    if (!answers) {
      state.SkipWithError(answers.error().c_str());
      return;
    }
    auto slice = [&](std::size_t from, std::size_t to) {
      long mine = 0;
      for (std::size_t i = from; i < to; ++i)
        oblique::oracle::judge_explained<float>(
            *batch[i], (*answers)[i],
            [&mine](const oblique::oracle::ConsumerFinding& f, const std::string&, bool) {
              mine += f.judged ? 1 : 0;
            },
            {});
      judged += mine;
    };
    std::vector<std::thread> workers;
    const std::size_t step = (batch.size() + threads - 1) / threads;
    for (std::size_t from = 0; from < batch.size(); from += step)
      workers.emplace_back(slice, from, std::min(batch.size(), from + step));
    for (auto& w : workers) w.join();
  }
  state.SetItemsProcessed(judged);
}
BENCHMARK(shader_judged)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
