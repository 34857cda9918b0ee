#include "oblique/client/program.h"

#include <algorithm>
#include <csignal>

#include "oblique/protocol/child_process.h"
#include "oblique/protocol/matrix_order.h"

namespace oblique::client {

using protocol::ChildProcess;
static_assert(kMaxLineBytes == ChildProcess::kMaxLineBytes);

struct Program::State {
  ChildProcess child;
  std::chrono::milliseconds timeout;
  protocol::MatrixOrder order;
  long answered = 0;

  State(std::string command, std::chrono::milliseconds t, protocol::MatrixOrder o)
      : child(std::move(command)), timeout(t), order(o) {}

  /// The lines from `from` on put in the program's order (or back from it: the same map).
  void reorder(std::vector<std::string>& lines, std::size_t from = 0) const {
    if (order == protocol::MatrixOrder::rows) return;
    for (std::size_t i = from; i < lines.size(); ++i)
      lines[i] = protocol::other_matrix_order(lines[i]);
  }

  /// Starts the program. One that exits early must not take us down with it: a write to its
  /// closed input fails with EPIPE instead of raising SIGPIPE.
  Expected<Done> start() {
    std::signal(SIGPIPE, SIG_IGN);
    return child.start();
  }

  /// A failure of `cause`; for a crash or a timeout how the program ended and the end of its
  /// standard error are said, and it is stopped when `stop` (a read() leaves that to its caller).
  Failure failure(Failure::Cause cause, std::string what, std::string request,
                  std::vector<std::string> lines, bool stop = true) {
    using Cause = Failure::Cause;
    Failure f;
    f.cause = cause;
    f.request = std::move(request);
    f.lines = std::move(lines);
    if (cause == Cause::exited || cause == Cause::timed_out) {
      if (cause == Cause::exited) f.ended = child.end_description();
      if (stop) child.stop();
      // A shell that could not run the command, before any answer: nothing was asked.
      if (answered == 0 &&
          (f.ended == "exited with status 126" || f.ended == "exited with status 127")) {
        f.cause = Cause::cannot_run;
        what = "cannot run the program";
      }
      if (!f.ended.empty()) what += " (" + f.ended + ")";
      std::string tail = protocol::escape_bytes(child.stderr_tail());
      while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
      f.stderr_tail = tail;
      if (!tail.empty()) what += "; its standard error ends: " + tail;
    }
    f.what = std::move(what);
    return f;
  }

  /// Why an exchange ended before every line was read.
  Failure lost(ChildProcess::Outcome outcome, std::string request, std::vector<std::string> lines,
               bool stop = true) {
    if (outcome == ChildProcess::Outcome::too_long)
      return failure(Failure::Cause::overlong,
                     "an answer line longer than 1 MiB (not read further)", std::move(request),
                     {child.overlong_start() + "..."});
    if (outcome == ChildProcess::Outcome::exited)
      return failure(Failure::Cause::exited, "the program ended before answering",
                     std::move(request), std::move(lines), stop);
    return failure(Failure::Cause::timed_out,
                   "no answer within " + std::to_string(timeout.count()) + " ms",
                   std::move(request), std::move(lines), stop);
  }

  /// The program started if it is not running, and nothing left unread from before; or why not.
  std::optional<Failure> ready(const std::string& request) {
    if (!child.running()) {
      if (const Expected<Done> started = start(); !started)
        return failure(Failure::Cause::cannot_start,
                       "the program could not be started: " + started.error(), request, {});
    }
    if (std::vector<std::string> left = child.unasked_output(); !left.empty())
      return failure(Failure::Cause::left_over, "lines beyond the one answer to the request before",
                     request, std::move(left));
    return std::nullopt;
  }
};

Program::Program(std::string command, std::chrono::milliseconds timeout,
                 protocol::MatrixOrder order)
    : state_(std::make_unique<State>(std::move(command), timeout, order)) {}

Program::~Program() = default;

Reply Program::ask(const std::string& request, Clock::time_point deadline) {
  return ask(std::vector<std::string>{request}, deadline);
}

Reply Program::ask(const std::vector<std::string>& asked, Clock::time_point deadline) {
  State& s = *state_;
  Reply out;
  if (asked.empty()) return out;
  // What the program is handed (and what a failure quotes): the requests in its order.
  std::vector<std::string> requests = asked;
  s.reorder(requests);
  if (std::optional<Failure> f = s.ready(requests.front())) {
    out.failure = std::move(f);
    return out;
  }
  std::string input;
  for (const std::string& r : requests) input += r + "\n";
  const auto all = s.timeout * static_cast<long>(requests.size());
  const Clock::time_point end = Clock::now() + all < deadline ? Clock::now() + all : deadline;
  const auto outcome = s.child.exchange(input, requests.size(), out.lines, s.timeout, end);
  s.answered += static_cast<long>(out.lines.size());
  s.reorder(out.lines);  // its answers in the protocol's order
  if (outcome != ChildProcess::Outcome::done) {
    out.failure = s.lost(outcome, requests[out.lines.size()], {});
  } else if (std::vector<std::string> extra = s.child.unasked_output(); !extra.empty()) {
    const std::string what = requests.size() == 1
                                 ? "lines beyond the one answer to this request"
                                 : "lines beyond one answer per request (a batch of " +
                                       std::to_string(requests.size()) +
                                       " requests, this one the last)";
    out.failure = s.failure(Failure::Cause::beyond, what, requests.back(), std::move(extra));
  }
  return out;
}

Expected<Done> Program::start() {
  return state_->start();
}

void Program::queue(std::string_view text) {
  if (state_->order == protocol::MatrixOrder::rows) {
    state_->child.send(text);
    return;
  }
  std::string reordered;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    reordered += protocol::other_matrix_order(text.substr(at, end - at));
    if (end < text.size()) reordered += '\n';
    at = end + 1;
  }
  state_->child.send(reordered);
}

std::optional<Failure> Program::read(std::size_t count, std::vector<std::string>& lines,
                                     Clock::time_point deadline) {
  State& s = *state_;
  const std::size_t before = lines.size();
  const auto outcome = s.child.exchange({}, count, lines, s.timeout, deadline);
  s.answered += static_cast<long>(lines.size() - before);
  s.reorder(lines, before);
  if (outcome == ChildProcess::Outcome::done) return std::nullopt;
  return s.lost(outcome, "", {}, /*stop=*/false);
}

std::vector<std::string> Program::finish() {
  std::vector<std::string> extra;
  if (state_->child.running()) {
    const auto grace = std::min(state_->timeout, std::chrono::milliseconds(1000));
    extra = state_->child.close_and_drain(Clock::now() + grace);
  }
  state_->child.stop();
  return extra;
}

void Program::stop() {
  state_->child.stop();
}

bool Program::running() const {
  return state_->child.running();
}

long Program::answered() const {
  return state_->answered;
}

const std::string& Program::overlong_start() const {
  return state_->child.overlong_start();
}

Run run_once(const std::string& command, std::size_t keep, Clock::time_point deadline) {
  ChildProcess child(command);
  Run r;
  if (!child.start()) {
    r.started = false;
    return r;
  }
  r.timed_out =
      child.run_to_end(r.output, keep, deadline, r.status) == ChildProcess::Outcome::timed_out;
  return r;
}

}  // namespace oblique::client
