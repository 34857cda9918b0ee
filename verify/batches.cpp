#include "batches.h"

#include <algorithm>
#include <future>

namespace oblique::verify {

template <class T>
std::string Batch<T>::text() const {
  std::string out;
  for (const std::string& r : requests) {
    out += r;
    out += '\n';
  }
  return out;
}

template <class T>
Batch<T> draw_batch(const Draws<T>& draws, rc::Random& random, std::size_t size,
                    run::Tally& tally) {
  Batch<T> b;
  for (std::size_t k = 0, tries = 0; k < size && tries < 64 * size + 64; ++tries) {
    rc::Shrinkable<cases::Case<T>> drawn =
        draws.generator()(random.split(), static_cast<int>(tries % 101));
    cases::Case<T> value = drawn.value();
    if (draws.needs_status()) {
      auto problem =
          std::make_unique<oracle::FilteredProblem<T>>(value.matrix, value.plane, value.convention);
      if (const std::string why = draws.left_out(*problem); !why.empty()) {
        // No answer, and no status of the contract's for it: outside what it claims.
        tally.left_out(run::kinds_of(value), why, problem->exact_status() == Status::ok);
        continue;
      }
      b.problems.push_back(std::move(problem));
    } else {
      b.problems.push_back(nullptr);
    }
    ++k;
    b.cases.push_back(std::move(drawn));
    b.values.push_back(std::move(value));
    b.requests.push_back(request_text(b.values.back()));
  }
  return b;
}

void in_slices(std::size_t count, int threads,
               const std::function<void(std::size_t, std::size_t)>& work, std::size_t min_slice) {
  const std::size_t slices = std::max<std::size_t>(
      1, std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count / min_slice));
  const std::size_t size = (count + slices - 1) / slices;
  std::vector<std::future<void>> others;
  for (std::size_t i = 1; i < slices; ++i)
    others.push_back(
        std::async(std::launch::async, work, i * size, std::min(count, (i + 1) * size)));
  work(0, std::min(count, size));
  for (auto& other : others) other.get();
}

template <class T>
std::vector<Judged<T>> judge_batch(const Draws<T>& draws, const Batch<T>& b,
                                   const std::vector<std::string>& answers, int threads) {
  std::vector<Judged<T>> out(answers.size());
  auto judge_range = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) {
      const Expected<Answer<T>> answered = protocol::read_answer<T>(answers[k]);
      if (!answered) {
        out[k].protocol_error = answered.error();
        continue;
      }
      const cases::Case<T>& v = b.values[k];
      if (b.problems[k]) {
        out[k].finding = judge_answer(*b.problems[k], *answered, draws.checks());
      } else {
        const oracle::FilteredProblem<T> problem(v.matrix, v.plane, v.convention);
        out[k].finding = judge_answer(problem, *answered, draws.checks());
      }
    }
  };
  in_slices(answers.size(), threads, judge_range);
  return out;
}

#define OBLIQUE_VERIFY_BATCHES(T)                                                          \
  template struct Batch<T>;                                                                \
  template Batch<T> draw_batch<T>(const Draws<T>&, rc::Random&, std::size_t, run::Tally&); \
  template std::vector<Judged<T>> judge_batch<T>(const Draws<T>&, const Batch<T>&,         \
                                                 const std::vector<std::string>&, int);
OBLIQUE_VERIFY_BATCHES(float)
OBLIQUE_VERIFY_BATCHES(double)
#undef OBLIQUE_VERIFY_BATCHES

}  // namespace oblique::verify
