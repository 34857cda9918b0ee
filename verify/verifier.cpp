#include "oblique/verify/verifier.h"

#include <rapidcheck.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <optional>
#include <ostream>
#include <random>
#include <sstream>

#include "child_process.h"
#include "oblique/properties/counterexample_report.h"
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

template <class T>
rc::Gen<VerifyCase<T>> verify_case(std::vector<Family> families,
                                   std::vector<Convention> conventions) {
  return rc::gen::exec([families, conventions] {
    VerifyCase<T> v;
    // Four in five have an answer; the pick shrinks toward those.
    if (*rc::gen::resize(100, rc::gen::inRange(0, 5)) < 4) {
      v.c = *generators::valid_case_in<T>(families, conventions);
    } else {
      const generators::InvalidCase<T> ic = *generators::invalid_case_in<T>(families, conventions);
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

/// The suite's judgement, with the contract for external implementations: an input without an
/// answer may get any refusal (the implementation need not name our status); row 3 is held to
/// its accuracy bound.
template <class T>
std::optional<Found<T>> judge(const Problem<T>& problem, const Answered<T>& a) {
  properties::Checks checks;
  checks.statuses = properties::StatusContract::any_refusal;
  checks.row3_accuracy = true;
  const properties::Judgement judgement = properties::judge(problem, a.outcome, checks);
  const properties::Finding* violation = judgement.violation();
  if (!violation) return std::nullopt;
  Found<T> f;
  f.finding = *violation;
  if (a.outcome.status == Status::ok) f.result = a.outcome.projection;
  return f;
}

std::string shell_quote(const std::string& s) {
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
    families_ = options.families.empty() ? generators::every_family() : options.families;
    gen_ = verify_case<T>(families_, options.conventions);
    idle_ = std::chrono::milliseconds(static_cast<long>(options.request_timeout_seconds * 1000));
  }

  int run() {
    start_ = Clock::now();
    deadline_ = start_ + std::chrono::milliseconds(
                             static_cast<long>(std::max(0.0, options_.time_limit_seconds) * 1000));
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
    // implementation works on it while batch k is judged (on two threads).
    Batch current = next_batch(random, generated, batch);
    while (!current.cases.empty()) {
      batch = std::min<std::size_t>(batch * 2, 1024);
      Batch following;
      if (generated < options_.cases && Clock::now() < deadline_)
        following = next_batch(random, generated, batch);
      const std::size_t n = current.cases.size();
      std::vector<std::string> answers;
      const auto outcome = child_.exchange({}, n, answers, idle_, deadline_);
      const std::vector<Judged> judged = judge_all(current, answers);
      for (std::size_t k = 0; k < answers.size(); ++k) {
        const Judged& j = judged[k];
        if (!j.protocol_error.empty())
          return protocol_error(current.requests[k], answers[k], j.protocol_error);
        if (j.finding) {
          Found<T> finding = *j.finding;
          finding.answer_line = answers[k];
          return violation(current.cases[k], finding, done + static_cast<long>(k) + 1);
        }
        count(current.values[k]);
      }
      done += static_cast<long>(answers.size());
      if (outcome != ChildProcess::Outcome::done) {
        if (Clock::now() >= deadline_) break;  // the time limit, not the implementation
        if (done == 0 && outcome == ChildProcess::Outcome::exited) {
          const std::string end = child_.end_description();
          if (end == "exited with status 126" || end == "exited with status 127") {
            err_ << "oblique verify: cannot run the implementation (" << end
                 << "): " << child_.stderr_tail();
            child_.stop();
            return 2;
          }
        }
        return lost(current.cases, answers.size(), done);
      }
      current = std::move(following);
      if (options_.progress && seconds_since(last_progress) >= 2) {
        last_progress = Clock::now();
        err_ << "oblique verify: " << done << " cases, "
             << static_cast<long>(done / seconds_since(start_)) << " per second, no violation\n";
      }
    }
    child_.stop();
    return passed(done);
  }

 private:
  /// Generated cases, their values and request lines, queued for the implementation.
  struct Batch {
    std::vector<rc::Shrinkable<VerifyCase<T>>> cases;
    std::vector<VerifyCase<T>> values;
    std::vector<std::string> requests;
  };

  Batch next_batch(rc::Random& random, long& generated, std::size_t size) {
    Batch b;
    const std::size_t n =
        std::min<std::size_t>(size, static_cast<std::size_t>(options_.cases - generated));
    std::string text;
    for (std::size_t k = 0; k < n; ++k, ++generated) {
      b.cases.push_back(gen_(random.split(), static_cast<int>(generated % 101)));
      b.values.push_back(b.cases.back().value());
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

  /// Reads and judges every answer; the second half on another thread (GMP objects are not
  /// shared, and the values were taken out of their Shrinkables on this thread).
  std::vector<Judged> judge_all(const Batch& b, const std::vector<std::string>& answers) const {
    std::vector<Judged> out(answers.size());
    auto judge_range = [&](std::size_t from, std::size_t to) {
      for (std::size_t k = from; k < to; ++k) {
        const auto answered = read_answer<T>(answers[k], &out[k].protocol_error);
        if (!answered) continue;
        const VerifyCase<T>& v = b.values[k];
        const Problem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
        out[k].finding = judge(problem, *answered);
      }
    };
    const std::size_t half = answers.size() / 2;
    if (half < 8) {
      judge_range(0, answers.size());
      return out;
    }
    auto second = std::async(std::launch::async, judge_range, half, answers.size());
    judge_range(0, half);
    second.get();
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
    out_ << "  families: " << summary(families_seen_)
         << "\n  conventions: " << summary(conventions_seen_)
         << "\n  places (with an answer): " << summary(places_seen_)
         << "\n  inputs without an answer: " << summary(defects_seen_) << "\n";
    if (done < options_.cases)
      out_ << "  stopped by the time limit (" << options_.time_limit_seconds << " s) before "
           << options_.cases << " cases\n";
    return 0;
  }

  int protocol_error(const std::string& request, const std::string& answer,
                     const std::string& why) {
    child_.stop();
    err_ << "oblique verify: protocol error: the implementation's answer is not an answer of the "
            "protocol ("
         << why << ")\n  request: " << request << "\n  answer:  " << answer.substr(0, 400)
         << (answer.size() > 400 ? "..." : "") << "\n";
    return 2;
  }

  enum class Evaluation { pass, finding, protocol_error, out_of_time };

  /// Sends one case alone (restarting the implementation when it is not running).
  Evaluation evaluate(const VerifyCase<T>& v, Found<T>& finding) {
    if (Clock::now() >= deadline_) return Evaluation::out_of_time;
    std::string error;
    if (!child_.running() && !child_.start(&error)) return Evaluation::protocol_error;
    const std::string request = request_text(v.c);
    std::vector<std::string> answers;
    const auto outcome = child_.exchange(request + "\n", 1, answers, idle_, deadline_);
    if (outcome != ChildProcess::Outcome::done) {
      if (Clock::now() >= deadline_) return Evaluation::out_of_time;
      finding = lost_finding(outcome);
      child_.stop();
      return Evaluation::finding;
    }
    std::string why;
    const auto answered = read_answer<T>(answers[0], &why);
    if (!answered) return Evaluation::protocol_error;
    const Problem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
    auto judged = judge(problem, *answered);
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
    found.answer_line = child_.stderr_tail().empty() ? "" : "(stderr) " + child_.stderr_tail();
    return found;
  }

  /// The implementation stopped answering inside a batch: find the request that does it alone.
  int lost(const std::vector<rc::Shrinkable<VerifyCase<T>>>& cases, std::size_t answered,
           long done) {
    const std::string description = child_.end_description();
    const std::string tail = child_.stderr_tail();
    child_.stop();
    for (std::size_t k = answered; k < cases.size(); ++k) {
      Found<T> finding;
      switch (evaluate(cases[k].value(), finding)) {
        case Evaluation::pass: ++done; continue;
        case Evaluation::finding: return violation(cases[k], finding, done + 1);
        case Evaluation::protocol_error:
        case Evaluation::out_of_time: k = cases.size(); break;
      }
    }
    err_ << "oblique verify: the implementation stopped answering after " << done << " cases (it "
         << description << "), and no single request of the batch repeats it"
         << (tail.empty() ? "" : "\n  its standard error ended with:\n" + tail) << "\n";
    return 1;
  }

  int violation(const rc::Shrinkable<VerifyCase<T>>& failing, Found<T> finding, long cases_run) {
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
    ce.place = v.kind();
    if (found.result) properties::set_result(ce, *found.result);
    const Problem<T> problem(v.c.matrix, v.c.plane, v.c.convention);
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
      ce.notes.emplace_back("answer", found.answer_line.substr(0, 2000));
    if (!found.process.empty()) ce.notes.emplace_back("process", found.process);
    ce.notes.emplace_back("shrinking", std::to_string(steps) + " steps" +
                                           (out_of_time ? ", stopped by the time limit" : ""));

    const std::string request = request_text(v.c);
    properties::ReportContext context;
    context.directory = options_.report_dir;
    context.stem = "verify-" + f.kind;
    context.seed = options_.seed;
    std::string conventions;
    for (Convention c : options_.conventions)
      conventions += (conventions.empty() ? "" : ",") + std::string(convention_name(c));
    std::string families;
    for (Family fam : options_.families)
      families += (families.empty() ? "" : ",") + std::string(generators::family_name(fam));
    context.replay_run =
        options_.self + " verify --impl " + shell_quote(options_.command) + " --convention " +
        conventions + (families.empty() ? "" : " --families " + families) + " --precision " +
        std::string(protocol::scalar_name<T>()) + " --cases " + std::to_string(options_.cases) +
        " --seed " + std::to_string(options_.seed);
    context.replay_case = "echo " + shell_quote(request) + " | " + options_.command;
    const std::string path = properties::write_report(ce, context);

    out_ << "  " << f.kind << ": " << f.relation << "\n  residual: " << f.lhs
         << "\n  bound:    " << f.rhs << "\n  input (" << ce.family << ", " << ce.convention << ", "
         << ce.place << "): " << request << "\n";
    if (!found.answer_line.empty())
      out_ << "  answer: " << found.answer_line.substr(0, 400) << "\n";
    out_ << "  report: " << path << "\n  replay: " << context.replay_case << "\n";
    return 1;
  }

  const VerifyOptions& options_;
  std::ostream& out_;
  std::ostream& err_;
  ChildProcess child_;
  std::vector<Family> families_;
  rc::Gen<VerifyCase<T>> gen_ = verify_case<T>({Family::perspective}, {Convention::gl});
  std::chrono::milliseconds idle_{10000};
  Clock::time_point start_, deadline_;
  std::map<std::string, long> families_seen_, conventions_seen_, places_seen_, defects_seen_;
};

}  // namespace

int run_verify(const VerifyOptions& given, std::ostream& out, std::ostream& err) {
  ::signal(SIGPIPE, SIG_IGN);  // a child that exits must not take us with it
  VerifyOptions options = given;
  if (options.command.empty()) {
    err << "oblique verify: --impl needs a command\n";
    return 2;
  }
  if (options.conventions.empty()) {
    err << "oblique verify: no convention to check\n";
    return 2;
  }
  if (options.seed == 0) options.seed = std::random_device{}() | 1u;
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
