// oblique verify's request pipeline: batches of generated cases drawn under the contract (what it
// leaves out counted, not sent), and a batch's answers read and judged on several threads.
// Internal to oblique::verify.
#pragma once

#include <rapidcheck.h>

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cases.h"

namespace oblique::verify {

/// Generated cases, their values and request lines, for the implementation.
template <class T>
struct Batch {
  std::vector<rc::Shrinkable<cases::Case<T>>> cases;
  std::vector<cases::Case<T>> values;
  std::vector<std::string> requests;
  /// The checker of each case, made when the contract needed it to decide what is sent.
  std::vector<std::unique_ptr<oracle::FilteredProblem<T>>> problems;

  /// The requests, one line each.
  std::string text() const;
};

/// Draws up to `size` cases the contract sends (at most 64 draws per case, then fewer); what it
/// leaves out is counted in `tally` (left out) by oracle::not_judged()'s reason and by its family.
template <class T>
Batch<T> draw_batch(const Draws<T>& draws, rc::Random& random, std::size_t size, run::Tally& tally);

/// One answer judged: a protocol error (the line is no answer), a finding, or neither.
template <class T>
struct Judged {
  std::string protocol_error;
  std::optional<Found<T>> finding;
};

/// work(from, to) over [0, count) in equal slices on up to `threads` threads (this one among
/// them), none smaller than `min_slice` items, below which a thread costs more than it saves.
void in_slices(std::size_t count, int threads,
               const std::function<void(std::size_t, std::size_t)>& work,
               std::size_t min_slice = 8);

/// Reads and judges each answer of the batch, in equal slices on up to `threads` threads (GMP
/// objects are not shared, and the values were taken out of their Shrinkables on this thread).
template <class T>
std::vector<Judged<T>> judge_batch(const Draws<T>& draws, const Batch<T>& batch,
                                   const std::vector<std::string>& answers, int threads);

}  // namespace oblique::verify
