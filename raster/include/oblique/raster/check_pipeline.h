// Checks drawn one after another at the speed of the slowest of their three parts: while the
// renderer draws one answer's frame (on the caller's thread, which holds the GL context), the next
// answer's frame is built on a second thread and the read-back of the one before is judged on a
// third. A run that draws many answers (`oblique verify --rasterize`) feeds it; each result comes
// back tagged, in order, two submissions late (drain() gives the rest).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <future>
#include <optional>
#include <utility>
#include <vector>

#include "oblique/raster/raster.h"

namespace oblique::raster {

class CheckPipeline {
 public:
  /// One answer to check: what Rasterizer::check() takes, and a tag the caller knows it by.
  struct Job {
    Eigen::Matrix4d m, answer;
    Eigen::Vector4d c;
    Convention convention = Convention::gl;
    DepthBuffer buffer = DepthBuffer::fixed24;
    std::uint64_t seed = 1;
    int precision_bits = 53;
    long tag = 0;
  };
  /// A finished check: the same Result as Rasterizer::check() gives for the job.
  using Done = std::pair<long, Result>;

  /// Draws with `rasterizer`, which must outlive the pipeline and be used on this thread only.
  explicit CheckPipeline(Rasterizer& rasterizer) : rasterizer_(rasterizer) {}
  CheckPipeline(const CheckPipeline&) = delete;
  CheckPipeline& operator=(const CheckPipeline&) = delete;
  /// Waits for the work in flight (its results are dropped).
  ~CheckPipeline() = default;

  /// Starts `job`'s frame, draws the job before it and starts its judgement; the checks finished
  /// meanwhile (at most one), in submission order.
  std::vector<Done> submit(Job job);
  /// Every job still in flight, finished, in submission order.
  std::vector<Done> drain();

 private:
  struct Judging {
    long tag = 0;
    std::future<Result> result;
  };
  /// Renders the prepared job (here) and starts its judgement; the judgement before it, finished.
  std::optional<Done> advance();
  std::optional<Done> finish_judging();

  Rasterizer& rasterizer_;
  std::optional<std::pair<long, std::future<PreparedCheck>>> preparing_;
  std::optional<Judging> judging_;
};

}  // namespace oblique::raster
