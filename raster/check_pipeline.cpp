// The three-part pipeline of checks (check_pipeline.h): frames built and read-backs judged on
// threads of their own, the renderer on the caller's.
#include "oblique/raster/check_pipeline.h"

#include <memory>
#include <string>

namespace oblique::raster {

std::vector<CheckPipeline::Done> CheckPipeline::submit(Job job) {
  const int size = rasterizer_.options().size;
  std::future<PreparedCheck> next = std::async(std::launch::async, [job = std::move(job), size] {
    return prepare_check(job.m, job.c, job.answer, job.convention, job.buffer, size, job.seed,
                         job.precision_bits);
  });
  std::vector<Done> done;
  if (std::optional<Done> finished = advance()) done.push_back(std::move(*finished));
  preparing_.emplace(job.tag, std::move(next));
  return done;
}

std::vector<CheckPipeline::Done> CheckPipeline::drain() {
  std::vector<Done> done;
  if (std::optional<Done> finished = advance()) done.push_back(std::move(*finished));
  if (std::optional<Done> finished = finish_judging()) done.push_back(std::move(*finished));
  return done;
}

std::optional<CheckPipeline::Done> CheckPipeline::advance() {
  if (!preparing_) return std::nullopt;
  const long tag = preparing_->first;
  // Shared with the judging thread, which reads the frame while the next one is rendered here.
  const auto prepared = std::make_shared<const PreparedCheck>(preparing_->second.get());
  preparing_.reset();
  std::future<Result> result;
  double render_seconds = 0;
  Expected<Readback> readback = rasterizer_.render(*prepared, &render_seconds);
  if (!readback) {  // nothing drawn: the Result Rasterizer::check() gives, saying why
    Result r;
    r.why = readback.error();
    std::promise<Result> said;
    said.set_value(std::move(r));
    result = said.get_future();
  } else {
    result =
        std::async(std::launch::async, [prepared, render_seconds, read = std::move(*readback)] {
          return judge_prepared(*prepared, read, render_seconds);
        });
  }
  std::optional<Done> finished = finish_judging();
  judging_ = Judging{tag, std::move(result)};
  return finished;
}

std::optional<CheckPipeline::Done> CheckPipeline::finish_judging() {
  if (!judging_) return std::nullopt;
  Done done{judging_->tag, judging_->result.get()};
  judging_.reset();
  return done;
}

}  // namespace oblique::raster
