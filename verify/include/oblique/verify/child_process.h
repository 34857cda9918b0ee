// An implementation under test, run as a child process that speaks JSON Lines on its standard
// input and output. Reads and writes are interleaved with poll(), so a large batch of requests
// cannot deadlock against a child that answers while it reads, and every wait has a deadline.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <string_view>
#include <vector>

namespace oblique::verify {

using Clock = std::chrono::steady_clock;

class ChildProcess {
 public:
  /// `command` runs under /bin/sh -c, in its own process group.
  explicit ChildProcess(std::string command);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Starts the command; false (with `error`) when it cannot be started.
  bool start(std::string* error);
  bool running() const { return pid_ > 0; }

  enum class Outcome {
    done,       ///< every requested line was read
    exited,     ///< the child closed its output or exited first
    timed_out,  ///< no new line within the idle timeout, or the deadline passed
  };

  /// Queues `input` for the child's standard input; it is written while exchange() waits.
  void send(std::string_view input) { unwritten_.append(input); }

  /// Writes what is queued plus `input`, and reads until `lines` holds `want` lines. Waits at
  /// most `idle` for each new line and never past `deadline`. Lines keep no trailing newline (nor
  /// '\r'). Queued input not yet taken by the child stays queued for the next call.
  Outcome exchange(std::string_view input, std::size_t want, std::vector<std::string>& lines,
                   std::chrono::milliseconds idle, Clock::time_point deadline);

  /// Kills the process group (if still running) and reaps the child.
  void stop();

  /// How the child ended, once it has: "exited with status 3", "killed by signal 11 (SIGSEGV)".
  std::string end_description();

  /// The last few kilobytes the child wrote to its standard error.
  const std::string& stderr_tail() const { return stderr_tail_; }

 private:
  void close_fds();
  bool reap(bool wait);
  void keep_stderr(const char* data, std::size_t size);

  std::string command_;
  pid_t pid_ = -1;
  int in_ = -1, out_ = -1, err_ = -1;  // our ends: child's stdin, stdout, stderr
  std::string pending_;                // a partial line read from stdout
  std::string unwritten_;              // queued input the child has not taken yet
  std::size_t written_ = 0;            // how much of unwritten_ it has taken
  std::string stderr_tail_;
  int wait_status_ = 0;
  bool reaped_ = false;
};

}  // namespace oblique::verify
