#include "oblique/verify/verifier.h"

#include <fcntl.h>
#include <rapidcheck.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <random>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "child_process.h"
#include "oblique/properties/counterexample_report.h"
#include "oblique/properties/filtered.h"
#include "oblique/properties/generators.h"
#include "oblique/properties/judge.h"
#include "oblique/properties/properties.h"
#include "oblique/protocol/protocol.h"

namespace oblique::verify {

namespace {

using generators::Case;
using generators::Defect;
using generators::Family;
using properties::Problem;

/// One generated input: a valid-looking case, or one spoiled by a defect.
template <class T>
struct VerifyCase {
  Case<T> c;
  bool has_defect = false;
  Defect defect = Defect::camera_in_front;

  std::string kind() const {
    return has_defect ? "no answer: " + std::string(generators::defect_name(defect))
                      : std::string(generators::place_name(c.place));
  }
};

/// A case of the resolved contract (oblique::resolved()): four in five have an answer (the pick
/// shrinks toward those), the others one of its defects when its statuses are judged.
template <class T>
rc::Gen<VerifyCase<T>> verify_case(const Contract& contract) {
  const bool defects =
      contract.statuses && *contract.statuses != properties::StatusContract::answers_only;
  return rc::gen::exec([contract, defects] {
    VerifyCase<T> v;
    if (!defects || *rc::gen::resize(100, rc::gen::inRange(0, 5)) < 4) {
      v.c = *generators::valid_case_for<T>(contract);
    } else {
      const generators::InvalidCase<T> ic = *generators::invalid_case_for<T>(contract);
      v.c = ic.base;
      v.has_defect = true;
      v.defect = ic.defect;
    }
    return v;
  });
}

template <class T>
std::string request_text(const Case<T>& c) {
  return protocol::request_line(c.matrix, c.plane, c.convention);
}

/// An answer as read back: the outcome judge() takes, and the message of a refusal.
template <class T>
struct Answered {
  properties::Outcome<T> outcome{Status::ok, Matrix4<T>::Zero()};
  std::string message;
};

/// Reads one answer line; empty with `error` when it is not an answer of the protocol.
template <class T>
std::optional<Answered<T>> read_answer(const std::string& line, std::string* error) {
  const protocol::ParsedAnswer parsed =
      protocol::parse_answer(protocol::normalise_non_finite(line));
  if (!parsed.valid) {
    *error = parsed.error;
    return std::nullopt;
  }
  Answered<T> a;
  a.message = parsed.message;
  if (parsed.status != "ok") {
    const std::optional<Status> status = parse_status(parsed.status);
    if (!status) {
      *error = "unknown status \"" + parsed.status + "\"";
      return std::nullopt;
    }
    a.outcome.status = *status;
    return a;
  }
  for (int i = 0; i < 16; ++i) {
    std::string why;
    const std::string& token = (*parsed.projection)[static_cast<std::size_t>(i)];
    std::optional<T> value = protocol::parse_number<T>(token, &why);
    if (!value) {  // a number beyond T's range is an infinite entry to judge, not a protocol error
      std::string wide_why;
      if (const auto wide = protocol::parse_number<long double>(token, &wide_why))
        value =
            *wide < 0 ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::infinity();
    }
    if (!value) {
      *error = "projection[" + std::to_string(i) + "]: " + why;
      return std::nullopt;
    }
    a.outcome.projection(i / 4, i % 4) = *value;
  }
  return a;
}

/// What went wrong with one answer (or with the process while it was answering): the finding
/// and its evidence.
template <class T>
struct Found {
  properties::Finding finding;  ///< kind: "status", a property, ..., or "crash", "timeout"
  std::optional<Matrix4<T>> result;
  std::string answer_line, process;
};

/// The suite's judgement under the implementation's contract (the Checks from contract_checks()).
/// `problem` is the filtered checker (properties/filtered.h: the exact checker's verdicts, most
/// without GMP; each one used by one thread only).
template <class T>
std::optional<Found<T>> judge(const properties::FilteredProblem<T>& problem, const Answered<T>& a,
                              const properties::Checks& checks) {
  const properties::Judgement judgement = properties::judge(problem, a.outcome, checks);
  const properties::Finding* violation = judgement.violation();
  if (!violation) return std::nullopt;
  Found<T> f;
  f.finding = *violation;
  if (a.outcome.status == Status::ok) f.result = a.outcome.projection;
  return f;
}

std::string shell_quote(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || std::strchr("_./=,:+-@%", ch);
  });
  if (plain) return s;
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// One run of `oblique verify` in scalar type T.
template <class T>
class Verifier {
 public:
  Verifier(const VerifyOptions& options, std::ostream& out, std::ostream& err)
      : options_(options), out_(out), err_(err), child_(options.command) {
    contract_ =
        resolved(options.contract, {Convention::gl}, properties::StatusContract::any_refusal,
                 /*own_row3_accuracy=*/true);
    const bool answers_only = *contract_.statuses == properties::StatusContract::answers_only;
    if (options.contract.planes == Planes::unit &&
        std::find(contract_.places.begin(), contract_.places.end(), generators::Place::scaled) ==
            contract_.places.end())
      left_out_note_.push_back("place scaled (unit-normal planes)");
    if (answers_only)
      left_out_note_.push_back("every input without an exact answer (statuses answers_only)");
    else if (!contract_.refusals.empty())
      left_out_note_.push_back("inputs needing a refusal the contract does not list");
    for (generators::Place p : generators::all_places) {
      if (std::find(contract_.places.begin(), contract_.places.end(), p) ==
              contract_.places.end() &&
          !(options.contract.planes == Planes::unit && p == generators::Place::scaled))
        left_out_note_.push_back("place " + std::string(generators::place_name(p)));
    }
    for (Defect d : generators::all_defects) {
      if (!answers_only && std::find(contract_.defects.begin(), contract_.defects.end(), d) ==
                               contract_.defects.end())
        left_out_note_.push_back("no answer: " + std::string(generators::defect_name(d)));
    }
    gen_ = verify_case<T>(contract_);
    checks_.row3_accuracy = *contract_.row3_accuracy;
    checks_.properties = contract_.properties;
    checks_.statuses = *contract_.statuses;
    idle_ = std::chrono::milliseconds(static_cast<long>(options.request_timeout_seconds * 1000));
  }

  /// --replay: re-judges one report's case; 0 holds, 1 violated, 2 cannot.
  int replay_report(const std::string& path) {
    start_clock();
    const int result = replay_one(path, /*verbose=*/true);
    child_.stop();
    return result;
  }

  int run() {
    start_clock();
    if (!options_.regressions.empty()) {
      const int kept = replay_regressions();
      if (kept != 0) return kept;
      start_clock();  // the run's own time limit starts now
    }
    std::string error;
    if (!child_.start(&error)) {
      err_ << "oblique verify: cannot start the implementation: " << error << "\n";
      return 2;
    }
    rc::Random random(options_.seed);
    long done = 0, generated = 0;
    std::size_t batch = 16;
    auto last_progress = start_;
    // Batch k + 1 is generated and queued before batch k's answers are read, so the
    // implementation works on it while batch k is judged (on --threads threads).
    Batch current = next_batch(random, generated, batch);
    while (!current.cases.empty()) {
      batch = std::min<std::size_t>(batch * 2, 1024);
      Batch following;
      if (generated < case_limit() && Clock::now() < deadline_)
        following = next_batch(random, generated, batch);
      const std::size_t n = current.cases.size();
      std::vector<std::string> answers;
      bool restarted = false;  // --keep-going: a fresh process after a finding in this batch
      auto outcome = child_.exchange({}, n, answers, idle_, deadline_);
      bool time_up = false;
      if (outcome == ChildProcess::Outcome::timed_out && Clock::now() >= deadline_) {
        // The time limit ended the wait, not the implementation; it must still show that it is
        // answering: one more line within --timeout of its last one, or the request it owes is
        // a timeout finding (never a pass with an unanswered request).
        time_up = true;
        outcome = child_.exchange({}, answers.size() + 1, answers, idle_,
                                  child_.last_line_time() + idle_);
      }
      const std::vector<Judged> judged = judge_all(current, answers);
      for (std::size_t k = 0; k < answers.size(); ++k) {
        const Judged& j = judged[k];
        if (!j.protocol_error.empty())
          return protocol_error(current.requests[k], answers[k], j.protocol_error);
        if (j.finding) {
          Found<T> finding = *j.finding;
          finding.answer_line = answers[k];
          const VerifyCase<T>& v = current.values[k];
          const std::string key = finding.finding.kind + " x " +
                                  std::string(generators::family_name(v.c.family)) + " x " +
                                  v.kind();
          if (options_.keep_going && kinds_.count(key)) {
            ++kinds_[key].repeats;  // this kind is reported already
            continue;
          }
          const int result =
              confirmed_violation(current, k, answers, finding, done + static_cast<long>(k) + 1);
          if (!options_.keep_going || result != 1) return result;
          kinds_[key] = Kind{last_report_, 1};
          if (Clock::now() >= deadline_) break;
          // Go on with a fresh process, sent what the old one had queued.
          std::string error;
          if (!child_.start(&error)) {
            err_ << "oblique verify: cannot restart the implementation: " << error << "\n";
            return finish_findings(done);
          }
          std::string text;
          for (const std::string& r : following.requests) text += r + "\n";
          child_.send(text);
          restarted = true;
        }
        count(current.values[k]);
      }
      done += static_cast<long>(answers.size());
      if (!kinds_.empty() && Clock::now() >= deadline_) {
        stopped_by_time_ = true;
        break;
      }
      if (restarted) {
        current = std::move(following);
        continue;
      }
      if (outcome == ChildProcess::Outcome::too_long)
        return overlong_line(current.requests[answers.size()]);
      if (time_up && outcome == ChildProcess::Outcome::done) {
        dropped_ = static_cast<long>(n - answers.size());
        stopped_by_time_ = true;
        break;  // still answering: the time limit ends the run
      }
      if (time_up && outcome == ChildProcess::Outcome::timed_out) {
        return violation(current.cases[answers.size()],
                         lost_finding(ChildProcess::Outcome::timed_out), done + 1);
      }
      if (outcome != ChildProcess::Outcome::done) {
        if (done == 0 && outcome == ChildProcess::Outcome::exited) {
          const std::string end = child_.end_description();
          if (end == "exited with status 126" || end == "exited with status 127") {
            err_ << "oblique verify: cannot run the implementation (" << end
                 << "): " << escape_bytes(child_.stderr_tail());
            child_.stop();
            return 2;
          }
        }
        const int result = lost(current.cases, answers.size(), done, outcome);
        if (result == 1 && options_.keep_going && !kinds_.empty() && !last_report_.empty()) {
          kinds_[last_kind_ + " (ends the run)"] = Kind{last_report_, 1};
          return finish_findings(done);
        }
        return result;
      }
      current = std::move(following);
      if (options_.progress && seconds_since(last_progress) >= 2) {
        last_progress = Clock::now();
        err_ << "oblique verify: " << done << " cases, "
             << static_cast<long>(done / seconds_since(start_)) << " per second, no violation\n";
      }
    }
    if (!stopped_by_time_ && child_.running()) {
      // The count check of the last batch: once its input is closed, the implementation has
      // nothing more to say.
      const auto grace = std::min<Clock::duration>(idle_, std::chrono::seconds(1));
      const std::vector<std::string> extra = child_.close_and_drain(Clock::now() + grace);
      if (!extra.empty()) {
        return count_error("the implementation wrote lines beyond one answer per request (" +
                               std::to_string(done) + " requests, all answered)",
                           {}, extra);
      }
    }
    child_.stop();
    if (!kinds_.empty()) return finish_findings(done);
    if (done == 0) {
      err_ << "oblique verify: no case was judged within the time limit ("
           << options_.time_limit_seconds << " s); nothing is verified\n";
      return 2;
    }
    return passed(done);
  }

 private:
  /// Generated cases, their values and request lines, queued for the implementation.
  struct Batch {
    std::vector<rc::Shrinkable<VerifyCase<T>>> cases;
    std::vector<VerifyCase<T>> values;
    std::vector<std::string> requests;
    std::vector<std::unique_ptr<properties::FilteredProblem<T>>>
        problems;  ///< made when the contract needed them
  };

  bool contract_needs_status() const {
    return !properties::has_every_refusal(*contract_.statuses, contract_.refusals);
  }

  /// Why the contract leaves out this input ("" when it is sent): properties::not_judged(), the
  /// rule every tool shares.
  std::string left_out(const properties::FilteredProblem<T>& problem) const {
    return properties::not_judged(problem, checks_.statuses, contract_.refusals);
  }

  Batch next_batch(rc::Random& random, long& generated, std::size_t size) {
    Batch b;
    const std::size_t n =
        std::min<std::size_t>(size, static_cast<std::size_t>(case_limit() - generated));
    std::string text;
    for (std::size_t k = 0, draws = 0; k < n && draws < 64 * n + 64; ++draws) {
      rc::Shrinkable<VerifyCase<T>> drawn = gen_(random.split(), static_cast<int>(draws % 101));
      VerifyCase<T> value = drawn.value();
      if (contract_needs_status()) {
        auto problem = std::make_unique<properties::FilteredProblem<T>>(
            value.c.matrix, value.c.plane, value.c.convention);
        if (const std::string why = left_out(*problem); !why.empty()) {
          ++left_out_[why];
          continue;
        }
        b.problems.push_back(std::move(problem));
      } else {
        b.problems.push_back(nullptr);
      }
      ++k;
      ++generated;
      b.cases.push_back(std::move(drawn));
      b.values.push_back(std::move(value));
      b.requests.push_back(request_text(b.values.back().c));
      text += b.requests.back();
      text += '\n';
    }
    child_.send(text);
    return b;
  }

  struct Judged {
    std::string protocol_error;
    std::optional<Found<T>> finding;
  };

  /// Reads and judges every answer, in equal slices on up to options_.threads threads (GMP
  /// objects are not shared, and the values were taken out of their Shrinkables on this thread).
  std::vector<Judged> judge_all(const Batch& b, const std::vector<std::string>& answers) const {
    std::vector<Judged> out(answers.size());
    auto judge_range = [&](std::size_t from, std::size_t to) {
      for (std::size_t k = from; k < to; ++k) {
        const auto answered = read_answer<T>(answers[k], &out[k].protocol_error);
        if (!answered) continue;
        const VerifyCase<T>& v = b.values[k];
        if (b.problems[k]) {
          out[k].finding = judge(*b.problems[k], *answered, checks_);
        } else {
          const properties::FilteredProblem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
          out[k].finding = judge(problem, *answered, checks_);
        }
      }
    };
    constexpr std::size_t kMinSlice = 8;  // below this a thread costs more than it saves
    const std::size_t slices =
        std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(options_.threads),
                                                       answers.size() / kMinSlice));
    const std::size_t size = (answers.size() + slices - 1) / slices;
    std::vector<std::future<void>> others;
    for (std::size_t i = 1; i < slices; ++i) {
      others.push_back(std::async(std::launch::async, judge_range, i * size,
                                  std::min(answers.size(), (i + 1) * size)));
    }
    judge_range(0, std::min(answers.size(), size));
    for (auto& other : others) other.get();
    return out;
  }

  void count(const VerifyCase<T>& v) {
    ++families_seen_[std::string(generators::family_name(v.c.family))];
    ++conventions_seen_[std::string(convention_name(v.c.convention))];
    if (v.has_defect)
      ++defects_seen_[std::string(generators::defect_name(v.defect))];
    else
      ++places_seen_[std::string(generators::place_name(v.c.place))];
  }

  static std::string summary(const std::map<std::string, long>& counts) {
    std::string out;
    for (const auto& [name, n] : counts)
      out += (out.empty() ? "" : ", ") + name + " " + std::to_string(n);
    return out.empty() ? "none" : out;
  }

  int passed(long done) {
    const double elapsed = seconds_since(start_);
    out_ << "oblique verify: " << done << " cases, no violation (" << protocol::scalar_name<T>()
         << ", seed " << options_.seed << ", " << std::fixed;
    out_.precision(1);
    out_ << elapsed << " s, " << static_cast<long>(elapsed > 0 ? done / elapsed : 0)
         << " requests per second)\n";
    out_.unsetf(std::ios::floatfield);
    out_.precision(6);
    out_ << "  contract: " << contract_json(contract_) << "\n";
    out_ << "  families: " << summary(families_seen_)
         << "\n  conventions: " << summary(conventions_seen_)
         << "\n  places (with an answer): " << summary(places_seen_)
         << "\n  inputs without an answer: " << summary(defects_seen_) << "\n";
    if (!left_out_.empty() || !left_out_note_.empty()) {
      out_ << "  left out by the contract:";
      std::string sep = " ";
      for (const std::string& note : left_out_note_) {
        out_ << sep << note;
        sep = ", ";
      }
      for (const auto& [why, n] : left_out_) {
        out_ << sep << why << " " << n << " drawn";
        sep = ", ";
      }
      out_ << "\n";
    }
    if (stopped_by_time_ || done < case_limit())
      out_ << "  stopped by the time limit (" << options_.time_limit_seconds << " s)"
           << (options_.cases > 0 ? " before " + std::to_string(options_.cases) + " cases" : "")
           << (dropped_ > 0 ? "; the implementation was still answering (" +
                                  std::to_string(dropped_) + " requests in flight not judged)"
                            : "")
           << "\n";
    return 0;
  }

  int protocol_error(const std::string& request, const std::string& answer,
                     const std::string& why) {
    child_.stop();
    err_ << "oblique verify: protocol error: the implementation's answer is not an answer of the "
            "protocol ("
         << escape_bytes(why) << ")\n  request: " << request
         << "\n  answer:  " << escape_bytes(answer.substr(0, 400))
         << (answer.size() > 400 ? "..." : "") << "\n";
    return 2;
  }

  /// Answers out of step with requests: lines beyond one per request, or one missing.
  int count_error(const std::string& what, const std::vector<std::string>& requests,
                  const std::vector<std::string>& lines) {
    child_.stop();
    err_ << "oblique verify: protocol error: " << what << "\n";
    for (const std::string& r : requests) err_ << "  request: " << r << "\n";
    for (const std::string& l : lines)
      err_ << "  line:    " << escape_bytes(l.substr(0, 400)) << (l.size() > 400 ? "..." : "")
           << "\n";
    err_ << "  (each request gets exactly one answer line, in order)\n";
    return 2;
  }

  int overlong_line(const std::string& request) {
    child_.stop();
    err_ << "oblique verify: protocol error: an answer line longer than "
         << ChildProcess::kMaxLineBytes
         << " bytes (1 MiB, not read further)\n  request: " << request
         << "\n  line starts: " << escape_bytes(child_.overlong_start()) << "...\n";
    return 2;
  }

  /// The protocol problem of the last evaluation, reported by report_issue().
  struct Issue {
    std::string what, request;
    std::vector<std::string> lines;
  };

  int report_issue() {
    if (issue_.what.empty()) issue_.what = "the implementation could not be restarted";
    return count_error(issue_.what,
                       issue_.request.empty() ? std::vector<std::string>{}
                                              : std::vector<std::string>{issue_.request},
                       issue_.lines);
  }

  /// --keep-going: one report per kind, and an index of them.
  struct Kind {
    std::string report;
    long repeats = 0;  ///< cases of this kind found (the first one shrunk and reported)
  };

  int finish_findings(long done) {
    child_.stop();
    std::ostringstream index;
    index << "# oblique verify: " << kinds_.size() << " kinds of finding\n\n"
          << "Implementation `" << options_.command << "`, " << protocol::scalar_name<T>()
          << ", seed " << options_.seed << ", " << done << " cases judged.\n\n"
          << "| kind (property x family x place) | cases | report |\n|---|---|---|\n";
    for (const auto& [key, kind] : kinds_)
      index << "| " << key << " | " << kind.repeats << " | " << kind.report << " |\n";
    index << "\nThe whole run again:\n\n```sh\n" << replay_run_command() << "\n```\n";
    namespace fs = std::filesystem;
    std::string path = options_.report_dir + "/verify-index.md";
    for (int n = 2; fs::exists(path); ++n)
      path = options_.report_dir + "/verify-index-" + std::to_string(n) + ".md";
    std::ofstream(path) << index.str();
    out_ << "oblique verify: " << kinds_.size() << " kinds of finding in " << done
         << " cases (--keep-going); index: " << path << "\n";
    for (const auto& [key, kind] : kinds_)
      out_ << "  " << key << ": " << kind.repeats << " cases, report " << kind.report << "\n";
    return 1;
  }

  long case_limit() const {
    return options_.cases > 0 ? options_.cases : std::numeric_limits<long>::max();
  }

  enum class Evaluation { pass, finding, protocol_error, out_of_time };

  /// Sends one case alone (restarting the implementation when it is not running).
  Evaluation evaluate(const VerifyCase<T>& v, Found<T>& finding) {
    if (Clock::now() >= deadline_) return Evaluation::out_of_time;
    const properties::FilteredProblem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
    if (contract_needs_status() && !left_out(problem).empty())
      return Evaluation::pass;  // not an input the implementation promises anything for
    std::string error;
    issue_ = Issue{};
    if (!child_.running() && !child_.start(&error)) {
      issue_.what = "the implementation could not be restarted: " + error;
      return Evaluation::protocol_error;
    }
    // The count check of one evaluation: nothing left over before the request, one line after.
    if (std::vector<std::string> left = child_.unasked_output(); !left.empty()) {
      issue_ = Issue{"lines beyond the one answer to this request", last_request_, left};
      return Evaluation::protocol_error;
    }
    const std::string request = request_text(v.c);
    last_request_ = request;
    std::vector<std::string> answers;
    const auto outcome = child_.exchange(request + "\n", 1, answers, idle_, deadline_);
    if (outcome == ChildProcess::Outcome::too_long) {
      issue_ = Issue{"an answer line longer than 1 MiB (not read further)",
                     request,
                     {child_.overlong_start() + "..."}};
      return Evaluation::protocol_error;
    }
    if (outcome != ChildProcess::Outcome::done) {
      if (Clock::now() >= deadline_) return Evaluation::out_of_time;
      finding = lost_finding(outcome);
      child_.stop();
      return Evaluation::finding;
    }
    if (std::vector<std::string> extra = child_.unasked_output(); !extra.empty()) {
      extra.insert(extra.begin(), answers[0]);
      issue_ = Issue{"lines beyond the one answer to this request", request, extra};
      return Evaluation::protocol_error;
    }
    std::string why;
    const auto answered = read_answer<T>(answers[0], &why);
    if (!answered) {
      issue_ = Issue{
          "an answer that is not an answer of the protocol (" + why + ")", request, {answers[0]}};
      return Evaluation::protocol_error;
    }
    auto judged = judge(problem, *answered, checks_);
    if (!judged) return Evaluation::pass;
    finding = *judged;
    finding.answer_line = answers[0];
    return Evaluation::finding;
  }

  Found<T> lost_finding(ChildProcess::Outcome outcome) {
    Found<T> found;
    properties::Finding& f = found.finding;
    f.ratio = 1e300;
    if (outcome == ChildProcess::Outcome::exited) {
      f.kind = "crash";
      f.relation = "the implementation answers every request and keeps running";
      found.process = child_.end_description();
      f.lhs = "it " + found.process + " before answering";
      f.rhs = "an answer line";
    } else {
      f.kind = "timeout";
      std::ostringstream relation;
      relation << "an answer within " << options_.request_timeout_seconds << " s (--timeout)";
      f.relation = relation.str();
      found.process = "no answer line";
      f.lhs =
          "no answer within the timeout: it hangs on this request, or does not flush its "
          "standard output after each answer line";
      f.rhs = "an answer line";
    }
    found.answer_line =
        child_.stderr_tail().empty() ? "" : "(stderr) " + escape_bytes(child_.stderr_tail());
    return found;
  }

  /// The implementation stopped answering inside a batch: find the request that does it alone.
  /// When the time runs out before one request alone repeats it, the first unanswered request
  /// of the batch is reported as found there.
  int lost(const std::vector<rc::Shrinkable<VerifyCase<T>>>& cases, std::size_t answered, long done,
           ChildProcess::Outcome outcome) {
    Found<T> in_batch = lost_finding(outcome);
    const bool hung = outcome == ChildProcess::Outcome::timed_out;
    const std::string description = hung ? "gave no answer within --timeout" : in_batch.process;
    const std::string tail = escape_bytes(child_.stderr_tail());
    child_.stop();
    bool every_one_answered = true;
    for (std::size_t k = answered; k < cases.size(); ++k) {
      Found<T> finding;
      switch (evaluate(cases[k].value(), finding)) {
        case Evaluation::pass: continue;
        case Evaluation::finding: return violation(cases[k], finding, done + 1);
        case Evaluation::protocol_error: return report_issue();
        case Evaluation::out_of_time:
          if (k == answered) {
            in_batch.process += " (in a batch; not repeated alone within the time limit)";
            return violation(cases[answered], in_batch, done + 1);
          }
          every_one_answered = false;
          k = cases.size();
          break;
      }
    }
    if (every_one_answered && hung) {
      return count_error("the implementation answered " + std::to_string(answered) +
                             " of a batch's " + std::to_string(cases.size()) +
                             " requests and then nothing within --timeout, yet each unanswered "
                             "request alone gets its answer: an answer line is missing",
                         {}, {});
    }
    err_ << "oblique verify: the implementation stopped answering after " << done << " cases (it "
         << description << "), and no single request of the batch repeats it"
         << (tail.empty() ? "" : "\n  its standard error ended with:\n" + tail) << "\n";
    return 1;
  }

  void start_clock() {
    start_ = Clock::now();
    deadline_ = start_ + std::chrono::milliseconds(
                             static_cast<long>(std::max(0.0, options_.time_limit_seconds) * 1000));
  }

  /// The case of a report (its JSON sidecar): the request, and the family named there.
  std::optional<VerifyCase<T>> read_report_case(const std::string& path, std::string* error) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
      *error = "cannot read " + path;
      return std::nullopt;
    }
    std::ostringstream text;
    text << file.rdbuf();
    const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("request") || !j["request"].is_string()) {
      *error = path + " is not a report of oblique verify (no \"request\")";
      return std::nullopt;
    }
    if (j.contains("precision") && j["precision"] != std::string(protocol::scalar_name<T>())) {
      *error = path + " is a " + j["precision"].dump() + " case, not " +
               std::string(protocol::scalar_name<T>());
      return std::nullopt;
    }
    const protocol::ParsedLine parsed = protocol::parse_request(j["request"].get<std::string>());
    if (!parsed.request) {
      *error = path + ": " + parsed.error;
      return std::nullopt;
    }
    VerifyCase<T> v;
    for (int i = 0; i < 16; ++i) {
      const auto value = protocol::parse_number<T>(parsed.request->projection[i], error);
      if (!value) return std::nullopt;
      v.c.matrix(i / 4, i % 4) = *value;
    }
    for (int i = 0; i < 4; ++i) {
      const auto value = protocol::parse_number<T>(parsed.request->plane[i], error);
      if (!value) return std::nullopt;
      v.c.plane(i) = *value;
    }
    v.c.convention = parsed.request->convention.value_or(Convention::gl);
    if (j.contains("family") && j["family"].is_string()) {
      if (auto f = generators::parse_family(j["family"].get<std::string>())) v.c.family = *f;
    }
    return v;
  }

  /// Sends one report's case to the implementation and judges the answer.
  int replay_one(const std::string& path, bool verbose) {
    std::string error;
    const std::optional<VerifyCase<T>> v = read_report_case(path, &error);
    if (!v) {
      err_ << "oblique verify: --replay: " << error << "\n";
      return 2;
    }
    Found<T> found;
    switch (evaluate(*v, found)) {
      case Evaluation::pass:
        if (verbose) {
          out_ << "oblique verify: " << path << ": holds (" << protocol::scalar_name<T>() << ", "
               << convention_name(v->c.convention) << ")\n";
        }
        return 0;
      case Evaluation::finding: {
        const properties::Finding& f = found.finding;
        out_ << "oblique verify: " << path << ": violated: " << f.kind << ": " << f.relation
             << "\n";
        if (!f.expected.empty()) {
          out_ << "  expected: " << f.expected << "\n  got:      " << f.got << "\n";
        } else {
          out_ << "  residual: " << f.lhs << "\n  bound:    " << f.rhs << "\n";
        }
        if (!found.answer_line.empty())
          out_ << "  answer: " << escape_bytes(found.answer_line.substr(0, 400)) << "\n";
        return 1;
      }
      case Evaluation::protocol_error: return report_issue();
      case Evaluation::out_of_time:
        err_ << "oblique verify: --replay: out of time before the answer\n";
        return 2;
    }
    return 2;
  }

  /// --regressions DIR: every kept case first; the first that fails again ends the run.
  int replay_regressions() {
    namespace fs = std::filesystem;
    std::error_code ec;
    std::vector<std::string> paths;
    for (fs::directory_iterator it(options_.regressions, ec), end; !ec && it != end;
         it.increment(ec)) {
      if (it->path().extension() == ".json") paths.push_back(it->path().string());
    }
    if (ec && ec != std::errc::no_such_file_or_directory) {
      err_ << "oblique verify: --regressions " << options_.regressions << ": " << ec.message()
           << "\n";
      return 2;
    }
    std::sort(paths.begin(), paths.end());
    long replayed = 0, other_precision = 0;
    for (const std::string& path : paths) {
      std::string error;
      if (!read_report_case(path, &error)) {
        if (error.find(" case, not ") != std::string::npos) {
          ++other_precision;
          continue;
        }
        err_ << "oblique verify: --regressions: " << error << "\n";
        return 2;
      }
      const int result = replay_one(path, /*verbose=*/false);
      if (result != 0) {
        child_.stop();
        if (result == 1) out_ << "  (a kept regression fails again; the run is not started)\n";
        return result;
      }
      ++replayed;
    }
    child_.stop();
    out_ << "oblique verify: regressions: " << replayed << " kept cases hold"
         << (other_precision
                 ? " (" + std::to_string(other_precision) + " of another precision not replayed)"
                 : "")
         << "\n";
    return 0;
  }

  /// A finding in a batch is confirmed by sending its request alone (in a fresh process) before
  /// it is shrunk: an answer judged against the wrong request (an extra or a missing line before
  /// it) is a protocol error, not a property violation.
  int confirmed_violation(const Batch& batch, std::size_t k,
                          const std::vector<std::string>& answers, Found<T> finding,
                          long cases_run) {
    child_.stop();
    Found<T> alone;
    switch (evaluate(batch.values[k], alone)) {
      case Evaluation::finding: finding = alone; break;
      case Evaluation::out_of_time: break;  // reported as found in the batch
      case Evaluation::protocol_error: return report_issue();
      case Evaluation::pass: {
        std::vector<std::string> lines;
        const std::size_t from = k >= 2 ? k - 2 : 0;
        for (std::size_t i = from; i < std::min(answers.size(), k + 3); ++i)
          lines.push_back("answer " + std::to_string(i + 1) + (i == k ? " (judged)" : "") + ": " +
                          answers[i]);
        std::vector<std::string> alone_answer;
        child_.stop();
        return count_error(
            "answer " + std::to_string(k + 1) + " of a batch violates " + finding.finding.kind +
                ", but the same request sent alone is answered without a violation: the answers "
                "are out of step with the requests (an extra or a missing answer line before "
                "it), or an answer depends on earlier requests",
            {batch.requests[k]}, lines);
      }
    }
    return violation(batch.cases[k], finding, cases_run);
  }

  int violation(const rc::Shrinkable<VerifyCase<T>>& failing, Found<T> finding, long cases_run) {
    found_after_cases_ = cases_run;
    found_after_seconds_ = seconds_since(start_);
    child_.stop();  // it may still be working on the next batch; shrinking restarts it
    out_ << "oblique verify: " << finding.finding.kind << " violated after " << cases_run
         << " cases; shrinking";
    out_.flush();
    rc::Shrinkable<VerifyCase<T>> current = failing;
    int steps = 0, tries = 0;
    bool out_of_time = false;
    // Timeouts cost the whole timeout per try: the case is reported as found.
    bool progress = finding.finding.kind != "timeout";
    while (progress && !out_of_time) {
      progress = false;
      auto shrinks = current.shrinks();
      while (auto next = shrinks.next()) {
        Found<T> candidate;
        ++tries;
        const Evaluation e = evaluate(next->value(), candidate);
        if (e == Evaluation::out_of_time) {
          out_of_time = true;
          break;
        }
        if (e == Evaluation::protocol_error) {
          out_ << "\n";
          return report_issue();
        }
        if (e == Evaluation::finding && candidate.finding.kind == finding.finding.kind) {
          current = *next;
          finding = candidate;
          ++steps;
          progress = true;
          if (steps % 10 == 0) (out_ << ".").flush();
          break;
        }
      }
    }
    child_.stop();
    out_ << " " << steps << " steps (" << tries << " tries)"
         << (out_of_time ? ", stopped by the time limit" : "") << "\n";
    return write(current.value(), finding, steps, out_of_time);
  }

  int write(const VerifyCase<T>& v, const Found<T>& found, int steps, bool out_of_time) {
    const properties::Finding& f = found.finding;
    properties::Counterexample ce =
        properties::make_counterexample(v.c.matrix, v.c.plane, v.c.convention);
    ce.finding = f;
    ce.implementation = options_.command;
    ce.family = std::string(generators::family_name(v.c.family));
    const Problem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
    // "no answer: DEFECT" only where the input has none (a near_singular one may well have one).
    ce.place = v.has_defect && problem.exact_status() == Status::ok
                   ? std::string(generators::defect_name(v.defect)) + " (has an answer)"
                   : v.kind();
    if (found.result) properties::set_result(ce, *found.result);
    properties::set_views(ce, problem, found.result ? &*found.result : nullptr);
    ce.notes.emplace_back("implementation", options_.command);
    ce.notes.emplace_back("exact status", std::string(status_code(problem.exact_status())));
    if (problem.exact_status() == Status::ok) {
      std::string row;
      const exact::Vec exact_row = problem.exact_row3();
      for (int i = 0; i < 4; ++i) {
        T rounded = static_cast<T>(exact_row[i].get_d());
        row += (i ? ", " : "") + protocol::format_number(rounded);
      }
      ce.notes.emplace_back("exact third row (rounded)", "(" + row + ")");
    }
    if (!found.answer_line.empty())
      ce.notes.emplace_back("answer", escape_bytes(found.answer_line.substr(0, 2000)));
    if (!found.process.empty()) ce.notes.emplace_back("process", found.process);
    ce.notes.emplace_back("shrinking", std::to_string(steps) + " steps" +
                                           (out_of_time ? ", stopped by the time limit" : ""));
    ce.notes.emplace_back("found after", std::to_string(found_after_cases_) + " cases, " +
                                             seconds_text(found_after_seconds_) + " s");

    const std::string request = request_text(v.c);
    properties::ReportContext context;
    context.directory = options_.report_dir;
    context.stem = "verify-" + f.kind;
    context.seed = options_.seed;
    context.replay_run = replay_run_command();
    context.replay_case = "echo " + shell_quote(request) + " | " + options_.command;
    context.contract = contract_json(contract_);
    context.keep_existing = true;
    std::string path;
    try {
      path = properties::write_report(ce, context);
    } catch (const std::exception& e) {
      path = "(not written: " + std::string(e.what()) + ")";
    }
    last_report_ = path;
    last_kind_ = f.kind;
    const std::string json_path = path.size() > 3 && path.compare(path.size() - 3, 3, ".md") == 0
                                      ? path.substr(0, path.size() - 3) + ".json"
                                      : "";
    if (!json_path.empty() && !options_.save_regressions.empty()) save_regression(json_path);

    out_ << "  " << f.kind << ": " << f.relation << "\n";
    if (!f.expected.empty()) {
      out_ << "  expected: " << f.expected << "\n  got:      " << f.got << "\n";
    } else {
      out_ << "  residual: " << f.lhs << "\n  bound:    " << f.rhs << "\n";
    }
    out_ << "  input (" << ce.family << ", " << ce.convention << ", " << ce.place
         << "): " << request << "\n  found after " << found_after_cases_ << " cases, "
         << seconds_text(found_after_seconds_) << " s\n";
    if (!found.answer_line.empty())
      out_ << "  answer: " << escape_bytes(found.answer_line.substr(0, 400)) << "\n";
    out_ << "  report: " << path << "\n  replay: " << context.replay_case << "\n";
    if (!json_path.empty()) out_ << "  re-judge: " << replay_case_command(json_path) << "\n";
    return 1;
  }

  static std::string seconds_text(double seconds) {
    std::ostringstream text;
    text.setf(std::ios::fixed);
    text.precision(2);
    text << seconds;
    return text.str();
  }

  /// The whole run again: this run's own flags (every one of them), with its seed.
  std::string replay_run_command() const {
    std::string command = options_.self + " verify";
    bool has_seed = false;
    for (const std::string& a : options_.arguments) {
      if (a == "--seed" || a.rfind("--seed=", 0) == 0) has_seed = true;
      command += " " + shell_quote(a);
    }
    if (options_.arguments.empty()) command += " --impl " + shell_quote(options_.command);
    if (!has_seed) command += " --seed " + std::to_string(options_.seed);
    return command;
  }

  /// This case alone, judged: the run's contract and bounds flags, with --replay.
  std::string replay_case_command(const std::string& report_json) const {
    std::string command = options_.self + " verify --replay " + shell_quote(report_json) +
                          " --impl " + shell_quote(options_.command);
    static const char* const kept[] = {"--answers-only", "--statuses", "--planes",
                                       "--contract",     "--timeout",  "--precision"};
    const auto& args = options_.arguments;
    for (std::size_t i = 0; i < args.size(); ++i) {
      for (const char* flag : kept) {
        if (args[i] == flag) {
          command += " " + args[i];
          if (std::string(flag) != "--answers-only" && i + 1 < args.size())
            command += " " + shell_quote(args[++i]);
        } else if (args[i].rfind(std::string(flag) + "=", 0) == 0) {
          command += " " + shell_quote(args[i]);
        }
      }
    }
    return command;
  }

  void save_regression(const std::string& json_path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(options_.save_regressions, ec);
    const fs::path from(json_path);
    fs::path to = fs::path(options_.save_regressions) / from.filename();
    for (int n = 2; fs::exists(to, ec); ++n)
      to = fs::path(options_.save_regressions) /
           (from.stem().string() + "-" + std::to_string(n) + ".json");
    fs::copy_file(from, to, ec);
    if (ec) {
      err_ << "oblique verify: cannot save the regression to " << to.string() << ": "
           << ec.message() << "\n";
    } else {
      out_ << "  kept as a regression: " << to.string() << "\n";
    }
  }

  const VerifyOptions& options_;
  std::ostream& out_;
  std::ostream& err_;
  ChildProcess child_;
  Contract contract_;  ///< options_.contract resolved: every list filled
  rc::Gen<VerifyCase<T>> gen_ = verify_case<T>(Contract{});
  std::chrono::milliseconds idle_{10000};
  Clock::time_point start_, deadline_;
  std::map<std::string, long> families_seen_, conventions_seen_, places_seen_, defects_seen_;
  bool stopped_by_time_ = false;
  long found_after_cases_ = 0;
  double found_after_seconds_ = 0;
  std::string last_report_, last_kind_;
  std::map<std::string, Kind> kinds_;
  properties::Checks checks_;
  std::map<std::string, long> left_out_;
  std::vector<std::string> left_out_note_;
  long dropped_ = 0;
  Issue issue_;
  std::string last_request_;
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
  fs::create_directories(directory, ec);
  if (ec) return "cannot be created (" + ec.message() + ")";
  if (!fs::is_directory(directory, ec)) return "is not a directory";
  const std::string probe =
      (fs::path(directory) / (".oblique-verify-probe-" + std::to_string(::getpid()))).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return std::string("cannot be written (") + std::strerror(errno) + ")";
  const bool written = ::write(fd, "x", 1) == 1;
  ::close(fd);
  ::unlink(probe.c_str());
  if (!written) return "cannot be written";
  return "";
}

}  // namespace

int default_threads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

int run_verify(const VerifyOptions& given, std::ostream& out, std::ostream& err) {
  ::signal(SIGPIPE, SIG_IGN);  // a child that exits must not take us with it
  VerifyOptions options = given;
  if (options.command.empty()) {
    err << "oblique verify: --impl needs a command\n";
    return 2;
  }
  // Range checks: durations must fit the clock's arithmetic (and NaN is no duration).
  if (!(options.time_limit_seconds > 0 && options.time_limit_seconds <= kMaxSeconds)) {
    err << "oblique verify: --time-limit must be more than 0 and at most " << kMaxSeconds
        << " seconds (about 3 years), not " << options.time_limit_seconds << "\n";
    return 2;
  }
  if (!(options.request_timeout_seconds >= 0.001 &&
        options.request_timeout_seconds <= kMaxSeconds)) {
    err << "oblique verify: --timeout must be at least 0.001 and at most " << kMaxSeconds
        << " seconds, not " << options.request_timeout_seconds << "\n";
    return 2;
  }
  if (options.cases < 0) {
    err << "oblique verify: --cases must be positive\n";
    return 2;
  }
  if (!(options.threads >= 1 && options.threads <= 256)) {
    err << "oblique verify: --threads must be between 1 and 256, not " << options.threads << "\n";
    return 2;
  }
  // Standard input, output and error closed when we were started: give them /dev/null, so the
  // pipes to the implementation never take fds 0..2 (and our output never goes into its input).
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) < 0 && errno == EBADF) {
      const int null = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
      if (null >= 0 && null != fd) {
        ::dup2(null, fd);
        ::close(null);
      }
    }
  }
  // The report directory is checked before the run: a finding must not be lost after shrinking.
  if (std::string why = options.replay.empty() ? check_report_directory(options.report_dir) : "";
      !why.empty()) {
    err << "oblique verify: --report-dir " << options.report_dir << ": " << why << "\n";
    return 2;
  }
  if (options.seed == 0) options.seed = std::random_device{}() | 1u;
  if (!options.replay.empty()) {
    // The report's precision, whatever --precision says.
    std::ifstream file(options.replay, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
    if (!file || j.is_discarded() || !j.is_object()) {
      err << "oblique verify: --replay: cannot read the report " << options.replay << "\n";
      return 2;
    }
    if (j.contains("precision") && j["precision"].is_string()) {
      if (auto p = protocol::parse_precision(j["precision"].get<std::string>()))
        options.precision = *p;
    }
    switch (options.precision) {
      case protocol::Precision::float32:
        return Verifier<float>(options, out, err).replay_report(options.replay);
      case protocol::Precision::float64:
        return Verifier<double>(options, out, err).replay_report(options.replay);
      case protocol::Precision::long_double:
        err << "oblique verify: --replay: a long_double report\n";
        return 2;
    }
  }
  switch (options.precision) {
    case protocol::Precision::float32: return Verifier<float>(options, out, err).run();
    case protocol::Precision::float64: return Verifier<double>(options, out, err).run();
    case protocol::Precision::long_double:
      err << "oblique verify: --precision is float or double\n";
      return 2;
  }
  return 2;
}

}  // namespace oblique::verify
