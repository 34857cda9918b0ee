#include "oblique/oracle/consumer_program.h"

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
    throw ProgramFailure{kind, std::move(what), request, std::move(lines)};
  }

  /// Sends `r` and reads the numbers of its answer (read_consumer_answer()).
  std::vector<T> ask(const ConsumerRequest& r, ConsumerKind kind, std::size_t count,
                     std::size_t group) {
    request = r.line();
    answer.clear();
    if (!child.running()) {
      if (const Expected<Done> started = child.start(); !started)
        fail(ProgramFailure::Kind::protocol, "the program could not be started: " + started.error(),
             {});
    }
    if (std::vector<std::string> left = child.unasked_output(); !left.empty())
      fail(ProgramFailure::Kind::protocol, "lines beyond the one answer to the request before",
           left);
    std::vector<std::string> lines;
    const auto outcome =
        child.exchange(request + "\n", 1, lines, timeout, protocol::Clock::now() + timeout);
    using Outcome = protocol::ChildProcess::Outcome;
    if (outcome == Outcome::too_long)
      fail(ProgramFailure::Kind::protocol, "an answer line longer than 1 MiB (not read further)",
           {child.overlong_start() + "..."});
    if (outcome == Outcome::exited)
      fail(ProgramFailure::Kind::crash, "the program ended before answering", lines);
    if (outcome == Outcome::timed_out)
      fail(ProgramFailure::Kind::timeout,
           "no answer within " + std::to_string(timeout.count()) + " ms", lines);
    answer = lines.front();
    ++answered;
    if (std::vector<std::string> extra = child.unasked_output(); !extra.empty()) {
      extra.insert(extra.begin(), answer);
      fail(ProgramFailure::Kind::protocol, "lines beyond the one answer to this request", extra);
    }
    const Expected<std::vector<T>> numbers =
        protocol::read_consumer_answer<T>(answer, kind, count, group);
    if (!numbers)
      fail(ProgramFailure::Kind::protocol,
           "an answer that is not a " + std::string(protocol::consumer_kind_name(kind)) +
               " answer (" + numbers.error() + ")",
           {answer});
    return *numbers;
  }
};

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

namespace {

template <class T>
Vector3<T> vector3(const std::vector<T>& v, std::size_t at = 0) {
  return Vector3<T>(v[at], v[at + 1], v[at + 2]);
}

template <class T>
Vector4<T> vector4(const std::vector<T>& v, std::size_t at = 0) {
  return Vector4<T>(v[at], v[at + 1], v[at + 2], v[at + 3]);
}

template <class T>
Matrix4<T> matrix4(const std::vector<T>& v) {
  Matrix4<T> m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = v[static_cast<std::size_t>(i)];
  return m;
}

template <class T>
ConsumerRequest depth_request(ConsumerKind kind, const properties::DepthSample<T>& s) {
  ConsumerRequest r(kind);
  r.numbers("projection", s.projection)
      .numbers("original", s.original)
      .text("convention", convention_name(s.convention))
      .text("buffer", std::string(depth_buffer_name(s.buffer)))
      .numbers("ndc", Eigen::Matrix<T, 1, 2>(s.ndc_x, s.ndc_y))
      .number("depth", s.depth)
      .number("stored", static_cast<double>(s.stored));
  return r;
}

}  // namespace

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
          return vector3(s->ask(depth_request(kind, sample), kind, 3, 3));
        };
        break;
      case ConsumerKind::linear_depth:
        c.linear_depth = [s, kind](const properties::DepthSample<T>& sample) {
          return s->ask(depth_request(kind, sample), kind, 1, 1).front();
        };
        break;
      case ConsumerKind::culling_planes:
        c.culling_planes = [s, kind](const Matrix4<T>& m, Convention convention) {
          ConsumerRequest r(kind);
          r.numbers("projection", m).text("convention", convention_name(convention));
          const std::vector<T> v = s->ask(r, kind, 24, 4);
          FrustumPlanes<T> p;
          p.left = vector4(v, 0);
          p.right = vector4(v, 4);
          p.bottom = vector4(v, 8);
          p.top = vector4(v, 12);
          p.near_plane = vector4(v, 16);
          p.far_plane = vector4(v, 20);
          return p;
        };
        break;
      case ConsumerKind::camera_plane:
        c.camera_plane = [s, kind](const Matrix4<T>& view, const Vector4<T>& plane) {
          ConsumerRequest r(kind);
          r.numbers("view", view).numbers("plane", plane);
          return vector4(s->ask(r, kind, 4, 4));
        };
        break;
      case ConsumerKind::mirror_view:
        c.mirror_view = [s, kind](const Matrix4<T>& view, const Vector4<T>& plane) {
          ConsumerRequest r(kind);
          r.numbers("view", view).numbers("plane", plane);
          return matrix4(s->ask(r, kind, 16, 16));
        };
        break;
      case ConsumerKind::portal_view:
        c.portal_view = [s, kind](const Matrix4<T>& view, const Matrix4<T>& frame,
                                  const Matrix4<T>& linked) {
          ConsumerRequest r(kind);
          r.numbers("view", view).numbers("frame", frame).numbers("linked", linked);
          return matrix4(s->ask(r, kind, 16, 16));
        };
        break;
      case ConsumerKind::corners:
        c.corners = [s, kind](const Matrix4<T>& m, const Matrix4<T>& original,
                              Convention convention) {
          ConsumerRequest r(kind);
          r.numbers("projection", m)
              .numbers("original", original)
              .text("convention", convention_name(convention));
          const std::vector<T> v = s->ask(r, kind, 0, 3);
          std::vector<Vector3<T>> points;
          for (std::size_t i = 0; i < v.size(); i += 3) points.push_back(vector3(v, i));
          return points;
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
