#include "consumers.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <random>
#include <set>
#include <sstream>
#include <type_traits>

#include "batches.h"
#include "failure_database.h"
#include "oblique/cases/generators.h"
#include "oblique/client/consumer_program.h"
#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oblique.h"
#include "oblique/oracle/consumer_wire.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/names.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/report/counterexample_report.h"
#include "oblique/report/report_files.h"
#include "oblique/run/tally.h"
#include "oblique/shader/shader_runner.h"
#include "reporter.h"

namespace oblique::verify {

namespace {

using client::ConsumerProgram;
using client::Failure;
using protocol::ConsumerKind;
using protocol::shell_quote;

/// What a round is made of, all a report needs to replay it: the case (M, C, convention) and
/// the picks the round made, in order.
template <class T>
struct Round {
  cases::Case<T> c;
  std::vector<int> picks;
};

/// The first violation of a run, with its evidence.
template <class T>
struct Caught {
  oracle::ConsumerFinding finding;
  std::string inputs, request, answer;
  bool about_oblique_case = false;
  Round<T> round;
  long index = 0;               ///< of the round, from 0
  std::optional<Failure> lost;  ///< a crash or a timeout instead of a finding
};

/// A consumer finding's kinds: its property and the family of the round's case.
std::vector<run::Kind> finding_kinds(oracle::ConsumerCheck check, cases::Family family) {
  return {{"property", std::string(oracle::consumer_check_name(check))},
          {"family", std::string(cases::family_name(family))}};
}

/// What answers a run's requests: a program over the protocol (ConsumerProgram), or a shader on
/// the GPU path. Both give a Consumers for one-at-a-time rounds (replay, shrinking) and answer a
/// batch of asks; a request without an answer to judge throws (or returns) a Failure.
template <class T>
class Answerer {
 public:
  using Batch = typename ConsumerProgram<T>::Batch;
  virtual ~Answerer() = default;
  virtual Consumers<T> consumers(const std::vector<ConsumerKind>& kinds,
                                 const std::string& name) = 0;
  virtual Batch answer(const std::vector<const oracle::ConsumerAsk<T>*>& asks) = 0;
  virtual const std::string& last_request() const = 0;
  virtual const std::string& last_answer() const = 0;
  virtual void stop() {}
  /// The lines beyond one answer per request (a program's count check); none for a shader.
  virtual std::vector<std::string> finish() { return {}; }
  virtual long answered() const = 0;
};

template <class T>
class ProgramAnswerer final : public Answerer<T> {
 public:
  using typename Answerer<T>::Batch;
  ProgramAnswerer(const std::string& command, std::chrono::milliseconds timeout,
                  protocol::MatrixOrder order)
      : program_(command, timeout, order) {}
  Consumers<T> consumers(const std::vector<ConsumerKind>& kinds, const std::string& name) override {
    return program_.consumers(kinds, name);
  }
  Batch answer(const std::vector<const oracle::ConsumerAsk<T>*>& asks) override {
    return program_.answer(asks);
  }
  const std::string& last_request() const override { return program_.last_request(); }
  const std::string& last_answer() const override { return program_.last_answer(); }
  void stop() override { program_.stop(); }
  std::vector<std::string> finish() override { return program_.finish(); }
  long answered() const override { return program_.answered(); }

 private:
  ConsumerProgram<T> program_;
};

/// A shader's answer as the protocol's answer line would carry it.
template <class T>
std::string shader_answer_line(ConsumerKind kind, const std::vector<T>& numbers) {
  std::string line = "{\"" + std::string(protocol::consumer_answer_field(kind)) + "\": ";
  if (kind == ConsumerKind::linear_depth) return line + protocol::json_number(numbers.at(0)) + "}";
  line += "[";
  for (std::size_t i = 0; i < numbers.size(); ++i)
    line += (i ? ", " : "") + protocol::json_number(numbers[i]);
  return line + "]}";
}

/// --shader: the user's GLSL or HLSL function on the GPU path (oblique/shader). Its exchanges are
/// shown as the protocol's request and answer lines, so reports read alike.
class ShaderAnswerer final : public Answerer<float> {
 public:
  ShaderAnswerer(std::unique_ptr<shader::ShaderRunner> runner, oracle::Sampling sampling)
      : runner_(std::move(runner)), sampling_(sampling) {}
  Consumers<float> consumers(const std::vector<ConsumerKind>&, const std::string& name) override {
    Consumers<float> c = shader::shader_consumers(*runner_, name, sampling_);
    if (c.view_position) c.view_position = recorded(c.view_position, ConsumerKind::view_position);
    if (c.linear_depth) c.linear_depth = recorded(c.linear_depth, ConsumerKind::linear_depth);
    if (c.world_position)
      c.world_position = recorded(c.world_position, ConsumerKind::world_position);
    return c;
  }
  Batch answer(const std::vector<const oracle::ConsumerAsk<float>*>& asks) override {
    Batch out;
    Expected<std::vector<std::vector<float>>> answers = shader::answer_asks(*runner_, asks);
    if (!answers) {
      Failure f;
      f.cause = Failure::Cause::not_an_answer;
      f.what = "the shader could not be run: " + answers.error();
      f.request = asks.empty() ? "" : asks.back()->request().line();
      out.failure = f;
      return out;
    }
    // The request and answer lines are made where a violation needs them (play_batch()).
    out.numbers = std::move(*answers);
    answered_ += static_cast<long>(asks.size());
    return out;
  }
  const std::string& last_request() const override { return last_request_; }
  const std::string& last_answer() const override { return last_answer_; }
  long answered() const override { return answered_; }

 private:
  template <class F>
  F recorded(F inner, ConsumerKind kind) {
    return [this, inner, kind](const oracle::DepthSample<float>& s) {
      last_request_ = oracle::wire::depth_request(kind, s).line();
      try {
        const auto answer = inner(s);
        last_answer_ = shader_answer_line(kind, numbers(answer));
        ++answered_;
        return answer;
      } catch (const std::runtime_error& e) {
        Failure f;
        f.cause = Failure::Cause::not_an_answer;
        f.what = std::string("the shader could not be run: ") + e.what();
        f.request = last_request_;
        throw f;
      }
    };
  }
  static std::vector<float> numbers(float x) { return {x}; }
  static std::vector<float> numbers(const Vector3<float>& v) { return {v.x(), v.y(), v.z()}; }
  std::unique_ptr<shader::ShaderRunner> runner_;
  oracle::Sampling sampling_;
  std::string last_request_, last_answer_;
  long answered_ = 0;
};

/// How the replay commands name what answers: --impl COMMAND, or --shader SPEC (and its
/// language where given).
std::string answerer_flags(const VerifyOptions& options) {
  if (options.shader.empty()) return impl_flags(options);
  std::string flags = "--shader " + shell_quote(options.shader);
  if (options.shader_language)
    flags += " --shader-language " + std::string(shader::language_name(*options.shader_language));
  if (options.shader_device != "software") flags += " --device " + options.shader_device;
  for (const std::string& d : options.shader_defines) flags += " --define " + shell_quote(d);
  if (options.shader_v)
    flags += " --uv-v " + std::string(shader::v_direction_name(*options.shader_v));
  if (options.shader_vectors != shader::Vectors::column)
    flags += " --vectors " + std::string(shader::vectors_name(options.shader_vectors));
  return flags;
}

/// The run's answerer: the program, or with --shader the shader's functions (float only); none,
/// said on `err`, where the shader cannot be run.
template <class T>
std::unique_ptr<Answerer<T>> answerer_for(const VerifyOptions& options,
                                          const std::vector<ConsumerKind>& kinds,
                                          std::ostream& err) {
  if (options.shader.empty())
    return std::make_unique<ProgramAnswerer<T>>(
        options.command,
        std::chrono::milliseconds(static_cast<long>(options.request_timeout_seconds * 1000)),
        options.matrix_order());
  if constexpr (std::is_same_v<T, float>) {
    auto functions = shader::shader_functions(options.shader, kinds, options.shader_language);
    if (!functions) {
      err << "oblique verify: --shader " << options.shader << ": " << functions.error() << "\n";
      return nullptr;
    }
    for (shader::ShaderFunction& f : *functions) {
      f.defines = options.shader_defines;
      if (options.shader_v) f.v = *options.shader_v;
      f.vectors = options.shader_vectors;
    }
    shader::RunnerOptions run;
    run.device = options.shader_device == "gpu" ? raster::Device::gpu : raster::Device::software;
    run.timeout_seconds = options.request_timeout_seconds;
    auto runner = shader::ShaderRunner::open(*functions, run);
    if (!runner) {
      err << "oblique verify: " << runner.error() << "\n";  // it names the file
      return nullptr;
    }
    if (options.progress)
      err << "oblique verify: the shader runs on " << (*runner)->renderer() << "\n";
    return std::make_unique<ShaderAnswerer>(std::move(*runner), options.sampling);
  } else {
    err << "oblique verify: a shader computes in float: --shader runs with --precision float\n";
    return nullptr;
  }
}

template <class T>
class ConsumerRun {
 public:
  ConsumerRun(const VerifyOptions& options, const ConsumerMode& mode,
              std::unique_ptr<Answerer<T>> answerer, std::ostream& out, std::ostream& err)
      : options_(options),
        kinds_(mode.kinds),
        out_(out),
        err_(err),
        program_(std::move(answerer)),
        asked_(program_->consumers(kinds_, options.command)) {
    asked_.mirror_design = mode.mirror_design;
    if (options.shader.empty()) asked_.sampling = options.sampling;  // a shader's has its own
  }

  /// A round's choices from `picks`, in order from `next`, each clamped to its range (a report
  /// may have been edited; a shrunk pick may be below its range), the low end once they run out;
  /// each as taken appended to `taken`.
  static oracle::Pick recorded_picks(const std::vector<int>& picks, std::size_t& next,
                                     std::vector<int>& taken) {
    return [&picks, &next, &taken](int lo, int hi) {
      const int v = next < picks.size() ? picks[next++] : lo;
      taken.push_back(v < lo ? lo : v >= hi ? hi - 1 : v);
      return taken.back();
    };
  }

  /// --replay's round: the program asked each kind on `round`, its picks replayed from
  /// round.picks. Returns false for a protocol error (said on err_).
  bool play(const Round<T>& round) {
    std::size_t next = 0;
    std::vector<int> taken;
    const oracle::Pick pick = recorded_picks(round.picks, next, taken);
    const oracle::Settle settle = [&](const oracle::ConsumerFinding& f, const std::string& inputs,
                                      bool about) {
      tally(f, round, 0, inputs, about, program_->last_request(), program_->last_answer());
    };
    try {
      oracle::consumer_round<T>(round.c.matrix, round.c.plane, round.c.convention, asked_, pick,
                                settle, mistakes::explain_consumer<T>);
    } catch (const Failure& failure) {
      return lost(failure, round, 0);
    }
    return true;
  }

  /// The caught round asked again with `picks` (clamped as a report's are): its first violation
  /// of `check` whose likely cause is `cause` (any, where `cause` is empty), with the exchange
  /// and the picks as the round took them; none where it holds, or the program failed.
  std::optional<Caught<T>> violation_with(const Round<T>& round, const std::vector<int>& picks,
                                          oracle::ConsumerCheck check, const std::string& cause) {
    Round<T> taken{round.c, {}};
    std::size_t next = 0;
    const oracle::Pick pick = recorded_picks(picks, next, taken.picks);
    std::optional<Caught<T>> found;
    const oracle::Settle settle = [&](const oracle::ConsumerFinding& f, const std::string& inputs,
                                      bool about) {
      if (found || !f.judged || f.holds || f.check != check) return;
      if (!cause.empty() && f.likely_cause != cause) return;
      found =
          Caught<T>{f, inputs,      program_->last_request(), program_->last_answer(), about, round,
                    0, std::nullopt};
    };
    try {
      oracle::consumer_round<T>(round.c.matrix, round.c.plane, round.c.convention, asked_, pick,
                                settle, mistakes::explain_consumer<T>);
    } catch (const Failure& failure) {
      shrink_stopped_ = failure.what;  // a crash, a timeout or a protocol error: no more rounds
      return std::nullopt;
    }
    if (found) found->round = taken;
    return found;
  }

  /// Shrinks the caught round's picks (the choices a round makes: which pixel, pass, sample):
  /// each pick in turn tried at its range's low end, at half and one less, kept where the round
  /// still violates the same check with the same likely cause (a shrunk case where the answer
  /// comes within half of the digits of the right one, or another mistake's, would name none or
  /// another: what the finding was is kept); the program is asked again each time (at most
  /// kShrinkTries rounds and kShrinkSeconds; none after a crash or a timeout). Said on err_, and
  /// the report has the shrunk round.
  void shrink() {
    if (!caught_ || caught_->lost) return;
    set_shrinking_line(options_);
    // Said first (and flushed): an interrupted shrink still leaves the finding on the terminal.
    (err_ << "oblique verify: " << oracle::consumer_check_name(caught_->finding.check)
          << " violated in round " << caught_->index + 1
          << "; shrinking its picks\n  request (before shrinking): " << caught_->request
          << "\n  answer (before shrinking): " << caught_->answer << "\n")
        .flush();
    constexpr int kShrinkTries = 300;
    constexpr auto kShrinkSeconds = std::chrono::seconds(10);
    const auto deadline = std::chrono::steady_clock::now() + kShrinkSeconds;
    auto more = [&](int tries) {
      return tries < kShrinkTries && !shrink_stopped_ &&
             std::chrono::steady_clock::now() < deadline;
    };
    Caught<T> best = *caught_;
    int tries = 0, steps = 0;
    for (bool progress = true; progress && more(tries);) {
      progress = false;
      for (std::size_t i = 0; i < best.round.picks.size() && !progress && more(tries); ++i) {
        const int v = best.round.picks[i];
        for (const int candidate : {0, v / 2, v - 1}) {
          if (candidate >= v || !more(tries)) continue;
          std::vector<int> picks = best.round.picks;
          picks[i] = candidate;
          ++tries;
          if (std::optional<Caught<T>> c = violation_with(best.round, picks, best.finding.check,
                                                          caught_->finding.likely_cause);
              c && c->round.picks < best.round.picks) {
            c->index = best.index;
            best = *c;
            ++steps;
            progress = true;
            break;
          }
        }
      }
    }
    caught_ = best;
    shrink_steps_ = steps;
    shrink_tries_ = tries;
    if (tries > 0)
      err_ << "oblique verify: shrank the round's picks: " << steps << " steps (" << tries
           << " tries" << (shrink_stopped_ ? "; stopped: " + *shrink_stopped_ : std::string())
           << ")\n  request (shrunk, as the report has it): " << caught_->request
           << "\n  answer (shrunk): " << caught_->answer << "\n";
  }

  /// A request that got no answer to judge: a protocol error is said on err_ (false); a crash or
  /// a timeout is the run's finding unless one came before.
  bool lost(const Failure& failure, const Round<T>& round, long index) {
    if (failure.kind() == Failure::Kind::protocol) {
      err_ << "oblique verify: protocol error: " << failure.what
           << "\n  request: " << failure.request << "\n";
      for (const std::string& line : failure.lines)
        err_ << "  read: " << protocol::escape_bytes(line) << "\n";
      return false;
    }
    if (!caught_) {
      caught_ = Caught<T>{};
      caught_->lost = failure;
      caught_->request = failure.request;
      caught_->index = index;
      caught_->round = round;
    }
    return true;
  }

  /// One finding of round `index` counted, and kept as the run's violation when it is the first.
  void tally(const oracle::ConsumerFinding& f, const Round<T>& round, long index,
             const std::string& inputs, bool about, const std::string& request,
             const std::string& answer) {
    const std::string check(oracle::consumer_check_name(f.check));
    asked_checks_.insert(f.check);
    const std::vector<run::Kind> kinds = finding_kinds(f.check, round.c.family);
    if (const std::string_view why = oracle::not_applicable(f.check, round.c.family);
        !f.judged && !why.empty()) {
      // Nothing to judge on this family (corners of an infinite frustum, ...): said once in
      // the summary, not counted as left out. (A judged answer on it is settled as any.)
      tally_.not_applicable(kinds, check + " on " +
                                       std::string(cases::family_name(round.c.family)) + " (" +
                                       std::string(why) + ")");
      return;
    }
    if (!f.judged && f.unjudged == oracle::ConsumerFinding::Unjudged::not_applicable) {
      // The same on one matrix of a family it applies to (an infinite matrix of x_flipped); the
      // property stays claimed, so one never judged on any matrix is no pass.
      tally_.not_applicable(kinds, check + " (" + f.detail + ")");
      return;
    }
    if (!f.judged) {
      // Said among the reasons; counted against the property only where the contract claims
      // the case (an input without an answer is claimed by no consumer contract).
      tally_.left_out(kinds, f.detail, f.unjudged == oracle::ConsumerFinding::Unjudged::undecided);
      return;
    }
    tally_.judged(kinds);
    if (f.holds || caught_) return;
    caught_ = Caught<T>{f, inputs, request, answer, about, round, index, std::nullopt};
  }

  /// A finding of a planned round, waiting for the round's turn to be counted: `ask` is the
  /// batch's request it judges (npos: left out before asking).
  struct Pending {
    oracle::ConsumerFinding finding;
    std::string inputs;
    bool about = false;
    std::size_t ask = static_cast<std::size_t>(-1);
  };
  struct Planned {
    Round<T> round;
    std::vector<oracle::ConsumerAsk<T>> asks;
    std::size_t first_ask = 0;  ///< its first request's place in the batch
    std::vector<Pending> pending;
  };

  /// The rounds index, index + 1, ... planned: cases drawn, picks drawn and recorded. The cases
  /// are drawn in order on this thread (RapidCheck's generation is not thread-safe); each round's
  /// picks come from its own engine, seeded by its index, so the rounds are planned on --threads
  /// threads and are the same whatever the threads.
  std::vector<Planned> plan(const rc::Gen<cases::Case<T>>& cases, rc::Random& random, long index,
                            long count) {
    std::vector<Planned> out(static_cast<std::size_t>(count));
    for (long k = 0; k < count; ++k) {
      const long i = index + k;
      // A shader's run asks kRoundsPerCase rounds of each case drawn (other pixels, other
      // picks): the GPU takes thousands at once, and the judges analyse each matrix once.
      const long rounds_per_case = options_.shader.empty() ? 1 : kShaderRoundsPerCase;
      if (i % rounds_per_case == 0 || !last_case_)
        last_case_ = cases(random.split(), static_cast<int>(i / rounds_per_case % 101)).value();
      out[static_cast<std::size_t>(k)].round.c = *last_case_;
    }
    in_slices(
        out.size(), options_.threads,
        [&](std::size_t from, std::size_t to) {
          for (std::size_t k = from; k < to; ++k) {
            Planned& p = out[k];
            const long i = index + static_cast<long>(k);
            std::mt19937_64 engine(options_.seed * 0x9E3779B97F4A7C15ull +
                                   static_cast<std::uint64_t>(i));
            const oracle::Pick pick = [&](int lo, int hi) {
              const int v = std::uniform_int_distribution<int>(lo, hi - 1)(engine);
              p.round.picks.push_back(v);
              return v;
            };
            const oracle::Settle left_out = [&p](const oracle::ConsumerFinding& f,
                                                 const std::string& inputs, bool about) {
              p.pending.push_back(Pending{f, inputs, about});
            };
            p.asks = oracle::consumer_asks<T>(p.round.c.matrix, p.round.c.plane,
                                              p.round.c.convention, asked_, pick, left_out);
          }
        },
        16);
    return out;
  }

  /// A batch of rounds: every request sent at once, the answers judged on --threads threads,
  /// then counted round by round in order up to the first violation, crash, timeout or protocol
  /// error. Returns false for a protocol error (said on err_); `settled` is how many rounds were.
  bool play_batch(std::vector<Planned>& batch, long index, long& settled) {
    std::vector<const oracle::ConsumerAsk<T>*> asks;
    for (Planned& p : batch) {
      p.first_ask = asks.size();
      for (const auto& a : p.asks) asks.push_back(&a);
    }
    const typename Answerer<T>::Batch answers = program_->answer(asks);
    // A program's lines as it read and wrote them; a shader's made from its numbers.
    auto request_line = [&](std::size_t k) {
      return k < answers.requests.size() ? answers.requests[k] : asks[k]->request().line();
    };
    auto answer_line = [&](std::size_t k) {
      return k < answers.lines.size() ? answers.lines[k]
                                      : shader_answer_line(asks[k]->kind, answers.numbers[k]);
    };
    in_slices(
        batch.size(), options_.threads,
        [&](std::size_t from, std::size_t to) {
          for (std::size_t r = from; r < to; ++r) {
            Planned& p = batch[r];
            for (std::size_t j = 0; j < p.asks.size(); ++j) {
              const std::size_t g = p.first_ask + j;
              if (g >= answers.numbers.size()) break;
              oracle::judge_explained<T>(
                  p.asks[j], answers.numbers[g],
                  [&p, g](const oracle::ConsumerFinding& f, const std::string& inputs, bool about) {
                    p.pending.push_back(Pending{f, inputs, about, g});
                  },
                  mistakes::explain_consumer<T>);
            }
          }
        },
        1);
    settled = 0;
    for (std::size_t r = 0; r < batch.size(); ++r) {
      const Planned& p = batch[r];
      const long i = index + static_cast<long>(r);
      for (const Pending& f : p.pending) {
        // The exchange is kept only with a violation: a shader's batch writes its lines then.
        const bool asked = f.ask < answers.numbers.size();
        const bool kept = asked && f.finding.judged && !f.finding.holds;
        tally(f.finding, p.round, i, f.inputs, f.about, kept ? request_line(f.ask) : "",
              kept ? answer_line(f.ask) : "");
      }
      ++settled;
      if (caught_) return true;
      if (answers.failure && p.first_ask + p.asks.size() > answers.numbers.size())
        return lost(*answers.failure, p.round, i);
    }
    return true;
  }

  Verdict run() {
    const Contract contract =
        resolved(options_.contract, {Convention::gl}, cases::StatusContract::any_refusal, true);
    const rc::Gen<cases::Case<T>> cases = cases::valid_case_for<T>(contract);
    rc::Random random(options_.seed);
    const auto start = std::chrono::steady_clock::now();
    const auto deadline =
        start + std::chrono::milliseconds(static_cast<long>(options_.time_limit_seconds * 1000));
    auto last_progress = start;
    protocol::handle_interrupts();
    set_interrupted_line(options_, 0, "answers judged", 0);
    long index = 0;
    std::map<std::string, long> conventions, families;
    // Batches grow from one round (a first violation or crash is met at once) to kMaxBatch
    // (a GPU dispatch takes thousands at once).
    const long kMaxBatch = options_.shader.empty() ? 64 : 4096;
    long batch_size = 1;
    while (std::chrono::steady_clock::now() < deadline &&
           (options_.cases == 0 || index < options_.cases)) {
      const long count =
          options_.cases == 0 ? batch_size : std::min(batch_size, options_.cases - index);
      batch_size = std::min(kMaxBatch, batch_size * 2);
      std::vector<Planned> batch = plan(cases, random, index, count);
      long settled = 0;
      if (!play_batch(batch, index, settled)) {
        program_->stop();
        return Verdict::error;
      }
      for (long r = 0; r < settled; ++r) {
        const Round<T>& round = batch[static_cast<std::size_t>(r)].round;
        ++conventions[std::string(convention_name(round.c.convention))];
        ++families[std::string(cases::family_name(round.c.family))];
      }
      index += settled;
      if (caught_) break;
      const auto now = std::chrono::steady_clock::now();
      set_interrupted_line(options_, tally_.judged(), "answers judged",
                           std::chrono::duration<double>(now - start).count());
      if (options_.progress && now - last_progress > std::chrono::seconds(5)) {
        last_progress = now;
        err_ << "oblique verify: " << index << " rounds, " << tally_.judged() << " answers judged, "
             << static_cast<long>(std::chrono::duration<double>(now - start).count()) << " s\n";
      }
    }
    if (!counted()) return Verdict::error;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (caught_) {
      shrink();
      return report(seconds);
    }
    if (tally_.judged() == 0) {
      err_ << "oblique verify: no answer was judged in " << index
           << " rounds (left out: " << run::counts_text(tally_.reasons())
           << (tally_.not_applicable_reasons().empty()
                   ? ""
                   : "; not applicable: " + run::counts_text(tally_.not_applicable_reasons()))
           << "): nothing was verified\n";
      return Verdict::error;
    }
    // A pass means judged: every property asked and every family the contract claims had an
    // answer judged, where the property applies to a claimed family.
    auto applies = [](oracle::ConsumerCheck c, cases::Family f) {
      return oracle::not_applicable(c, f).empty();
    };
    std::vector<run::Kind> properties;
    for (const oracle::ConsumerCheck c : asked_checks_) {
      if (std::any_of(contract.families.begin(), contract.families.end(),
                      [&](cases::Family f) { return applies(c, f); }))
        properties.push_back({"property", std::string(oracle::consumer_check_name(c))});
    }
    std::vector<run::Kind> claims = properties;
    for (const cases::Family f : contract.families) {
      if (std::any_of(asked_checks_.begin(), asked_checks_.end(),
                      [&](oracle::ConsumerCheck c) { return applies(c, f); }))
        claims.push_back({"family", std::string(cases::family_name(f))});
    }
    run::Advice advice;
    advice.claimant = "the run claims";
    advice.unit = "answer";
    advice.rounds = "rounds";
    advice.leave_out = [](const run::Kind& k) {
      return k.axis == "family" ? "leave " + k.name + " out of --families"
                                : std::string("narrow --families to cases it has");
    };
    if (const std::vector<std::string> unjudged = run::unjudged(tally_, claims, index, advice);
        !unjudged.empty()) {
      for (const std::string& u : unjudged) err_ << "oblique verify: " << u << "\n";
      err_ << "oblique verify: no violation in " << tally_.judged()
           << " answers judged, but not all that was claimed was judged; not a pass\n";
      return Verdict::error;
    }
    std::ostringstream line;
    line.precision(3);
    line << std::fixed << seconds;
    out_ << "oblique verify: no violation in " << tally_.judged() << " answers judged, " << index
         << " rounds of " << kind_list() << " (" << protocol::scalar_name<T>() << ", seed "
         << options_.seed << ", " << line.str()
         << " s)\n  judged: " << run::counts_text(tally_.by("property"))
         << "\n  conventions: " << run::counts_text(conventions)
         << "\n  families: " << run::counts_text(families)
         << "\n  left out: " << run::counts_text(tally_.reasons()) << "\n";
    if (!tally_.not_applicable_reasons().empty())
      out_ << "  not applicable (rounds): " << run::counts_text(tally_.not_applicable_reasons())
           << "\n";
    // Judged in part only: a property with more than the warning share of its samples left out.
    if (const std::string partly =
            run::partly_judged(tally_, properties, run::kLeftOutWarning, /*with_axis=*/false);
        !partly.empty()) {
      out_ << run::partly_judged_warning(partly, options_.strict);
      if (options_.strict) return Verdict::error;
    }
    return Verdict::holds;
  }

  /// --replay: the report's round again; prints every violation.
  Verdict replay(const Round<T>& round, const std::string& report_path) {
    if (!play(round)) {
      program_->stop();
      return Verdict::error;
    }
    if (!counted()) return Verdict::error;
    if (!caught_ && tally_.judged() == 0) {
      // An edited report, or a case the program is never asked about: no verdict at all.
      err_ << "oblique verify: --replay " << report_path
           << ": the round judged nothing (left out: " << run::counts_text(tally_.reasons())
           << "); nothing is verified\n";
      return Verdict::error;
    }
    if (!caught_) {
      out_ << "oblique verify: the round holds (" << run::counts_text(tally_.by("property"))
           << " judged; left out: " << run::counts_text(tally_.reasons()) << ")\n";
      return Verdict::holds;
    }
    if (caught_->lost) {
      out_ << "oblique verify: " << caught_->lost->what << "\n  request: " << caught_->request
           << "\n";
    } else {
      out_ << "oblique verify: violated: " << oracle::describe(caught_->finding)
           << "\n  request: " << caught_->request << "\n  answer: " << caught_->answer << "\n";
    }
    return Verdict::violated;
  }

 private:
  /// The count check at the end (ConsumerProgram::finish()): a program that wrote lines beyond
  /// one answer per request had its answers judged against other requests, so neither a pass nor
  /// a violation stands; says so on err_ and returns false.
  bool counted() {
    const std::vector<std::string> extra = program_->finish();
    if (extra.empty()) return true;
    err_
        << "oblique verify: protocol error: the program wrote lines beyond one answer per request ("
        << program_->answered() << " answer lines read before)";
    if (caught_ && !caught_->lost)
      err_ << "; the answers were out of step with the requests, so the "
           << oracle::consumer_check_name(caught_->finding.check)
           << " violation judged on one of them is not reported";
    err_ << "\n";
    for (std::size_t i = 0; i < extra.size() && i < 5; ++i)
      err_ << "  read: " << protocol::escape_bytes(extra[i]) << "\n";
    return false;
  }

  std::string kind_list() const {
    std::string out;
    for (const ConsumerKind k : kinds_)
      out += (out.empty() ? "" : ", ") + std::string(protocol::consumer_kind_name(k));
    return out;
  }

  /// The report's JSON: everything the replay needs, M and C in exact hex.
  std::string report_json(const std::string& check) const {
    const Caught<T>& c = *caught_;
    std::string picks = "[";
    for (std::size_t i = 0; i < c.round.picks.size(); ++i)
      picks += (i ? ", " : "") + std::to_string(c.round.picks[i]);
    picks += "]";
    std::string kinds = "[";
    for (std::size_t i = 0; i < kinds_.size(); ++i)
      kinds += (i ? ", " : "") + protocol::json_string(protocol::consumer_kind_name(kinds_[i]));
    kinds += "]";
    const Matrix4<T> m = c.round.c.matrix;
    const Eigen::Matrix<T, 1, 4> plane = c.round.c.plane.transpose();
    return "{\"type\": \"consumers\", \"check\": " + protocol::json_string(check) +
           ", \"finding\": " +
           protocol::json_string(c.lost ? c.lost->what : oracle::describe(c.finding)) +
           ", \"precision\": " + protocol::json_string(protocol::scalar_name<T>()) +
           ", \"kinds\": " + kinds +
           ", \"convention\": " + protocol::json_string(convention_name(c.round.c.convention)) +
           ", \"family\": " + protocol::json_string(cases::family_name(c.round.c.family)) +
           ", \"projection\": " + hex_list(m) + ", \"plane\": " + hex_list(plane) +
           ", \"picks\": " + picks + ", \"mirror_design\": " +
           protocol::json_string(oracle::mirror_design_name(asked_.mirror_design)) +
           ", \"request\": " + protocol::json_string(c.request) +
           ", \"answer\": " + protocol::json_string(c.answer) +
           (options_.shader.empty() ? std::string()
                                    : ", \"shader\": " + protocol::json_string(options_.shader)) +
           ", \"seed\": " + std::to_string(options_.seed) +
           ", \"round\": " + std::to_string(c.index) + "}\n";
  }

  Verdict report(double seconds) {
    set_reporting_line(options_);
    const Caught<T>& c = *caught_;
    const std::string check = c.lost
                                  ? (c.lost->kind() == Failure::Kind::crash ? "crash" : "timeout")
                                  : std::string(oracle::consumer_check_name(c.finding.check));
    report::ReportFiles files(options_.report_dir);
    const std::string stem = files.reserve_stem("verify-consumer-" + check, {".md", ".json"});
    const std::string json_path =
        (std::filesystem::path(options_.report_dir) / (stem + ".json")).string();
    std::string md;
    if (c.lost) {
      md = "# Counterexample: " + check + "\n\n`" + options_.command + "`: " + c.lost->what +
           ".\n\n";
    } else {
      md = report::consumer_report_markdown(options_.command, c.finding, c.inputs) + "\n";
    }
    char elapsed[32];
    std::snprintf(elapsed, sizeof elapsed, "%.3f", seconds);
    md += "## The exchange\n\nRound " + std::to_string(c.index + 1) + " (" +
          std::string(protocol::scalar_name<T>()) + ", seed " + std::to_string(options_.seed) +
          "), after " + elapsed + " s" +
          (c.lost              ? std::string()
           : shrink_tries_ > 0 ? ", its picks shrunk in " + std::to_string(shrink_steps_) +
                                     " steps (" + std::to_string(shrink_tries_) + " rounds asked)"
                               : std::string(", its picks already at their smallest")) +
          ". The request:\n\n```\n" + c.request + "\n```\n\nThe answer:\n\n```\n" +
          (c.answer.empty() ? "(none)" : c.answer) + "\n```\n\n";
    if (!c.lost && !c.about_oblique_case)
      md += report::stage_drawn_pictures(files, stem, c.finding, options_.command);
    if (!c.lost && c.about_oblique_case)
      md += report::stage_consumer_pictures<T>(files, stem, c.round.c.matrix, c.round.c.plane,
                                               c.round.c.convention, c.finding, options_.command);
    md += "## Replay\n\n```sh\n# the whole run\n" + rerun_command(options_) +
          "\n# this round again, judged (exit 0 holds, 1 violated)\n" + options_.self +
          " verify --replay " + shell_quote(json_path) + " " + answerer_flags(options_) +
          (options_.shader.empty()
               ? "\n# the one request\necho " +
                     shell_quote(protocol::in_matrix_order(c.request, options_.matrix_order())) +
                     " | " + options_.command
               : std::string()) +
          "\n```\n";
    files.open(stem + ".md") << md;
    files.open(stem + ".json") << report_json(check);
    err_ << "oblique verify: "
         << (c.lost ? c.lost->what : "violated: " + oracle::describe(c.finding)) << "\n";
    return commit_report(files, stem, err_);
  }

  const VerifyOptions& options_;
  int shrink_steps_ = 0, shrink_tries_ = 0;
  /// Why shrinking stopped early: a shrink round's crash, timeout or protocol error.
  std::optional<std::string> shrink_stopped_;
  std::vector<ConsumerKind> kinds_;
  std::ostream& out_;
  std::ostream& err_;
  std::unique_ptr<Answerer<T>> program_;
  Consumers<T> asked_;
  /// Judged, left out and not applicable, by property and family.
  run::Tally tally_;
  std::set<oracle::ConsumerCheck> asked_checks_;
  std::optional<Caught<T>> caught_;
  /// The case the last planned round asked (a shader's run asks several rounds of each).
  std::optional<cases::Case<T>> last_case_;
  static constexpr long kShaderRoundsPerCase = 64;
};

template <class T>
Verdict replay_in(const VerifyOptions& options, const ReplayMode& mode,
                  const protocol::JsonValue& report, std::ostream& out, std::ostream& err) {
  std::string error;
  std::vector<T> m, c;
  Round<T> round;
  // The design the run judged mirror_view by (absent in reports before it was recorded: the
  // command line's).
  ConsumerMode replayed{{}, mode.mirror_design};
  std::vector<ConsumerKind>& kinds = replayed.kinds;
  const protocol::JsonValue* k = report.find("kinds");
  const protocol::JsonValue* picks = report.find("picks");
  const protocol::JsonValue* convention = report.find("convention");
  std::optional<Convention> parsed_convention =
      convention && convention->is_string() ? parse_convention(convention->text) : std::nullopt;
  if (k && k->is_array()) {
    for (std::size_t i = 0; i < k->size(); ++i) {
      if (const auto kind = protocol::parse_consumer_kind((*k)[i].text)) kinds.push_back(*kind);
    }
  }
  if (kinds.empty()) error = "\"kinds\" names no request kind";
  if (error.empty() && !parsed_convention) error = "\"convention\" is not a convention";
  if (error.empty() && (!picks || !picks->is_array())) error = "\"picks\" must be an array";
  if (error.empty()) {
    for (std::size_t i = 0; i < picks->size(); ++i) {
      char* end = nullptr;
      const long v = std::strtol((*picks)[i].text.c_str(), &end, 10);
      if (!(*picks)[i].is_number() || *end != '\0') {
        error = "\"picks\"[" + std::to_string(i) + "] is not an integer";
        break;
      }
      round.picks.push_back(static_cast<int>(v));
    }
  }
  if (error.empty() && report_numbers<T>(report, "projection", 16, m, error) &&
      report_numbers<T>(report, "plane", 4, c, error)) {
    for (int i = 0; i < 16; ++i) round.c.matrix(i / 4, i % 4) = m[static_cast<std::size_t>(i)];
    for (int i = 0; i < 4; ++i) round.c.plane(i) = c[static_cast<std::size_t>(i)];
    round.c.convention = *parsed_convention;
  }
  if (const protocol::JsonValue* design = report.find("mirror_design"); error.empty() && design) {
    const std::optional<oracle::MirrorDesign> parsed =
        design->is_string() ? oracle::parse_mirror_design(design->text) : std::nullopt;
    if (parsed)
      replayed.mirror_design = *parsed;
    else
      error = "\"mirror_design\" is reflected_view or proper_camera";
  }
  if (!error.empty()) {
    err << "oblique verify: --replay " << mode.report << ": " << error << "\n";
    return Verdict::error;
  }
  std::unique_ptr<Answerer<T>> answerer = answerer_for<T>(options, kinds, err);
  if (!answerer) return Verdict::error;
  return ConsumerRun<T>(options, replayed, std::move(answerer), out, err)
      .replay(std::move(round), mode.report);
}

}  // namespace

Verdict replay_consumer_report(const VerifyOptions& options, const ReplayMode& mode,
                               const protocol::JsonValue& report, std::ostream& out,
                               std::ostream& err) {
  const protocol::JsonValue* precision = report.find("precision");
  if (precision && precision->text == "float")
    return replay_in<float>(options, mode, report, out, err);
  if (precision && precision->text == "double")
    return replay_in<double>(options, mode, report, out, err);
  err << "oblique verify: --replay " << mode.report << ": \"precision\" is float or double\n";
  return Verdict::error;
}

Verdict verify_consumers(const VerifyOptions& options, const ConsumerMode& mode, std::ostream& out,
                         std::ostream& err) {
  if (mode.kinds.empty()) {
    err << "oblique verify: --consumers names no request kind\n";
    return Verdict::error;
  }
  switch (options.precision) {
    case protocol::Precision::float32: {
      std::unique_ptr<Answerer<float>> answerer = answerer_for<float>(options, mode.kinds, err);
      if (!answerer) return Verdict::error;
      return ConsumerRun<float>(options, mode, std::move(answerer), out, err).run();
    }
    case protocol::Precision::float64: {
      std::unique_ptr<Answerer<double>> answerer = answerer_for<double>(options, mode.kinds, err);
      if (!answerer) return Verdict::error;
      return ConsumerRun<double>(options, mode, std::move(answerer), out, err).run();
    }
    case protocol::Precision::long_double: break;
  }
  err << "oblique verify: --precision is float or double\n";
  return Verdict::error;
}

}  // namespace oblique::verify
