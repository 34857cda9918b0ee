#include "rasterize.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <ostream>
#include <sstream>
#include <utility>

#include "failure_database.h"
#include "oblique/client/program.h"
#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/protocol/numbers.h"
#include "oblique/protocol/protocol.h"
#include "oblique/raster/raster_report.h"
#include "oblique/report/report_files.h"
#include "reporter.h"

namespace oblique::verify {

namespace {

raster::Options raster_options(const RasterOptions& options) {
  raster::Options out;
  out.device = options.device == "gpu" ? raster::Device::gpu : raster::Device::software;
  out.size = options.size;
  return out;
}

}  // namespace

template <class T>
RasterLook<T>::RasterLook(const VerifyOptions& options, RasterOptions raster, std::ostream& out,
                          std::ostream& err)
    : options_(options), raster_(std::move(raster)), out_(out), err_(err) {}

template <class T>
bool RasterLook<T>::open() {
  const auto opened = raster::Rasterizer::open(raster_options(raster_));
  if (!opened) {
    err_ << "oblique verify: raster: inconclusive: " << opened.error() << "\n";
    return false;
  }
  rasterizer_ = *opened;
  return true;
}

template <class T>
std::optional<raster::Result> RasterLook<T>::draw(const cases::Case<T>& v,
                                                  const std::string& answer, std::uint64_t seed,
                                                  std::string* why) {
  auto not_drawn = [why](std::string reason) {
    if (why) *why = std::move(reason);
    return std::nullopt;
  };
  const Expected<Answer<T>> read = protocol::read_answer<T>(answer);
  if (!read || read->status != Status::ok) return not_drawn("the answer holds no matrix");
  raster::Result r =
      rasterizer_->check(v.matrix.template cast<double>(), v.plane.template cast<double>(),
                         read->projection.template cast<double>(), v.convention, raster_.buffer,
                         seed, std::numeric_limits<T>::digits);
  if (!tally(r)) return not_drawn(r.why);
  return r;
}

template <class T>
bool RasterLook<T>::tally(const raster::Result& r) {
  if (!r.rendered) {
    ++not_drawn_;
    return false;
  }
  ++drawn_;
  worst_depth_ratio_ = std::max(worst_depth_ratio_, r.worst_depth_ratio);
  return true;
}

template <class T>
std::optional<Verdict> RasterLook<T>::sample(const cases::Case<T>& v, const std::string& request,
                                             const std::string& answer, long index) {
  if (index != 1 && index % raster_.every != 0) return std::nullopt;
  const Expected<Answer<T>> read = protocol::read_answer<T>(answer);
  if (!read || read->status != Status::ok) return std::nullopt;  // no matrix to draw
  if (!pipeline_) pipeline_ = std::make_unique<raster::CheckPipeline>(*rasterizer_);
  in_flight_[index] = Drawn{v, request, answer};
  raster::CheckPipeline::Job job;
  job.m = v.matrix.template cast<double>();
  job.c = v.plane.template cast<double>();
  job.answer = read->projection.template cast<double>();
  job.convention = v.convention;
  job.buffer = raster_.buffer;
  job.seed = options_.seed ^ static_cast<std::uint64_t>(index);
  job.precision_bits = std::numeric_limits<T>::digits;
  job.tag = index;
  return settle(pipeline_->submit(std::move(job)));
}

template <class T>
std::optional<Verdict> RasterLook<T>::drain() {
  if (!pipeline_) return std::nullopt;
  return settle(pipeline_->drain());
}

template <class T>
std::optional<Verdict> RasterLook<T>::settle(std::vector<raster::CheckPipeline::Done> done) {
  for (auto& [index, r] : done) {
    const auto found = in_flight_.find(index);
    if (found == in_flight_.end()) continue;
    const Drawn drawn = std::move(found->second);
    in_flight_.erase(found);
    if (!tally(r) || r.outcome == raster::Outcome::pass) continue;
    if (r.outcome == raster::Outcome::inconclusive) {
      err_ << "oblique verify: raster: inconclusive at answer " << index << ": " << r.why
           << "\n  request: " << drawn.request << "\n  the run again: " << rerun_command(options_)
           << "\n";
      return Verdict::inconclusive;
    }
    return report(drawn.v, drawn.request, drawn.answer, r, index);
  }
  return std::nullopt;
}

template <class T>
void RasterLook<T>::finding(const cases::Case<T>& v, const std::string& answer,
                            const std::string& report_md) {
  std::string why;
  const std::optional<raster::Result> r = draw(v, answer, options_.seed, &why);
  if (!r) {
    err_ << "oblique verify: raster: the finding's answer is not drawn: " << why << "\n";
    return;
  }
  const std::string verdict = r->outcome == raster::Outcome::pass   ? "passes (" + r->why + ")"
                              : r->outcome == raster::Outcome::fail ? "FAIL, " + r->why
                                                                    : "inconclusive: " + r->why;
  const std::string said =
      "oblique verify: raster: the finding's answer on the rasterizer: " + verdict;
  // Beside the finding's report: STEM.raster.md with the pixels (only when STEM.md was written).
  namespace fs = std::filesystem;
  if (fs::path(report_md).extension() != ".md") {
    err_ << said << "\n";
    return;
  }
  const fs::path md_path(report_md);
  const std::string stem = md_path.stem().string() + ".raster";
  report::ReportFiles files(md_path.parent_path());
  std::string md = "# The finding's answer on the rasterizer\n\nThe answer of [" +
                   md_path.filename().string() + "](" + md_path.filename().string() +
                   "), drawn on " + rasterizer_->renderer() + " in a " +
                   std::to_string(raster_.size) + " x " + std::to_string(raster_.size) +
                   " frame (depth buffer " + std::string(depth_buffer_name(raster_.buffer)) +
                   ", frame seed " + std::to_string(options_.seed) + "): **" + verdict + "**.\n\n";
  if (r->outcome == raster::Outcome::fail)
    md += raster::stage_flagged_section(files, stem, *r, raster_.size);
  files.open(stem + ".md") << md;
  std::ostringstream log;
  if (files.commit(log))
    err_ << said << " (" << (md_path.parent_path() / (stem + ".md")).string() << ")\n";
  else
    err_ << said << "\noblique verify: raster: " << stem << ".md not written: " << log.str();
}

template <class T>
void RasterLook<T>::summary() const {
  char line[160];
  std::snprintf(line, sizeof line,
                "%ld answers drawn %d x %d, none failed; worst depth %.3g of its bound", drawn_,
                raster_.size, raster_.size, worst_depth_ratio_);
  out_ << "raster: " << rasterizer_->renderer() << ": " << line;
  if (not_drawn_ > 0)
    out_ << "; " << not_drawn_
         << " not drawn (the core has no answer to judge against, or the answer is beyond "
            "float32)";
  out_ << "\n";
}

template <class T>
Verdict RasterLook<T>::report(const cases::Case<T>& v, const std::string& request,
                              const std::string& answer, const raster::Result& r, long index) {
  report::ReportFiles files(options_.report_dir);
  const std::string stem = files.reserve_stem("verify-raster", {".md", ".json"});
  const std::string json_path =
      (std::filesystem::path(options_.report_dir) / (stem + ".json")).string();
  std::string md =
      "# Counterexample: the rasterizer\n\n`" + options_.command +
      "`'s answer passes the properties, but drawn on " + rasterizer_->renderer() +
      " it fails: " + r.why +
      ".\n\n## The case\n\n- family: " + std::string(cases::family_name(v.family)) + ", place " +
      cases::case_kind(v) + "\n- convention: " + std::string(convention_name(v.convention)) +
      ", depth buffer " + std::string(depth_buffer_name(raster_.buffer)) +
      "\n- M: " + oracle::numbers_text(v.matrix) + "\n- C: " + oracle::numbers_text(v.plane) +
      "\n\nAnswer " + std::to_string(index) + " of the run. The request:\n\n```\n" + request +
      "\n```\n\nThe answer:\n\n```\n" + answer + "\n```\n\n";
  const Expected<Answer<double>> answered = protocol::read_answer<double>(answer);
  if (answered && answered->status == Status::ok)
    md += raster::stage_raster_finding(
        files, stem, r, raster_.size, v.matrix.template cast<double>(),
        v.plane.template cast<double>(), answered->projection, v.convention);
  else
    md += raster::stage_flagged_section(files, stem, r, raster_.size);
  md += "\n## Replay\n\n```sh\n# the whole run\n" + rerun_command(options_) +
        "\n# this request again, its answer drawn (exit 0 holds, 1 fails, 3 inconclusive)\n" +
        options_.self + " verify --replay " + shell_quote(json_path) + " " + impl_flags(options_) +
        "\n# the one request\necho " +
        shell_quote(protocol::in_matrix_order(request, options_.matrix_order())) + " | " +
        options_.command + "\n```\n";
  files.open(stem + ".md") << md;
  files.open(stem + ".json")
      << "{\"type\": \"raster\", \"finding\": " << protocol::json_string(r.why)
      << ", \"precision\": " << protocol::json_string(protocol::scalar_name<T>())
      << ", \"convention\": " << protocol::json_string(convention_name(v.convention))
      << ", \"buffer\": \"" << std::string(depth_buffer_name(raster_.buffer))
      << "\", \"size\": " << raster_.size
      << ", \"seed\": " << (options_.seed ^ static_cast<std::uint64_t>(index))
      << ", \"projection\": " << hex_list(v.matrix) << ", \"plane\": " << hex_list(v.plane)
      << ", \"request\": " << protocol::json_string(request)
      << ", \"answer\": " << protocol::json_string(answer) << "}\n";
  err_ << "oblique verify: raster: answer " << index << " passes the properties but fails on "
       << rasterizer_->renderer() << ": " << r.why << "\n";
  return commit_report(files, stem, err_);
}

template class RasterLook<float>;
template class RasterLook<double>;

Verdict replay_raster_report(const VerifyOptions& options, const ReplayMode& mode,
                             const protocol::JsonValue& report, std::ostream& out,
                             std::ostream& err) {
  auto fail = [&](const std::string& why) {
    err << "oblique verify: --replay " << mode.report << ": " << why << "\n";
    return Verdict::error;
  };
  const protocol::JsonValue* request = report.find("request");
  const protocol::JsonValue* convention = report.find("convention");
  const protocol::JsonValue* buffer = report.find("buffer");
  const protocol::JsonValue* size = report.find("size");
  const protocol::JsonValue* seed = report.find("seed");
  if (!request || !request->is_string()) return fail("\"request\" must be a string");
  const std::optional<Convention> parsed =
      convention && convention->is_string() ? parse_convention(convention->text) : std::nullopt;
  if (!parsed) return fail("\"convention\" is not a convention");
  std::vector<double> m, c;
  std::string error;
  if (!report_numbers<double>(report, "projection", 16, m, error) ||
      !report_numbers<double>(report, "plane", 4, c, error))
    return fail(error);
  // A report without "buffer" was drawn into the default fixed24 buffer; one that names a buffer
  // must name a known one.
  const std::optional<DepthBuffer> drawn_into =
      !buffer               ? std::optional<DepthBuffer>(DepthBuffer::fixed24)
      : buffer->is_string() ? parse_depth_buffer(buffer->text)
                            : std::nullopt;
  if (!drawn_into) return fail("\"buffer\" is not a depth buffer (fixed24 or float32)");
  RasterOptions frame;
  frame.device = mode.raster_device;
  frame.buffer = *drawn_into;
  if (size) {
    char* end = nullptr;
    const long n = size->is_number() ? std::strtol(size->text.c_str(), &end, 10) : 0;
    if (!(end && *end == '\0' && n >= 16 && n <= 4096))
      return fail("\"size\" must be a whole number of pixels within [16, 4096]");
    frame.size = static_cast<int>(n);
  }
  const std::uint64_t frame_seed =
      seed && seed->is_number() ? std::strtoull(seed->text.c_str(), nullptr, 10) : 1;
  cases::Case<double> v;
  for (int i = 0; i < 16; ++i) v.matrix(i / 4, i % 4) = m[static_cast<std::size_t>(i)];
  for (int i = 0; i < 4; ++i) v.plane(i) = c[static_cast<std::size_t>(i)];
  v.convention = *parsed;
  const auto timeout =
      std::chrono::milliseconds(static_cast<long>(options.request_timeout_seconds * 1000));
  client::Program program(options.command, timeout, options.matrix_order());
  const client::Reply reply = program.ask(request->text);
  program.stop();
  if (reply.failure) {
    using Cause = client::Failure::Cause;
    const client::Failure& f = *reply.failure;
    if (f.cause == Cause::cannot_start)
      return fail("cannot start the implementation (" + f.what + ")");
    if (f.cause == Cause::overlong) return fail("an answer line longer than 1 MiB (not read)");
    if (f.cause == Cause::timed_out)
      return fail("no answer within " + std::to_string(timeout.count()) + " ms");
    if (f.cause != Cause::beyond)
      return fail("the implementation ended before answering (" + f.ended + ")");
  }
  const std::vector<std::string>& lines = reply.lines;
  RasterLook<double> look(options, frame, out, err);
  if (!look.open()) return Verdict::inconclusive;
  std::string why;
  const std::optional<raster::Result> r = look.draw(v, lines.front(), frame_seed, &why);
  if (!r) return fail(why + ": " + lines.front());
  out << "oblique verify: raster: " << raster::outcome_name(r->outcome) << ": " << r->why
      << "\n  answer: " << lines.front() << "\n";
  return r->outcome == raster::Outcome::pass   ? Verdict::holds
         : r->outcome == raster::Outcome::fail ? Verdict::violated
                                               : Verdict::inconclusive;
}

}  // namespace oblique::verify
