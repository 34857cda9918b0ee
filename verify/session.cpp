#include "session.h"

#include <algorithm>

namespace oblique::verify {

template <class T>
Session<T>::Session(const VerifyOptions& options, const Draws<T>& draws)
    : options_(options),
      draws_(draws),
      child_(options.command),
      idle_(static_cast<long>(options.request_timeout_seconds * 1000)) {
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
typename Session<T>::Evaluation Session<T>::evaluate(const generators::Case<T>& v,
                                                     Found<T>& finding) {
  last_answer_.reset();
  if (out_of_time()) return Evaluation::out_of_time;
  const properties::FilteredProblem<T> problem(v.matrix, v.plane, v.convention);
  if (draws_.needs_status() && !draws_.left_out(problem).empty())
    return Evaluation::pass;  // not an input the implementation promises anything for
  issue_ = Issue{};
  if (!child_.running()) {
    if (const Expected<Done> started = child_.start(); !started) {
      issue_.what = "the implementation could not be restarted: " + started.error();
      return Evaluation::protocol_error;
    }
  }
  // The count check of one evaluation: nothing left over before the request, one line after.
  if (std::vector<std::string> left = child_.unasked_output(); !left.empty()) {
    issue_ = Issue{"lines beyond the one answer to this request", last_request_, left};
    return Evaluation::protocol_error;
  }
  const std::string request = request_text(v);
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
    if (out_of_time()) return Evaluation::out_of_time;
    finding = lost_finding(outcome);
    child_.stop();
    return Evaluation::finding;
  }
  if (std::vector<std::string> extra = child_.unasked_output(); !extra.empty()) {
    extra.insert(extra.begin(), answers[0]);
    issue_ = Issue{"lines beyond the one answer to this request", request, extra};
    return Evaluation::protocol_error;
  }
  const Expected<protocol::TypedAnswer<T>> answered = protocol::read_answer<T>(answers[0]);
  if (!answered) {
    issue_ = Issue{"an answer that is not an answer of the protocol (" + answered.error() + ")",
                   request,
                   {answers[0]}};
    return Evaluation::protocol_error;
  }
  last_answer_ = *answered;
  auto judged = judge(problem, *answered, draws_.checks());
  if (!judged) return Evaluation::pass;
  finding = *judged;
  finding.answer_line = answers[0];
  return Evaluation::finding;
}

template <class T>
std::optional<properties::Observation<T>> Session<T>::observe(const generators::Case<T>& v) {
  Found<T> found;
  const Evaluation e = evaluate(v, found);
  if (!last_answer_ || (e != Evaluation::pass && e != Evaluation::finding)) return std::nullopt;
  return properties::Observation<T>{v.matrix,
                                    v.plane,
                                    v.convention,
                                    last_answer_->status,
                                    last_answer_->projection,
                                    e == Evaluation::finding};
}

template <class T>
Found<T> Session<T>::lost_finding(ChildProcess::Outcome outcome) {
  Found<T> found;
  properties::Finding& f = found.finding;
  f.shows = properties::Shows::program;
  if (outcome == ChildProcess::Outcome::exited) {
    f.check = properties::Check::crash;
    found.process = child_.end_description();
    f.message = "it " + found.process + " before answering";
  } else {
    f.check = properties::Check::timeout;
    f.bound = options_.request_timeout_seconds;
    found.process = "no answer line";
    f.message =
        "no answer within the timeout: it hangs on this request, or does not flush its "
        "standard output after each answer line";
  }
  found.answer_line =
      child_.stderr_tail().empty() ? "" : "(stderr) " + escape_bytes(child_.stderr_tail());
  return found;
}

template class Session<float>;
template class Session<double>;

}  // namespace oblique::verify
