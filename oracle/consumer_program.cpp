#include "oblique/oracle/consumer_program.h"

#include "oblique/oracle/consumer_wire.h"
#include "oblique/protocol/child_process.h"

namespace oblique::properties {

using protocol::ConsumerKind;
using protocol::ConsumerRequest;

template <class T>
struct ConsumerProgram<T>::State {
  protocol::ChildProcess child;
  std::chrono::milliseconds timeout;
  std::string request, answer;
  long answered = 0;  ///< answer lines read

  State(std::string command, std::chrono::milliseconds t) : child(std::move(command)), timeout(t) {}

  [[noreturn]] void fail(ProgramFailure::Kind kind, std::string what,
                         std::vector<std::string> lines) {
    throw failure(kind, std::move(what), std::move(lines));
  }

  /// Why the current request got no answer to judge: for a crash or a timeout, the program is
  /// stopped and how it ended and the end of its standard error are said.
  ProgramFailure failure(ProgramFailure::Kind kind, std::string what,
                         std::vector<std::string> lines) {
    if (kind != ProgramFailure::Kind::protocol) {
      const std::string end = kind == ProgramFailure::Kind::crash ? child.end_description() : "";
      child.stop();
      // A shell that could not run the command, before any answer: nothing was verified.
      if (answered == 0 && (end == "exited with status 126" || end == "exited with status 127")) {
        kind = ProgramFailure::Kind::protocol;
        what = "cannot run the program";
      }
      if (!end.empty()) what += " (" + end + ")";
      std::string tail = protocol::escape_bytes(child.stderr_tail());
      while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
      if (!tail.empty()) what += "; its standard error ends: " + tail;
    }
    return ProgramFailure{kind, std::move(what), request, std::move(lines)};
  }

  /// The program started if it is not running, and nothing left unread from before; or why not.
  std::optional<ProgramFailure> ready() {
    if (!child.running()) {
      if (const Expected<Done> started = child.start(); !started)
        return failure(ProgramFailure::Kind::protocol,
                       "the program could not be started: " + started.error(), {});
    }
    if (std::vector<std::string> left = child.unasked_output(); !left.empty())
      return failure(ProgramFailure::Kind::protocol,
                     "lines beyond the one answer to the request before", left);
    return std::nullopt;
  }

  /// Why an exchange ended before every line was read.
  ProgramFailure lost(protocol::ChildProcess::Outcome outcome, std::vector<std::string> lines) {
    using Outcome = protocol::ChildProcess::Outcome;
    if (outcome == Outcome::too_long)
      return failure(ProgramFailure::Kind::protocol,
                     "an answer line longer than 1 MiB (not read further)",
                     {child.overlong_start() + "..."});
    if (outcome == Outcome::exited)
      return failure(ProgramFailure::Kind::crash, "the program ended before answering",
                     std::move(lines));
    return failure(ProgramFailure::Kind::timeout,
                   "no answer within " + std::to_string(timeout.count()) + " ms", std::move(lines));
  }

  /// An answer line's numbers, or why it is not an answer of its kind.
  Expected<std::vector<T>> read_answer(const std::string& line, ConsumerKind kind) const {
    const auto [count, group] = wire::answer_shape(kind);
    const Expected<std::vector<T>> numbers =
        protocol::read_consumer_answer<T>(line, kind, count, group);
    if (!numbers)
      return Expected<std::vector<T>>::failure("an answer that is not a " +
                                               std::string(protocol::consumer_kind_name(kind)) +
                                               " answer (" + numbers.error() + ")");
    return numbers;
  }

  /// Sends `r` and reads the numbers of its answer (read_consumer_answer()).
  std::vector<T> ask(const ConsumerRequest& r, ConsumerKind kind) {
    request = r.line();
    answer.clear();
    if (std::optional<ProgramFailure> f = ready()) throw *f;
    std::vector<std::string> lines;
    const auto outcome =
        child.exchange(request + "\n", 1, lines, timeout, protocol::Clock::now() + timeout);
    if (outcome != protocol::ChildProcess::Outcome::done) throw lost(outcome, lines);
    answer = lines.front();
    ++answered;
    if (std::vector<std::string> extra = child.unasked_output(); !extra.empty()) {
      extra.insert(extra.begin(), answer);
      fail(ProgramFailure::Kind::protocol, "lines beyond the one answer to this request", extra);
    }
    const Expected<std::vector<T>> numbers = read_answer(answer, kind);
    if (!numbers) fail(ProgramFailure::Kind::protocol, numbers.error(), {answer});
    return *numbers;
  }
};

template <class T>
typename ConsumerProgram<T>::Batch ConsumerProgram<T>::answer(
    const std::vector<const ConsumerAsk<T>*>& asks) {
  State& s = *state_;
  Batch out;
  if (asks.empty()) return out;
  std::vector<std::string>& requests = out.requests;
  std::string input;
  for (const ConsumerAsk<T>* a : asks) {
    requests.push_back(a->request().line());
    input += requests.back() + "\n";
  }
  s.request = requests.front();
  s.answer.clear();
  if (std::optional<ProgramFailure> f = s.ready()) {
    out.failure = std::move(f);
    return out;
  }
  const auto deadline = protocol::Clock::now() + s.timeout * static_cast<long>(asks.size());
  const auto outcome = s.child.exchange(input, asks.size(), out.lines, s.timeout, deadline);
  s.answered += static_cast<long>(out.lines.size());
  if (outcome != protocol::ChildProcess::Outcome::done) {
    s.request = requests[out.lines.size()];
    out.failure = s.lost(outcome, {});
  } else if (std::vector<std::string> extra = s.child.unasked_output(); !extra.empty()) {
    s.request = requests.back();
    out.failure = s.failure(ProgramFailure::Kind::protocol,
                            "lines beyond one answer per request (a batch of " +
                                std::to_string(asks.size()) + " requests, this one the last)",
                            extra);
    out.lines.clear();
    return out;
  }
  for (std::size_t i = 0; i < out.lines.size(); ++i) {
    const Expected<std::vector<T>> numbers = s.read_answer(out.lines[i], asks[i]->kind);
    if (!numbers) {
      s.request = requests[i];
      out.failure = s.failure(ProgramFailure::Kind::protocol, numbers.error(), {out.lines[i]});
      out.lines.resize(i);
      break;
    }
    out.numbers.push_back(*numbers);
  }
  out.lines.resize(out.numbers.size());
  if (!out.lines.empty()) s.answer = out.lines.back();
  return out;
}

template <class T>
ConsumerProgram<T>::ConsumerProgram(std::string command, std::chrono::milliseconds timeout)
    : state_(std::make_unique<State>(std::move(command), timeout)) {}

template <class T>
ConsumerProgram<T>::~ConsumerProgram() = default;

template <class T>
const std::string& ConsumerProgram<T>::last_request() const {
  return state_->request;
}

template <class T>
const std::string& ConsumerProgram<T>::last_answer() const {
  return state_->answer;
}

template <class T>
void ConsumerProgram<T>::stop() {
  state_->child.stop();
}

template <class T>
std::vector<std::string> ConsumerProgram<T>::finish() {
  std::vector<std::string> extra;
  if (state_->child.running()) {
    const auto grace = std::min(state_->timeout, std::chrono::milliseconds(1000));
    extra = state_->child.close_and_drain(protocol::Clock::now() + grace);
  }
  state_->child.stop();
  return extra;
}

template <class T>
long ConsumerProgram<T>::answered() const {
  return state_->answered;
}

template <class T>
Consumers<T> ConsumerProgram<T>::consumers(const std::vector<ConsumerKind>& kinds,
                                           const std::string& name) const {
  Consumers<T> c;
  c.name = name;
  State* s = state_.get();
  for (const ConsumerKind kind : kinds) {
    switch (kind) {
      case ConsumerKind::view_position:
        c.view_position = [s, kind](const properties::DepthSample<T>& sample) {
          return wire::vector3(s->ask(wire::depth_request(kind, sample), kind));
        };
        break;
      case ConsumerKind::linear_depth:
        c.linear_depth = [s, kind](const properties::DepthSample<T>& sample) {
          return s->ask(wire::depth_request(kind, sample), kind).front();
        };
        break;
      case ConsumerKind::culling_planes:
        c.culling_planes = [s, kind](const Matrix4<T>& m, Convention convention) {
          return wire::planes(s->ask(wire::culling_request(m, convention), kind));
        };
        break;
      case ConsumerKind::camera_plane:
        c.camera_plane = [s, kind](const Matrix4<T>& view, const Vector4<T>& plane) {
          return wire::vector4(s->ask(wire::view_and_plane_request(kind, view, plane), kind));
        };
        break;
      case ConsumerKind::mirror_view:
        c.mirror_view = [s, kind](const Matrix4<T>& view, const Vector4<T>& plane) {
          return wire::matrix4(s->ask(wire::view_and_plane_request(kind, view, plane), kind));
        };
        break;
      case ConsumerKind::portal_view:
        c.portal_view = [s, kind](const Matrix4<T>& view, const Matrix4<T>& frame,
                                  const Matrix4<T>& linked) {
          return wire::matrix4(s->ask(wire::portal_request(view, frame, linked), kind));
        };
        break;
      case ConsumerKind::corners:
        c.corners = [s, kind](const Matrix4<T>& m, const Matrix4<T>& original,
                              Convention convention) {
          return wire::points(s->ask(wire::corners_request(m, original, convention), kind));
        };
        break;
    }
  }
  return c;
}

template class ConsumerProgram<float>;
template class ConsumerProgram<double>;
template class ConsumerProgram<long double>;

}  // namespace oblique::properties
