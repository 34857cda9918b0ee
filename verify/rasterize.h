// oblique verify --rasterize: a sample of the answers (one in --raster-every, and the first) and
// every finding's answer drawn on a real rasterizer (oblique::raster). An answer that passes the
// properties but fails on the rasterizer is a finding of its own kind, reported with its pixels;
// --replay of that report asks the program again and draws its answer. Internal to
// oblique::verify.
#pragma once

#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "cases.h"
#include "oblique/protocol/json.h"
#include "oblique/raster/check_pipeline.h"
#include "oblique/raster/raster.h"
#include "oblique/verify/verifier.h"

namespace oblique::verify {

template <class T>
class RasterLook {
 public:
  RasterLook(const VerifyOptions& options, RasterOptions raster, std::ostream& out,
             std::ostream& err);

  /// Opens the rasterizer (its self-checks included); false, said on err, when it cannot judge.
  bool open();

  /// The answer line to case `v` (sent as `request`), the `index`-th answer of the run from 1:
  /// drawn when its turn comes, in a raster::CheckPipeline (its frame built and the answer before
  /// it judged on other threads), so the verdict returned is an earlier answer's: a failure on
  /// the rasterizer is reported (Verdict::violated), a tripped self-check ends the run
  /// (Verdict::inconclusive); otherwise nullopt. drain() gives the last ones'.
  std::optional<Verdict> sample(const cases::Case<T>& v, const std::string& request,
                                const std::string& answer, long index);
  /// The answers still in the pipeline (sample()), drawn and judged: the first verdict that ends
  /// the run.
  std::optional<Verdict> drain();

  /// A finding's answer drawn too; one line on err says what the rasterizer made of it, and
  /// when it was drawn, STEM.raster.md beside the finding's report `report_md` (STEM.md) holds
  /// the verdict and the flagged pixels' picture.
  void finding(const cases::Case<T>& v, const std::string& answer, const std::string& report_md);

  /// One line for a run's end: answers drawn, all passed, the renderer, the worst depth error.
  void summary() const;

  /// The answer line to case `v` drawn (frame seed `seed`); nullopt where it holds no matrix, the
  /// case has no answer to judge against, or the frame could not be drawn (`why` says which).
  std::optional<raster::Result> draw(const cases::Case<T>& v, const std::string& answer,
                                     std::uint64_t seed, std::string* why = nullptr);

 private:
  Verdict report(const cases::Case<T>& v, const std::string& request, const std::string& answer,
                 const raster::Result& result, long index);

  /// The answers whose turn came, drawn in the pipeline, by tag (their index).
  struct Drawn {
    cases::Case<T> v;
    std::string request, answer;
  };
  /// The verdict of finished checks, as sample()'s: the first that ends the run.
  std::optional<Verdict> settle(std::vector<raster::CheckPipeline::Done> done);
  /// The run's tally of one result: false where nothing was rendered.
  bool tally(const raster::Result& r);

  const VerifyOptions& options_;
  const RasterOptions raster_;
  std::ostream& out_;
  std::ostream& err_;
  std::shared_ptr<raster::Rasterizer> rasterizer_;
  long drawn_ = 0, not_drawn_ = 0;
  double worst_depth_ratio_ = 0;
  std::unique_ptr<raster::CheckPipeline> pipeline_;
  std::map<long, Drawn> in_flight_;
};

/// --replay of a raster finding's report: the request sent again, the answer drawn. Exit 0 holds,
/// 1 fails again, 3 inconclusive, 2 when the report or the program cannot be read.
Verdict replay_raster_report(const VerifyOptions& options, const ReplayMode& mode,
                             const protocol::JsonValue& report, std::ostream& out,
                             std::ostream& err);

}  // namespace oblique::verify
