// The child process behind every program the harness asks (protocol/child_process.h), under the
// ways programs misbehave: an answer that waits in the pipe while we are busy elsewhere is read,
// not called a hang; a program run once is ended with all it left behind, at its exit or at the
// time limit, whoever holds its output open.
#include "oblique/protocol/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace oblique::protocol {
namespace {

using namespace std::chrono_literals;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The time limit or the idle wait over before we ask (we were judging or drawing): what the pipe
// already holds is still read. It returned timed_out without looking, a false hang.
TEST(ChildProcess, anAnswerWaitingInThePipeIsReadAfterTheWaitIsOver) {
  ChildProcess child("echo 'an answer'; exec sleep 30");
  ASSERT_TRUE(child.start());
  std::this_thread::sleep_for(300ms);  // it answers while we are busy elsewhere
  std::vector<std::string> lines;
  EXPECT_EQ(child.exchange({}, 1, lines, 10ms, Clock::now() - 1s), ChildProcess::Outcome::done);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "an answer");
  // Nothing more waiting: the same call is a timeout, and it returns at once.
  const auto start = Clock::now();
  EXPECT_EQ(child.exchange({}, 2, lines, 10ms, Clock::now() - 1s),
            ChildProcess::Outcome::timed_out);
  EXPECT_LT(seconds_since(start), 0.5);
}

TEST(ChildProcess, aProgramThatClosedItsOutputIsSaidToHaveDoneSo) {
  ChildProcess child("exec >&-; exec sleep 30");
  ASSERT_TRUE(child.start());
  std::vector<std::string> lines;
  EXPECT_EQ(child.exchange("x\n", 1, lines, 2000ms, Clock::now() + 2s),
            ChildProcess::Outcome::exited);
  EXPECT_EQ(child.end_description(), "closed its standard output and is still running");
}

// Run once: the exit is taken when it comes, though a descendant in a session of its own holds
// the output open for 60 s; what it left is ended.
TEST(ChildProcess, runToEndTakesTheExitNotTheDescendantsOutput) {
  ChildProcess child("setsid sleep 60 & echo $! > /dev/stderr; echo said; exit 3");
  ASSERT_TRUE(child.start());
  std::string output;
  int status = 0;
  const auto start = Clock::now();
  EXPECT_EQ(child.run_to_end(output, 1 << 16, Clock::now() + 20s, status),
            ChildProcess::Outcome::exited);
  EXPECT_LT(seconds_since(start), 5);
  EXPECT_EQ(status, 3);
  EXPECT_EQ(output, "said\n");
  const pid_t descendant = static_cast<pid_t>(
      std::stol(child.stderr_tail().empty() ? std::string("0") : child.stderr_tail()));
  ASSERT_GT(descendant, 0) << "the descendant's pid was not read";
  EXPECT_NE(::kill(descendant, 0), 0) << "the descendant outlived the run";
}

// At the time limit the whole group is killed, a program that ignores SIGTERM too, and only the
// first `keep` bytes of a flood are kept.
TEST(ChildProcess, runToEndStopsAHangAtItsDeadline) {
  ChildProcess child("trap '' TERM; yes | head -c 100000; sleep 60");
  ASSERT_TRUE(child.start());
  std::string output;
  int status = 0;
  const auto start = Clock::now();
  EXPECT_EQ(child.run_to_end(output, 1000, Clock::now() + 1s, status),
            ChildProcess::Outcome::timed_out);
  EXPECT_LT(seconds_since(start), 5);
  EXPECT_EQ(status, 124);
  EXPECT_EQ(output.size(), 1000u);
}

}  // namespace
}  // namespace oblique::protocol
