// oblique verify's confirm-and-shrink: a finding in a batch is confirmed by sending its request
// alone, then shrunk through the implementation to a small case and reported; a process that
// stops answering inside a batch has the request that does it alone found. Internal to
// oblique::verify.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "batches.h"
#include "cases.h"
#include "reporter.h"
#include "session.h"

namespace oblique::verify {

template <class T>
class Shrinker {
 public:
  Shrinker(Session<T>& session, Reporter<T>& reporter, std::ostream& out, std::ostream& err)
      : session_(session), reporter_(reporter), out_(out), err_(err) {}

  /// Case k of a batch was found violating: confirmed alone (a fresh process) and shrunk, or a
  /// protocol error when alone it holds (the answers were out of step with the requests).
  Verdict confirm(const Batch<T>& batch, std::size_t k, const std::vector<std::string>& answers,
                  Found<T> finding, long cases_run);
  /// Shrinks a confirmed finding through the implementation and reports it (violated), or
  /// reports a protocol error met on the way (error).
  Verdict shrink(const rc::Shrinkable<cases::Case<T>>& failing, Found<T> finding, long cases_run);
  /// The implementation stopped answering after `answered` cases of the batch: the request that
  /// does it alone is found and shrunk.
  Verdict isolate(const std::vector<rc::Shrinkable<cases::Case<T>>>& cases, std::size_t answered,
                  long done, const client::Failure& failure);

 private:
  /// Which known mistake explains the shrunk case's answer, with the diagnosis's panel of cases
  /// (those the contract promises) asked too.
  mistakes::Diagnosis diagnose(const cases::Case<T>& shrunk, const Found<T>& finding);

  Session<T>& session_;
  Reporter<T>& reporter_;
  std::ostream& out_;
  std::ostream& err_;
};

}  // namespace oblique::verify
