#include "shrinker.h"

#include <algorithm>
#include <ostream>

namespace oblique::verify {

template <class T>
Verdict Shrinker<T>::confirm(const Batch<T>& batch, std::size_t k,
                             const std::vector<std::string>& answers, Found<T> finding,
                             long cases_run) {
  using Evaluation = typename Session<T>::Evaluation;
  session_.program().stop();
  Found<T> alone;
  switch (session_.evaluate(batch.values[k], alone)) {
    case Evaluation::finding: finding = alone; break;
    case Evaluation::out_of_time: break;  // reported as found in the batch
    case Evaluation::protocol_error:
      session_.program().stop();
      return reporter_.issue(session_.issue());
    case Evaluation::pass: {
      std::vector<std::string> lines;
      const std::size_t from = k >= 2 ? k - 2 : 0;
      for (std::size_t i = from; i < std::min(answers.size(), k + 3); ++i)
        lines.push_back("answer " + std::to_string(i + 1) + (i == k ? " (judged)" : "") + ": " +
                        answers[i]);
      session_.program().stop();
      return reporter_.count_error(
          "answer " + std::to_string(k + 1) + " of a batch violates " +
              std::string(check_name(finding.finding.check)) +
              ", but the same request sent alone is answered without a violation: the answers "
              "are out of step with the requests (an extra or a missing answer line before "
              "it), or an answer depends on earlier requests",
          {batch.requests[k]}, lines);
    }
  }
  return shrink(batch.cases[k], finding, cases_run);
}

template <class T>
Verdict Shrinker<T>::shrink(const rc::Shrinkable<cases::Case<T>>& failing, Found<T> finding,
                            long cases_run) {
  using Evaluation = typename Session<T>::Evaluation;
  const long found_after_cases = cases_run;
  const double found_after_seconds = session_.seconds_since_start();
  session_.program().stop();  // it may still be working on the next batch; shrinking restarts it
  out_ << "oblique verify: " << check_name(finding.finding.check) << " violated after " << cases_run
       << " cases; shrinking";
  out_.flush();
  rc::Shrinkable<cases::Case<T>> current = failing;
  int steps = 0, tries = 0;
  bool out_of_time = false;
  // Timeouts cost the whole timeout per try: the case is reported as found.
  bool progress = finding.finding.check != oracle::Check::timeout;
  while (progress && !out_of_time) {
    progress = false;
    auto shrinks = current.shrinks();
    while (auto next = shrinks.next()) {
      Found<T> candidate;
      ++tries;
      const Evaluation e = session_.evaluate(next->value(), candidate);
      if (e == Evaluation::out_of_time) {
        out_of_time = true;
        break;
      }
      if (e == Evaluation::protocol_error) {
        out_ << "\n";
        session_.program().stop();
        return reporter_.issue(session_.issue());
      }
      if (e == Evaluation::finding && candidate.finding.check == finding.finding.check) {
        current = *next;
        finding = candidate;
        ++steps;
        progress = true;
        if (steps % 10 == 0) (out_ << ".").flush();
        break;
      }
    }
  }
  out_ << " " << steps << " steps (" << tries << " tries)"
       << (out_of_time ? ", stopped by the time limit" : "") << "\n";
  const mistakes::Diagnosis diagnosis = diagnose(current.value(), finding);
  session_.program().stop();
  return reporter_.finding(current.value(), finding, steps, out_of_time, found_after_cases,
                           found_after_seconds, diagnosis);
}

template <class T>
mistakes::Diagnosis Shrinker<T>::diagnose(const cases::Case<T>& shrunk, const Found<T>& finding) {
  using oracle::Check;
  const Check check = finding.finding.check;
  if (check == Check::crash || check == Check::timeout || check == Check::protocol) return {};
  // The shrunk case's answer as judged: a matrix, or (a status finding) the refusal.
  const mistakes::Observation<T> seen{shrunk.matrix,
                                      shrunk.plane,
                                      shrunk.convention,
                                      finding.result ? Status::ok : finding.finding.answered,
                                      finding.result ? *finding.result : shrunk.matrix,
                                      true,
                                      shrunk.family};
  const auto& families = session_.draws().contract().families;
  const auto& conventions = session_.draws().contract().conventions;
  // A probe the implementation does not answer (it crashed, hung or broke the protocol) ends the
  // probing: each further one would cost a restart or the whole --timeout.
  bool answering = true;
  // Said (and flushed) first: a slow implementation takes a while over the panel.
  (out_ << "oblique verify: diagnosing the likely cause (asking the implementation up to "
        << mistakes::kPanelCasesPerConvention * static_cast<int>(conventions.size())
        << " more cases)\n")
      .flush();
  const mistakes::Probe<T> probe = [this, &families, &conventions, &answering](
                                       const Matrix4<T>& m, const Vector4<T>& c,
                                       Convention convention, cases::Family family) {
    if (!answering || std::find(families.begin(), families.end(), family) == families.end() ||
        std::find(conventions.begin(), conventions.end(), convention) == conventions.end())
      return std::optional<mistakes::Observation<T>>();
    cases::Case<T> v;
    v.matrix = m;
    v.plane = c;
    v.convention = convention;
    v.family = family;
    std::optional<mistakes::Observation<T>> seen = session_.observe(v);
    if (!seen && (!session_.program().running() || !session_.issue().what.empty()))
      answering = false;
    return seen;
  };
  const std::optional<cases::StatusContract>& statuses = session_.draws().contract().statuses;
  return mistakes::diagnose<T>({seen}, probe,
                               statuses && *statuses == cases::StatusContract::answers_only);
}

template <class T>
Verdict Shrinker<T>::isolate(const std::vector<rc::Shrinkable<cases::Case<T>>>& cases,
                             std::size_t answered, long done, const client::Failure& failure) {
  using Evaluation = typename Session<T>::Evaluation;
  Found<T> in_batch = session_.lost_finding(failure);
  const bool hung = failure.kind() == client::Failure::Kind::timeout;
  const std::string description = hung ? "gave no answer within --timeout" : in_batch.process;
  const std::string& tail = failure.stderr_tail;
  session_.program().stop();
  bool every_one_answered = true;
  for (std::size_t k = answered; k < cases.size(); ++k) {
    Found<T> finding;
    switch (session_.evaluate(cases[k].value(), finding)) {
      case Evaluation::pass: continue;
      case Evaluation::finding: return shrink(cases[k], finding, done + 1);
      case Evaluation::protocol_error:
        session_.program().stop();
        return reporter_.issue(session_.issue());
      case Evaluation::out_of_time:
        if (k == answered) {
          in_batch.process += " (in a batch; not repeated alone within the time limit)";
          return shrink(cases[answered], in_batch, done + 1);
        }
        every_one_answered = false;
        k = cases.size();
        break;
    }
  }
  if (every_one_answered && hung) {
    session_.program().stop();
    return reporter_.count_error(
        "the implementation answered " + std::to_string(answered) + " of a batch's " +
            std::to_string(cases.size()) +
            " requests and then nothing within --timeout, yet each unanswered request alone gets "
            "its answer: an answer line is missing",
        {}, {});
  }
  err_ << "oblique verify: the implementation stopped answering after " << done << " cases (it "
       << description << "), and no single request of the batch repeats it"
       << (tail.empty() ? "" : "\n  its standard error ended with:\n" + tail) << "\n";
  return Verdict::violated;
}

template class Shrinker<float>;
template class Shrinker<double>;

}  // namespace oblique::verify
