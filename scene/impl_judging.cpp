// oblique check --impl: each rendered pass's request sent to the user's program (the apply
// protocol), and its answers judged as oblique verify judges them.
#include <algorithm>
#include <chrono>
#include <limits>

#include "oblique/client/program.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/protocol.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/scene/check.h"

namespace oblique::scene {

namespace {

/// The request's M and C in T (Eigen's cast: IEEE rounding, an infinity beyond T's range).
template <class T>
Matrix4<T> request_projection(const SurfaceCheck& pass) {
  static_assert(std::numeric_limits<T>::is_iec559);
  return pass.camera_projection.template cast<T>();
}
template <class T>
Vector4<T> request_plane(const SurfaceCheck& pass) {
  return pass.plane_in_camera.template cast<T>();
}

template <class T>
void judge_answer_in(const Scene& scene, SurfaceCheck& pass, const std::string& line) {
  pass.impl_answer = line;
  pass.impl_findings.clear();
  auto protocol_error = [&](const std::string& why) {
    oracle::Finding f;
    f.check = oracle::Check::protocol;
    f.shows = oracle::Shows::program;
    f.message = why;
    pass.impl_findings.push_back(f);
  };
  const Expected<Answer<T>> answer = protocol::read_answer<T>(line);
  if (!answer) return protocol_error(answer.error());
  const Answer<T> outcome{answer->status, answer->projection};
  const oracle::Problem<T> problem(request_projection<T>(pass), request_plane<T>(pass),
                                   scene.convention);
  cases::Checks checks;
  checks.statuses = cases::StatusContract::any_refusal;
  checks.row3_accuracy = true;
  // As verify: the judgement stops at the first violation (every = true would go on to the
  // properties after a non-finite answer, whose exact arithmetic cannot take infinities).
  pass.impl_findings = oracle::judge(problem, outcome, checks).checks;
}

/// The likely cause of the wrong answers among the passes' (every answer judged is a case).
template <class T>
mistakes::Diagnosis diagnose_in(const Scene& scene, const std::vector<SurfaceCheck*>& passes,
                                const std::vector<std::string>& lines) {
  std::vector<mistakes::Observation<T>> seen;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    const Expected<Answer<T>> answer = protocol::read_answer<T>(lines[i]);
    if (!answer) continue;
    mistakes::Observation<T> o{request_projection<T>(*passes[i]),
                               request_plane<T>(*passes[i]),
                               scene.convention,
                               answer->status,
                               answer->projection,
                               false,
                               std::nullopt};
    for (const oracle::Finding& f : passes[i]->impl_findings) o.wrong = o.wrong || !f.holds;
    seen.push_back(o);
  }
  return mistakes::diagnose<T>(seen);
}

}  // namespace

std::string impl_request(const Scene& scene, const SurfaceCheck& pass,
                         protocol::Precision precision) {
  switch (precision) {
    case protocol::Precision::float32:
      return protocol::request_line<float>(request_projection<float>(pass),
                                           request_plane<float>(pass), scene.convention);
    case protocol::Precision::float64: break;
    case protocol::Precision::long_double:
      return protocol::request_line<long double>(request_projection<long double>(pass),
                                                 request_plane<long double>(pass),
                                                 scene.convention);
  }
  return protocol::request_line<double>(request_projection<double>(pass),
                                        request_plane<double>(pass), scene.convention);
}

void judge_impl_answer(const Scene& scene, SurfaceCheck& pass, const std::string& line,
                       protocol::Precision precision) {
  switch (precision) {
    case protocol::Precision::float32: return judge_answer_in<float>(scene, pass, line);
    case protocol::Precision::float64: return judge_answer_in<double>(scene, pass, line);
    case protocol::Precision::long_double: return judge_answer_in<long double>(scene, pass, line);
  }
}

Expected<std::size_t> judge_implementation(const Scene& scene, SceneCheck& check,
                                           const std::string& command, double timeout_seconds) {
  std::vector<SurfaceCheck*> rendered;
  std::vector<std::string> requests;
  for (SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    rendered.push_back(&s);
    requests.push_back(impl_request(scene, s, check.impl_precision));
  }
  if (rendered.empty()) return std::size_t{0};
  const auto idle = std::chrono::milliseconds(static_cast<long>(timeout_seconds * 1000));
  client::Program program(command, idle, check.impl_order);
  const client::Reply reply = program.ask(requests, client::Clock::now() + 4 * idle);
  const std::vector<std::string>& lines = reply.lines;
  using Cause = client::Failure::Cause;
  if (reply.failure && reply.failure->cause == Cause::cannot_start)
    return Expected<std::size_t>::failure("cannot start the implementation (" +
                                          reply.failure->what + ")");
  // As verify: once its input is closed, a program that has answered every request has nothing
  // more to say; lines beyond one per request mean the answers were out of step (each would be
  // judged against another request's plane), a protocol error, not a finding.
  std::vector<std::string> extra = reply.ok() ? program.finish() : std::vector<std::string>{};
  if (reply.failure && reply.failure->cause == Cause::beyond) extra = reply.failure->lines;
  program.stop();
  if (reply.failure && reply.failure->cause != Cause::beyond) {
    const client::Failure& f = *reply.failure;
    const std::string ended = f.cause == Cause::timed_out  ? "timed out"
                              : f.cause == Cause::overlong ? "an answer line longer than 1 MiB"
                                                           : f.ended;
    std::string why = "the implementation answered " + std::to_string(lines.size()) + " of " +
                      std::to_string(rendered.size()) + " requests (" + ended + ")";
    if (!f.stderr_tail.empty()) why += "; its standard error:\n" + f.stderr_tail;
    return Expected<std::size_t>::failure(why);
  }
  if (!extra.empty()) {
    return Expected<std::size_t>::failure(
        "the implementation wrote lines beyond one answer per request (" +
        std::to_string(rendered.size()) + " requests; the first extra line: " +
        protocol::escape_bytes(extra.front().substr(0, 200)) + ")");
  }
  for (std::size_t i = 0; i < rendered.size(); ++i)
    judge_impl_answer(scene, *rendered[i], lines[i], check.impl_precision);
  switch (check.impl_precision) {
    case protocol::Precision::float32:
      check.impl_diagnosis = diagnose_in<float>(scene, rendered, lines);
      break;
    case protocol::Precision::float64:
      check.impl_diagnosis = diagnose_in<double>(scene, rendered, lines);
      break;
    case protocol::Precision::long_double:
      check.impl_diagnosis = diagnose_in<long double>(scene, rendered, lines);
      break;
  }
  return rendered.size();
}

}  // namespace oblique::scene
