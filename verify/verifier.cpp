// `oblique verify`'s run: the options checked, then batches of generated requests sent to the
// implementation and judged while it answers the next (batches.h), each finding confirmed and
// shrunk (shrinker.h) and reported (reporter.h). The rooms: cases.h (the contract into draws, an
// answer read and judged), session.h (the program, one request alone), failure_database.h
// (--replay, --regressions).
#include "oblique/verify/verifier.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <ostream>
#include <random>
#include <thread>

#include "accuracy.h"
#include "batches.h"
#include "cases.h"
#include "consumers.h"
#include "failure_database.h"
#include "oblique/protocol/interrupts.h"
#include "rasterize.h"
#include "reporter.h"
#include "session.h"
#include "shrinker.h"

namespace oblique::verify {

namespace {

/// One run of `oblique verify` in scalar type T.
template <class T>
class Verifier {
 public:
  Verifier(const VerifyOptions& options, const MatrixMode& mode, std::ostream& out,
           std::ostream& err)
      : options_(options),
        mode_(mode),
        err_(err),
        draws_(options.contract),
        session_(options, draws_),
        reporter_(options, mode.save_regressions, draws_, out, err),
        shrinker_(session_, reporter_, out, err),
        database_(session_, reporter_, out, err),
        raster_(options, mode.rasterize.value_or(RasterOptions{}), out, err),
        accuracy_(options, mode.accuracy_dir, out, err) {
    if (mode.keep_going) reporter_.one_report_per_cause();
  }

  /// --replay: re-judges one report's case.
  Verdict replay_report(const std::string& path) {
    const Verdict result = database_.replay(path, /*verbose=*/true);
    session_.program().stop();
    return result;
  }

  Verdict run() {
    if (!mode_.regressions.empty()) {
      const Verdict kept = database_.replay_all(mode_.regressions);
      if (kept != Verdict::holds) return kept;
      session_.start_clock();  // the run's own time limit starts now
    }
    if (mode_.rasterize && !raster_.open()) return Verdict::inconclusive;
    client::Program& program = session_.program();
    const Clock::time_point deadline = session_.deadline();
    const auto idle = session_.idle();
    if (const Expected<Done> started = program.start(); !started) {
      err_ << "oblique verify: cannot start the implementation: " << started.error() << "\n";
      return Verdict::error;
    }
    rc::Random random(options_.seed);
    protocol::handle_interrupts();
    set_interrupted_line(options_, 0, "cases judged", 0);
    long done = 0, generated = 0;
    std::size_t batch = 16;
    auto last_progress = session_.start();
    std::map<std::string, Kind> kinds;
    run::Tally tally;
    bool stopped_by_time = false;
    long dropped = 0;
    // Batch k + 1 is generated and queued before batch k's answers are read, so the
    // implementation works on it while batch k is judged (on --threads threads).
    Batch<T> current = next_batch(random, generated, batch, tally);
    while (!current.cases.empty()) {
      batch = std::min<std::size_t>(batch * 2, 1024);
      Batch<T> following;
      if (generated < case_limit() && Clock::now() < deadline)
        following = next_batch(random, generated, batch, tally);
      const std::size_t n = current.cases.size();
      std::vector<std::string> answers;
      bool restarted = false;  // --keep-going: a fresh process after a finding in this batch
      std::optional<client::Failure> failure = program.read(n, answers, deadline);
      bool time_up = false;
      if (failure && failure->kind() == client::Failure::Kind::timeout &&
          Clock::now() >= deadline) {
        // The time limit ended the wait, not the implementation; it must still show that it is
        // answering: one more line within --timeout of its last one, or the request it owes is
        // a timeout finding (never a pass with an unanswered request).
        time_up = true;
        // From now: the time we spent judging and drawing is not the implementation's.
        failure = program.read(answers.size() + 1, answers, Clock::now() + idle);
      }
      const std::vector<Judged<T>> judged = judge_batch(draws_, current, answers, options_.threads);
      for (std::size_t k = 0; k < answers.size(); ++k) {
        const Judged<T>& j = judged[k];
        if (!j.protocol_error.empty()) {
          program.stop();
          return reporter_.protocol_error(current.requests[k], answers[k], j.protocol_error);
        }
        if (j.finding) {
          Found<T> finding = *j.finding;
          finding.answer_line = answers[k];
          const cases::Case<T>& v = current.values[k];
          const std::string key = std::string(check_name(finding.finding.check)) + " x " +
                                  std::string(cases::family_name(v.family)) + " x " +
                                  cases::case_kind(v);
          if (mode_.keep_going && kinds.count(key)) {
            ++kinds[key].repeats;  // this kind is reported already
            continue;
          }
          set_shrinking_line(options_);
          const Verdict result =
              shrinker_.confirm(current, k, answers, finding, done + static_cast<long>(k) + 1);
          // Drawn once confirmed: an answer out of step with its request is no finding to draw.
          if (mode_.rasterize && result == Verdict::violated && reporter_.last_report_is_new())
            raster_.finding(v, answers[k], reporter_.last_report());
          if (!mode_.keep_going || result != Verdict::violated) return result;
          kinds[key] = Kind{reporter_.last_report(), 1, reporter_.last_cause()};
          if (Clock::now() >= deadline) break;
          // Go on with a fresh process, sent what the old one had queued.
          if (const Expected<Done> started = program.start(); !started) {
            err_ << "oblique verify: cannot restart the implementation: " << started.error()
                 << "\n";
            program.stop();
            return reporter_.index(kinds, done);
          }
          program.queue(following.text());
          restarted = true;
        }
        tally.judged(run::kinds_of(current.values[k]));
        if (!mode_.accuracy_dir.empty() && !judged[k].finding)
          accuracy_.passed(current.values[k], current.requests[k], answers[k]);
        // Drawing stops at the time limit (the answers left are judged, not drawn).
        if (mode_.rasterize && !judged[k].finding && Clock::now() < deadline) {
          const long index = done + static_cast<long>(k) + 1;
          if (const std::optional<Verdict> drawn =
                  raster_.sample(current.values[k], current.requests[k], answers[k], index)) {
            program.stop();
            return *drawn;
          }
        }
      }
      done += static_cast<long>(answers.size());
      if (kinds.empty())
        set_interrupted_line(options_, done, "cases judged", session_.seconds_since_start());
      if (!kinds.empty() && Clock::now() >= deadline) {
        stopped_by_time = true;
        break;
      }
      if (restarted) {
        current = std::move(following);
        continue;
      }
      if (failure && failure->cause == client::Failure::Cause::overlong) {
        const std::string start = program.overlong_start();
        program.stop();
        return reporter_.overlong_line(current.requests[answers.size()], start);
      }
      if (time_up && !failure) {
        dropped = static_cast<long>(n - answers.size());
        stopped_by_time = true;
        break;  // still answering: the time limit ends the run
      }
      if (time_up && failure->kind() == client::Failure::Kind::timeout) {
        set_shrinking_line(options_);
        return shrinker_.shrink(current.cases[answers.size()], session_.lost_finding(*failure),
                                done + 1);
      }
      if (failure) {
        if (done == 0 && failure->cause == client::Failure::Cause::cannot_run) {
          err_ << "oblique verify: cannot run the implementation (" << failure->ended
               << "): " << failure->stderr_tail << "\n";
          program.stop();
          return Verdict::error;
        }
        set_shrinking_line(options_);
        const Verdict result = shrinker_.isolate(current.cases, answers.size(), done, *failure);
        if (result == Verdict::violated && mode_.keep_going && !kinds.empty() &&
            !reporter_.last_report().empty()) {
          kinds[reporter_.last_kind() + " (ends the run)"] =
              Kind{reporter_.last_report(), 1, reporter_.last_cause()};
          program.stop();
          return reporter_.index(kinds, done);
        }
        return result;
      }
      current = std::move(following);
      if (options_.progress &&
          std::chrono::duration<double>(Clock::now() - last_progress).count() >= 2) {
        last_progress = Clock::now();
        err_ << "oblique verify: " << done << " cases, "
             << static_cast<long>(done / session_.seconds_since_start())
             << " per second, no violation\n";
      }
    }
    if (!stopped_by_time && program.running()) {
      // The count check of the last batch: once its input is closed, the implementation has
      // nothing more to say (program.finish(): a second at most to say it).
      const std::vector<std::string> extra = program.finish();
      if (!extra.empty()) {
        return reporter_.count_error(
            "the implementation wrote lines beyond one answer per request (" +
                std::to_string(done) + " requests, all answered)",
            {}, extra);
      }
    }
    program.stop();
    // The last answer drawn: its frame was being built while the run went on.
    if (mode_.rasterize)
      if (const std::optional<Verdict> drawn = raster_.drain()) return *drawn;
    if (!kinds.empty()) return reporter_.index(kinds, done);
    if (done == 0) {
      err_ << "oblique verify: no case was judged within the time limit ("
           << options_.time_limit_seconds << " s); nothing is verified\n";
      return Verdict::error;
    }
    // A pass means judged: every family and convention the contract claims had a case judged.
    if (const std::vector<std::string> unjudged =
            run::unjudged(tally, run::claims_of(draws_.contract()), done, matrix_advice());
        !unjudged.empty()) {
      for (const std::string& line : unjudged) err_ << "oblique verify: " << line << "\n";
      err_ << "oblique verify: no violation in " << done
           << " cases, but not all the contract claims was judged; not a pass\n";
      return Verdict::error;
    }
    const Verdict verdict =
        reporter_.passed(done, session_.seconds_since_start(), tally, stopped_by_time, dropped);
    if (verdict != Verdict::holds) return verdict;
    if (mode_.rasterize) raster_.summary();
    if (!mode_.accuracy_dir.empty() && verdict == Verdict::holds && !accuracy_.write())
      return Verdict::error;
    return verdict;
  }

 private:
  long case_limit() const {
    return options_.cases > 0 ? options_.cases : std::numeric_limits<long>::max();
  }

  /// The next batch (at most `size`, within --cases), sent to the implementation at once.
  Batch<T> next_batch(rc::Random& random, long& generated, std::size_t size, run::Tally& tally) {
    const std::size_t n =
        std::min<std::size_t>(size, static_cast<std::size_t>(case_limit() - generated));
    Batch<T> b = draw_batch(draws_, random, n, tally);
    generated += static_cast<long>(b.cases.size());
    session_.program().queue(b.text());
    return b;
  }

  const VerifyOptions& options_;
  const MatrixMode mode_;
  std::ostream& err_;
  Draws<T> draws_;
  Session<T> session_;
  Reporter<T> reporter_;
  Shrinker<T> shrinker_;
  FailureDatabase<T> database_;
  RasterLook<T> raster_;
  AccuracyLook<T> accuracy_;
};

}  // namespace

namespace {

constexpr double kMaxSeconds = 1e8;

/// Empty when reports can be written into `directory` (created if missing), else why not.
/// A directory that does not exist yet is created to try it, and removed again (reports create
/// it when they are written).
std::string check_report_directory(const std::string& directory) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<fs::path> created;  // the levels that did not exist, deepest first
  for (fs::path p = fs::absolute(directory, ec); !p.empty() && !fs::exists(p, ec);
       p = p.parent_path()) {
    created.push_back(p);
    if (p == p.parent_path()) break;
  }
  struct Tidy {
    std::vector<fs::path>& levels;
    ~Tidy() {
      std::error_code ignored;
      for (const fs::path& p : levels) fs::remove(p, ignored);  // empty directories only
    }
  } tidy{created};
  const std::string probe =
      (fs::path(directory) / (".oblique-verify-probe-" + std::to_string(::getpid()))).string();
  // A run beside this one probing the same new directory removes it when it is done: one that
  // vanishes between being made and being written to is made again (a few times), never called
  // "not a directory".
  constexpr int kTries = 8;
  int fd = -1;
  for (int attempt = 1;; ++attempt) {
    fs::create_directories(directory, ec);
    // A parent removed beside us while it was being made: the same race, one level up.
    if (ec && ec == std::errc::no_such_file_or_directory && attempt < kTries) continue;
    if (ec) return "cannot be created (" + ec.message() + ")";
    const bool is_directory = fs::is_directory(directory, ec);
    if (is_directory) fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    const bool vanished = !is_directory ? !fs::exists(directory, ec) : fd < 0 && errno == ENOENT;
    if (fd >= 0 || !vanished || attempt == kTries) {
      if (!is_directory && !vanished) return "is not a directory";
      break;
    }
  }
  if (fd < 0) return std::string("cannot be written (") + std::strerror(errno) + ")";
  const bool written = ::write(fd, "x", 1) == 1;
  ::close(fd);
  ::unlink(probe.c_str());
  if (!written) return "cannot be written";
  return "";
}

/// --replay: the report's own mode and scalar type, whatever the command line says.
Verdict replay(const VerifyOptions& given, const ReplayMode& mode, std::ostream& out,
               std::ostream& err) {
  VerifyOptions options = given;
  if (const Expected<protocol::JsonValue> report = read_report(mode.report); report) {
    if (report_is(*report, "consumers"))
      return replay_consumer_report(options, mode, *report, out, err);
    if (report_is(*report, "raster")) return replay_raster_report(options, mode, *report, out, err);
  }
  const Expected<std::optional<protocol::Precision>> precision = report_precision(mode.report);
  if (!precision) {
    err << "oblique verify: --replay: cannot read the report " << mode.report << " ("
        << precision.error() << ")\n";
    return Verdict::error;
  }
  if (*precision) options.precision = **precision;
  switch (options.precision) {
    case protocol::Precision::float32:
      return Verifier<float>(options, MatrixMode{}, out, err).replay_report(mode.report);
    case protocol::Precision::float64:
      return Verifier<double>(options, MatrixMode{}, out, err).replay_report(mode.report);
    case protocol::Precision::long_double: break;
  }
  err << "oblique verify: --replay: a long_double report\n";
  return Verdict::error;
}

Verdict verify_matrices(const VerifyOptions& options, const MatrixMode& mode, std::ostream& out,
                        std::ostream& err) {
  if (mode.rasterize &&
      !(mode.rasterize->every >= 1 && mode.rasterize->size >= 16 && mode.rasterize->size <= 4096)) {
    err << "oblique verify: --raster-every must be at least 1 and --raster-size within [16, "
           "4096]\n";
    return Verdict::error;
  }
  if (std::string why = mode.accuracy_dir.empty() ? "" : check_report_directory(mode.accuracy_dir);
      !why.empty()) {
    err << "oblique verify: --accuracy " << mode.accuracy_dir << ": " << why << "\n";
    return Verdict::error;
  }
  switch (options.precision) {
    case protocol::Precision::float32: return Verifier<float>(options, mode, out, err).run();
    case protocol::Precision::float64: return Verifier<double>(options, mode, out, err).run();
    case protocol::Precision::long_double: break;
  }
  err << "oblique verify: --precision is float or double\n";
  return Verdict::error;
}

}  // namespace

int default_threads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

Verdict run_verify(const VerifyOptions& given, const Mode& mode, std::ostream& out,
                   std::ostream& err) {
  ::signal(SIGPIPE, SIG_IGN);  // a child that exits must not take us with it
  VerifyOptions options = given;
  if (!options.shader.empty()) {
    const bool consumers =
        std::holds_alternative<ConsumerMode>(mode) || std::holds_alternative<ReplayMode>(mode);
    if (!consumers) {
      err << "oblique verify: --shader runs depth functions: it needs --consumers view_position, "
             "linear_depth (or --replay of a consumer report)\n";
      return Verdict::error;
    }
    if (!options.command.empty() && options.command != options.shader) {
      err << "oblique verify: --shader and --impl each name what answers: give one\n";
      return Verdict::error;
    }
    options.command = options.shader;  // the name reports give it
  }
  if (options.command.empty()) {
    err << "oblique verify: --impl needs a command (or --shader FILE[:FUNCTION] for depth "
           "functions in GLSL or HLSL)\n";
    return Verdict::error;
  }
  // Range checks: durations must fit the clock's arithmetic (and NaN is no duration).
  if (!(options.time_limit_seconds > 0 && options.time_limit_seconds <= kMaxSeconds)) {
    err << "oblique verify: --time-limit must be more than 0 and at most " << kMaxSeconds
        << " seconds (about 3 years), not " << options.time_limit_seconds << "\n";
    return Verdict::error;
  }
  if (!(options.request_timeout_seconds >= 0.001 &&
        options.request_timeout_seconds <= kMaxSeconds)) {
    err << "oblique verify: --timeout must be at least 0.001 and at most " << kMaxSeconds
        << " seconds, not " << options.request_timeout_seconds << "\n";
    return Verdict::error;
  }
  if (options.cases < 0) {
    err << "oblique verify: --cases must be positive\n";
    return Verdict::error;
  }
  if (!(options.threads >= 1 && options.threads <= 256)) {
    err << "oblique verify: --threads must be between 1 and 256, not " << options.threads << "\n";
    return Verdict::error;
  }
  if (options.seed == 0) options.seed = std::random_device{}() | 1u;
  if (const auto* replayed = std::get_if<ReplayMode>(&mode))
    return replay(options, *replayed, out, err);
  // The report directory is checked before the run: a finding must not be lost after shrinking.
  if (std::string why = check_report_directory(options.report_dir); !why.empty()) {
    err << "oblique verify: --report-dir " << options.report_dir << ": " << why << "\n";
    return Verdict::error;
  }
  if (const auto* consumers = std::get_if<ConsumerMode>(&mode))
    return verify_consumers(options, *consumers, out, err);
  return verify_matrices(options, std::get<MatrixMode>(mode), out, err);
}

}  // namespace oblique::verify
