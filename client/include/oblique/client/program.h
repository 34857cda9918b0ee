// A user's program asked over its standard input and output: request lines written, one answer
// line read for each, in order (the matrix protocol of `oblique apply`, the consumer request
// kinds). The one client of every tool that asks a program: verify, check --impl, report accuracy
// and the consumer checks. It starts the program when first asked, writes while it reads (a long
// batch cannot deadlock), and says why a request got no answer as a typed failure: the program
// crashed, timed out, or wrote what is not one answer line per request.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/expected.h"
#include "oblique/protocol/matrix_order.h"

namespace oblique::client {

using Clock = std::chrono::steady_clock;

/// The longest answer line read: a longer one is not buffered whole (memory per line is bounded)
/// but fails its exchange (Failure::Cause::overlong).
inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

/// Why a request got no answer to judge.
struct Failure {
  enum class Kind {
    crash,     ///< the program exited or closed its output
    timeout,   ///< no answer within the timeout
    protocol,  ///< what it wrote is not one answer line per request, or it could not be run
  };
  enum class Cause {
    exited,         ///< crash: it ended before answering
    timed_out,      ///< timeout
    cannot_start,   ///< protocol: no process could be started (pipes, fork)
    cannot_run,     ///< protocol: the shell could not run the command (126, 127), nothing asked
    left_over,      ///< protocol: lines written before the request, beyond the answers before
    beyond,         ///< protocol: lines beyond one answer per request, after the last
    overlong,       ///< protocol: a line that grew beyond kMaxLineBytes
    not_an_answer,  ///< protocol: a line that is not an answer of its request's kind
  };
  Cause cause = Cause::not_an_answer;
  /// The kind its cause is: exited a crash, timed_out a timeout, every other cause protocol.
  Kind kind() const {
    return cause == Cause::exited      ? Kind::crash
           : cause == Cause::timed_out ? Kind::timeout
                                       : Kind::protocol;
  }
  std::string what;     ///< in words, with how the program ended and its standard error's end
  std::string request;  ///< the request line that got no answer (or the last of a batch)
  /// What was read of it: the extra lines (left_over, beyond), the start of an overlong line,
  /// the line that is not an answer.
  std::vector<std::string> lines;
  /// How the program ended ("exited with status 3", "killed by signal 11 (SIGSEGV)"): crashes.
  std::string ended;
  /// The last bytes of its standard error, escaped (protocol::escape_bytes()), without the
  /// trailing line end.
  std::string stderr_tail;
};

/// What an exchange read: one answer line per request, in order, up to the first request that
/// got none (`failure` then says why; its request is that one). After a `beyond` failure the
/// lines read are kept but none can be matched to its request.
struct Reply {
  std::vector<std::string> lines;
  std::optional<Failure> failure;
  bool ok() const { return !failure; }
};

class Program {
 public:
  /// `command` runs under /bin/sh -c when first asked; each answer line may take `timeout`
  /// after the one before it. `order`: how it takes and writes the matrices of the lines (the
  /// lines given and returned here are in the protocol's own order, M by rows).
  Program(std::string command, std::chrono::milliseconds timeout,
          protocol::MatrixOrder order = protocol::MatrixOrder::rows);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// Writes `requests` (one line each) and reads one answer line for each, every line within
  /// the timeout of the one before, never past `deadline`. Before writing: the program is started
  /// when it is not running, and output left from before fails the exchange (protocol). After
  /// reading: lines beyond these answers fail it as a whole (Cause::beyond: nothing read can be
  /// matched to its request).
  Reply ask(const std::vector<std::string>& requests,
            Clock::time_point deadline = Clock::time_point::max());
  Reply ask(const std::string& request, Clock::time_point deadline = Clock::time_point::max());

  /// The pipeline (`oblique verify`'s matrix requests): start() once, queue() the requests of a
  /// batch, and read() their answers while the next batch is queued; finish() at the end.
  Expected<Done> start();
  /// Queues request text (lines, each ending in '\n') to be written while a later read() waits.
  void queue(std::string_view text);
  /// Reads answer lines of what was queued into `lines` until it holds `count` (lines already
  /// there count), each within the timeout of the one before, never past `deadline`. The failure,
  /// when not every line came: `request` is left empty (the caller knows which request the next
  /// line answers); a wait the deadline ended is a timeout too (compare the clock with the
  /// deadline).
  std::optional<Failure> read(std::size_t count, std::vector<std::string>& lines,
                              Clock::time_point deadline);

  /// The count check that ends a conversation: closes the program's input, reads what it still
  /// writes (waiting at most the smaller of its timeout and a second) and stops it. Returns the
  /// lines beyond the one answer per request: when there are any, the answers were out of step
  /// with the requests and what was judged was another request's answer.
  std::vector<std::string> finish();

  /// Stops the program (and its process group); the next ask() starts a fresh one.
  void stop();
  bool running() const;

  /// Answer lines read so far (over every start).
  long answered() const;
  /// The first bytes of the line that made a `too long` failure.
  const std::string& overlong_start() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// A program run once, not asked (a fuzz target on one input): its standard input closed, its
/// standard output collected (the first `keep` bytes in `output`) until it has exited, then what
/// it left behind ended, so output a descendant holds open cannot keep us waiting. At `deadline`
/// its whole process group is killed.
struct Run {
  bool started = true;  ///< false: no process could be started
  bool timed_out = false;
  std::string output;
  /// The exit status as a shell gives it (128 + the signal's number when killed).
  int status = 0;
};
Run run_once(const std::string& command, std::size_t keep, Clock::time_point deadline);

}  // namespace oblique::client
