// A user's program that answers the consumer request kinds (oblique/protocol/consumer_messages.h)
// as an oblique::Consumers<T>: each function of consumers() writes one request line (a Failure
// thrown when it gets no answer to judge) to the program and reads its one answer line, so every
// tool that checks a Consumers (the consumer round of oblique/oracle/consumers.h) checks the
// program the same way; or a batch of a round's asks at once (answer()). Used by `oblique verify
// --consumers` (batches) and `oblique check
// --impl` on a scene with consumers (one request at a time).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "oblique/client/program.h"
#include "oblique/oracle/consumers.h"
#include "oblique/protocol/consumer_messages.h"

namespace oblique::client {

using oracle::ConsumerAsk;

template <class T>
class ConsumerProgram {
 public:
  /// `command` runs under /bin/sh -c when first asked; each answer may take `timeout`.
  ConsumerProgram(std::string command, std::chrono::milliseconds timeout,
                  protocol::MatrixOrder order = protocol::MatrixOrder::rows);
  ~ConsumerProgram();
  ConsumerProgram(const ConsumerProgram&) = delete;
  ConsumerProgram& operator=(const ConsumerProgram&) = delete;

  /// The functions of `kinds`, named `name`; the others are empty (not asked).
  Consumers<T> consumers(const std::vector<protocol::ConsumerKind>& kinds,
                         const std::string& name) const;

  /// A batch's answers: one line per request, in order, up to the first request that got none
  /// or whose line is not its kind's answer (`failure` then says why, its request that one); the
  /// answers before it are to be judged.
  struct Batch {
    std::vector<std::string> requests;    ///< the request lines, one per ask
    std::vector<std::string> lines;       ///< the answer lines, as read
    std::vector<std::vector<T>> numbers;  ///< each line's numbers (read_consumer_answer())
    std::optional<Failure> failure;
  };
  /// Writes the request lines of `asks` at once and reads one answer line for each, in order:
  /// each may take the timeout after the one before it (reads and writes interleave, so a long
  /// batch cannot deadlock). Lines beyond the batch's answers fail it as a whole (nothing read
  /// can be matched to its request).
  Batch answer(const std::vector<const ConsumerAsk<T>*>& asks);

  /// The last request written and the answer line read for it (empty before the first).
  const std::string& last_request() const;
  const std::string& last_answer() const;

  /// Stops the program (and its process group).
  void stop();

  /// The count check that ends a conversation: closes the program's input, reads what it still
  /// writes (waiting at most the smaller of its timeout and a second) and stops it. Returns the
  /// lines beyond the one answer per request: when there are any, the answers were out of step
  /// with the requests and what was judged was another request's answer.
  std::vector<std::string> finish();

  /// Answer lines read so far.
  long answered() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace oblique::client
