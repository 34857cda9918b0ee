// raster_bench: a 1000 x 1000 frame (one million samples) through oblique::raster, in its three
// parts and whole: building the frame, rendering it on llvmpipe, judging the read-back. Reports
// samples a second (items_per_second). The target: a whole pass judged in under 0.5 s on a
// 2-core machine.
#include <benchmark/benchmark.h>

#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/raster/raster.h"

namespace {

using oblique::Convention;
using oblique::DepthBuffer;
using oblique::raster::Rasterizer;

struct Pass {
  Eigen::Matrix4d m = oblique::perspective<double>(1.0, 1.78, 0.1, 500.0, Convention::gl);
  Eigen::Vector4d c = Eigen::Vector4d(0.0, 0.93, 0.37, -1.9);
  Eigen::Matrix4d answer = oblique::apply<double>(m, c, Convention::gl).projection;
};

constexpr int kSize = 1000;

Rasterizer* rasterizer(benchmark::State& state) {
  static const auto opened = Rasterizer::open({oblique::raster::Device::software, kSize});
  if (!opened) {
    state.SkipWithError(opened.error().c_str());
    return nullptr;
  }
  return opened->get();
}

void raster_frame(benchmark::State& state) {
  const Pass p;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        oblique::raster::make_frame(p.m, p.c, p.answer, Convention::gl, kSize, 1));
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}
BENCHMARK(raster_frame)->Unit(benchmark::kMillisecond);

void raster_render(benchmark::State& state) {
  Rasterizer* r = rasterizer(state);
  if (!r) return;
  const Pass p;
  const auto frame = oblique::raster::make_frame(p.m, p.c, p.answer, Convention::gl, kSize, 1);
  for (auto _ : state) {
    auto readback = r->render(frame, p.answer, Convention::gl, DepthBuffer::fixed24);
    benchmark::DoNotOptimize(readback);
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}
BENCHMARK(raster_render)->Unit(benchmark::kMillisecond);

void raster_judge(benchmark::State& state) {
  Rasterizer* r = rasterizer(state);
  if (!r) return;
  const Pass p;
  const auto frame = oblique::raster::make_frame(p.m, p.c, p.answer, Convention::gl, kSize, 1);
  const auto readback = r->render(frame, p.answer, Convention::gl, DepthBuffer::fixed24);
  const auto accepted = oblique::raster::accepted_row3(p.m, p.c, Convention::gl, 53);
  for (auto _ : state) {
    benchmark::DoNotOptimize(oblique::raster::judge_frame(frame, *readback, p.m, p.c, p.answer,
                                                          p.answer, accepted, Convention::gl,
                                                          DepthBuffer::fixed24));
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}
BENCHMARK(raster_judge)->Unit(benchmark::kMillisecond);

// The whole pass, as `oblique check --rasterize` runs it.
void raster_pass(benchmark::State& state) {
  Rasterizer* r = rasterizer(state);
  if (!r) return;
  const Pass p;
  for (auto _ : state) {
    const auto result = r->check(p.m, p.c, p.answer, Convention::gl, DepthBuffer::fixed24, 1);
    if (result.outcome != oblique::raster::Outcome::pass) state.SkipWithError(result.why.c_str());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
}
BENCHMARK(raster_pass)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
