#include "oblique/client/consumer_program.h"

#include "oblique/oracle/consumer_wire.h"

namespace oblique::client {

using protocol::ConsumerKind;
using protocol::ConsumerRequest;
namespace wire = oracle::wire;

template <class T>
struct ConsumerProgram<T>::State {
  Program program;
  std::string request, answer;

  State(std::string command, std::chrono::milliseconds t, protocol::MatrixOrder order)
      : program(std::move(command), t, order) {}

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

  /// Sends `r` and reads the numbers of its answer (read_consumer_answer()); throws the Failure
  /// when it gets none to judge.
  std::vector<T> ask(const ConsumerRequest& r, ConsumerKind kind) {
    request = r.line();
    answer.clear();
    Reply reply = program.ask(request);
    if (reply.failure) {
      // Beyond the one answer: the answer first, then what followed it.
      if (reply.failure->cause == Failure::Cause::beyond)
        reply.failure->lines.insert(reply.failure->lines.begin(), reply.lines.front());
      throw *reply.failure;
    }
    answer = reply.lines.front();
    const Expected<std::vector<T>> numbers = read_answer(answer, kind);
    if (!numbers) {
      Failure f;
      f.cause = Failure::Cause::not_an_answer;
      f.what = numbers.error();
      f.request = request;
      f.lines = {answer};
      throw f;
    }
    return *numbers;
  }
};

template <class T>
typename ConsumerProgram<T>::Batch ConsumerProgram<T>::answer(
    const std::vector<const ConsumerAsk<T>*>& asks) {
  State& s = *state_;
  Batch out;
  if (asks.empty()) return out;
  for (const ConsumerAsk<T>* a : asks) out.requests.push_back(a->request().line());
  s.request = out.requests.front();
  s.answer.clear();
  Reply reply = s.program.ask(out.requests);
  out.lines = std::move(reply.lines);
  if (reply.failure) {
    s.request = reply.failure->request;
    // Beyond one answer per request: none of the lines can be matched to its request.
    if (reply.failure->cause == Failure::Cause::beyond) out.lines.clear();
    out.failure = std::move(reply.failure);
  }
  for (std::size_t i = 0; i < out.lines.size(); ++i) {
    const Expected<std::vector<T>> numbers = s.read_answer(out.lines[i], asks[i]->kind);
    if (!numbers) {
      s.request = out.requests[i];
      Failure f;
      f.cause = Failure::Cause::not_an_answer;
      f.what = numbers.error();
      f.request = out.requests[i];
      f.lines = {out.lines[i]};
      out.failure = std::move(f);
      break;
    }
    out.numbers.push_back(*numbers);
  }
  out.lines.resize(out.numbers.size());
  if (!out.lines.empty()) s.answer = out.lines.back();
  return out;
}

template <class T>
ConsumerProgram<T>::ConsumerProgram(std::string command, std::chrono::milliseconds timeout,
                                    protocol::MatrixOrder order)
    : state_(std::make_unique<State>(std::move(command), timeout, order)) {}

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
  state_->program.stop();
}

template <class T>
std::vector<std::string> ConsumerProgram<T>::finish() {
  return state_->program.finish();
}

template <class T>
long ConsumerProgram<T>::answered() const {
  return state_->program.answered();
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
        c.view_position = [s, kind](const oracle::DepthSample<T>& sample) {
          return wire::vector3(s->ask(wire::depth_request(kind, sample), kind));
        };
        break;
      case ConsumerKind::world_position:
        c.world_position = [s, kind](const oracle::DepthSample<T>& sample) {
          return wire::vector3(s->ask(wire::depth_request(kind, sample), kind));
        };
        break;
      case ConsumerKind::linear_depth:
        c.linear_depth = [s, kind](const oracle::DepthSample<T>& sample) {
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

}  // namespace oblique::client
