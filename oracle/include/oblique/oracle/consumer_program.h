// A user's program that answers the consumer request kinds (oblique/protocol/consumer_messages.h)
// as an oblique::Consumers<T>: each function of consumers() writes one request line to the
// program and reads its one answer line, so every tool that checks a Consumers (the consumer
// round of oblique/oracle/consumers.h) checks the program the same way. Used by
// `oblique verify --consumers` and `oblique check --impl` on a scene with consumers.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "oblique/oracle/consumers.h"
#include "oblique/protocol/consumer_messages.h"

namespace oblique::properties {

/// Why a request got no answer to judge; thrown by the functions of ConsumerProgram::consumers().
struct ProgramFailure {
  enum class Kind {
    crash,     ///< the program exited or closed its output
    timeout,   ///< no answer within the timeout
    protocol,  ///< the line is not an answer of its kind, or lines beyond the one answer
  };
  Kind kind = Kind::protocol;
  std::string what;     ///< in words, with how the program ended and its standard error's end
  std::string request;  ///< the request line
  std::vector<std::string> lines;  ///< what was read
};

template <class T>
class ConsumerProgram {
 public:
  /// `command` runs under /bin/sh -c when first asked; each answer may take `timeout`.
  ConsumerProgram(std::string command, std::chrono::milliseconds timeout);
  ~ConsumerProgram();
  ConsumerProgram(const ConsumerProgram&) = delete;
  ConsumerProgram& operator=(const ConsumerProgram&) = delete;

  /// The functions of `kinds`, named `name`; the others are empty (not asked).
  Consumers<T> consumers(const std::vector<protocol::ConsumerKind>& kinds,
                         const std::string& name) const;

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

}  // namespace oblique::properties
