// An implementation under test, run as a child process that speaks JSON Lines on its standard
// input and output. Reads and writes are interleaved with poll(), so a large batch of requests
// cannot deadlock against a child that answers while it reads, and every wait has a deadline.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/expected.h"
#include "oblique/protocol/shell_text.h"

namespace oblique::protocol {

using Clock = std::chrono::steady_clock;

class ChildProcess {
 public:
  /// `command` runs under /bin/sh -c, in its own process group.
  explicit ChildProcess(std::string command);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Starts the command, or says why it cannot be started.
  Expected<Done> start();
  bool running() const { return pid_ > 0; }

  enum class Outcome {
    done,       ///< every requested line was read
    exited,     ///< the child closed its output or exited first
    timed_out,  ///< no new line within the idle timeout, or the deadline passed
    too_long,   ///< a line grew beyond kMaxLineBytes (its start is in overlong_start())
  };

  /// The longest answer line read: a longer one is not buffered whole (memory per line is
  /// bounded) but reported as Outcome::too_long.
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

  /// Queues `input` for the child's standard input; it is written while exchange() waits.
  void send(std::string_view input) { unwritten_.append(input); }

  /// Writes what is queued plus `input`, and reads until `lines` holds `want` lines. Waits at
  /// most `idle` for each new line and never past `deadline`. Lines keep no trailing newline (nor
  /// '\r'). Queued input not yet taken by the child stays queued for the next call.
  Outcome exchange(std::string_view input, std::size_t want, std::vector<std::string>& lines,
                   std::chrono::milliseconds idle, Clock::time_point deadline);

  /// Kills the process group (if still running) and reaps the child; descendants that left the
  /// group (setsid) and were orphaned to us (we are their subreaper) are killed too.
  void stop();

  /// Output the child wrote beyond the lines asked for: complete or partial lines already read,
  /// plus whatever its standard output holds right now (no waiting). Each line at most 400 bytes.
  std::vector<std::string> unasked_output();

  /// Closes the child's standard input and reads what it still writes until it closes its output,
  /// at most until `until`: the lines beyond those asked for (a count check at the end of a run).
  std::vector<std::string> close_and_drain(Clock::time_point until);

  /// For a program that is run once, not asked: closes its standard input and collects its
  /// standard output (the first `keep` bytes in `output`) until it has exited, then ends what it
  /// left behind (its process group, and descendants that left it), so output a descendant holds
  /// open cannot keep us waiting. At `deadline` the whole group is killed and timed_out returned.
  /// `status` is the exit status as a shell gives it (128 + the signal's number when killed).
  Outcome run_to_end(std::string& output, std::size_t keep, Clock::time_point deadline,
                     int& status);

  /// When the child last completed an answer line (or was started).
  Clock::time_point last_line_time() const { return last_line_; }

  /// The first bytes of a line that grew beyond kMaxLineBytes.
  const std::string& overlong_start() const { return overlong_; }

  /// How the child ended, once it has: "exited with status 3", "killed by signal 11 (SIGSEGV)".
  std::string end_description();

  /// The last few kilobytes the child wrote to its standard error, as bytes (any encoding, cut
  /// anywhere): escape them before printing (escape_bytes()).
  const std::string& stderr_tail() const { return stderr_tail_; }

 private:
  void close_fds();
  bool reap(bool wait);
  void keep_stderr(const char* data, std::size_t size);
  bool read_output(char* buffer, std::size_t size);

  std::string command_;
  pid_t pid_ = -1;
  int in_ = -1, out_ = -1, err_ = -1;  // our ends: child's stdin, stdout, stderr
  std::string pending_;                // a partial line read from stdout
  std::string unwritten_;              // queued input the child has not taken yet
  std::size_t written_ = 0;            // how much of unwritten_ it has taken
  std::string stderr_tail_;
  std::string overlong_;
  Clock::time_point last_line_{};
  int wait_status_ = 0;
  bool reaped_ = false;
};

}  // namespace oblique::protocol
