#include "session.h"

#include <algorithm>

namespace oblique::verify {

template <class T>
Session<T>::Session(const VerifyOptions& options, const Draws<T>& draws)
    : options_(options),
      draws_(draws),
      idle_(static_cast<long>(options.request_timeout_seconds * 1000)),
      program_(options.command, idle_, options.matrix_order()) {
  start_clock();
}

template <class T>
void Session<T>::start_clock() {
  start_ = Clock::now();
  deadline_ = start_ + std::chrono::milliseconds(
                           static_cast<long>(std::max(0.0, options_.time_limit_seconds) * 1000));
}

template <class T>
double Session<T>::seconds_since_start() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

template <class T>
typename Session<T>::Evaluation Session<T>::evaluate(const cases::Case<T>& v, Found<T>& finding) {
  last_answer_.reset();
  if (out_of_time()) return Evaluation::out_of_time;
  const oracle::FilteredProblem<T> problem(v.matrix, v.plane, v.convention);
  if (draws_.needs_status() && !draws_.left_out(problem).empty())
    return Evaluation::pass;  // not an input the implementation promises anything for
  issue_ = Issue{};
  const std::string request = request_text(v);
  const std::string before = last_request_;
  last_request_ = request;
  // The count check of one evaluation (the client's): nothing left over before the request, one
  // line after.
  const client::Reply reply = program_.ask(request, deadline_);
  if (reply.failure) {
    using Cause = client::Failure::Cause;
    const client::Failure& f = *reply.failure;
    switch (f.cause) {
      case Cause::cannot_start:
        issue_.what = "the implementation could not be restarted: " + f.what;
        return Evaluation::protocol_error;
      case Cause::cannot_run:
        issue_ = Issue{"cannot run the implementation: " + f.what, request, {}};
        return Evaluation::protocol_error;
      case Cause::left_over:
        issue_ = Issue{"lines beyond the one answer to this request", before, f.lines};
        return Evaluation::protocol_error;
      case Cause::overlong:
        issue_ = Issue{"an answer line longer than 1 MiB (not read further)", request, f.lines};
        return Evaluation::protocol_error;
      case Cause::beyond: {
        std::vector<std::string> lines = f.lines;
        lines.insert(lines.begin(), reply.lines.front());
        issue_ = Issue{"lines beyond the one answer to this request", request, lines};
        return Evaluation::protocol_error;
      }
      case Cause::not_an_answer:  // (the client does not read answers; kept for completeness)
        issue_ = Issue{f.what, request, f.lines};
        return Evaluation::protocol_error;
      case Cause::exited:
      case Cause::timed_out:
        if (out_of_time()) return Evaluation::out_of_time;
        finding = lost_finding(f);
        program_.stop();
        return Evaluation::finding;
    }
  }
  const std::vector<std::string>& answers = reply.lines;
  const Expected<Answer<T>> answered = protocol::read_answer<T>(answers[0]);
  if (!answered) {
    issue_ = Issue{"an answer that is not an answer of the protocol (" + answered.error() + ")",
                   request,
                   {answers[0]}};
    return Evaluation::protocol_error;
  }
  last_answer_ = *answered;
  auto judged = judge_answer(problem, *answered, draws_.checks());
  if (!judged) return Evaluation::pass;
  finding = *judged;
  finding.answer_line = answers[0];
  return Evaluation::finding;
}

template <class T>
std::optional<mistakes::Observation<T>> Session<T>::observe(const cases::Case<T>& v) {
  Found<T> found;
  const Evaluation e = evaluate(v, found);
  if (!last_answer_ || (e != Evaluation::pass && e != Evaluation::finding)) return std::nullopt;
  return mistakes::Observation<T>{v.matrix,
                                  v.plane,
                                  v.convention,
                                  last_answer_->status,
                                  last_answer_->projection,
                                  e == Evaluation::finding,
                                  v.family};
}

template <class T>
Found<T> Session<T>::lost_finding(const client::Failure& failure) {
  Found<T> found;
  oracle::Finding& f = found.finding;
  f.shows = oracle::Shows::program;
  if (failure.kind() == client::Failure::Kind::crash) {
    f.check = oracle::Check::crash;
    found.process = failure.ended;
    f.message = "it " + found.process + " before answering";
  } else {
    f.check = oracle::Check::timeout;
    f.bound = options_.request_timeout_seconds;
    found.process = "no answer line";
    f.message =
        "no answer within the timeout: it hangs on this request, or does not flush its "
        "standard output after each answer line";
  }
  found.answer_line = failure.stderr_tail.empty() ? "" : "(stderr) " + failure.stderr_tail;
  return found;
}

template class Session<float>;
template class Session<double>;

}  // namespace oblique::verify
