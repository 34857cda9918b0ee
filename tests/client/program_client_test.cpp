// oblique::client::Program, the one client of every tool that asks a program: each failure typed
// by its cause (a crash, a timeout, lines that are not one answer per request, a line over the
// limit, a command that cannot run), the pipeline of queued requests, and a program run once.
#include "oblique/client/program.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

namespace oblique::client {
namespace {

constexpr auto kTimeout = std::chrono::milliseconds(2000);
using Cause = Failure::Cause;

std::vector<std::string> numbered(int n) {
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) out.push_back("request " + std::to_string(i));
  return out;
}

TEST(ProgramClient, everyRequestGetsItsAnswerInOrder) {
  Program program("sed -u 's/request/answer/'", kTimeout);
  const Reply reply = program.ask(numbered(500));
  ASSERT_TRUE(reply.ok()) << reply.failure->what;
  ASSERT_EQ(reply.lines.size(), 500u);
  for (int i = 0; i < 500; ++i) ASSERT_EQ(reply.lines[i], "answer " + std::to_string(i));
  EXPECT_EQ(program.answered(), 500);
  EXPECT_TRUE(program.finish().empty());
  EXPECT_FALSE(program.running());
}

TEST(ProgramClient, aCrashKeepsTheAnswersBeforeAndSaysHowItEnded) {
  Program program(
      "i=0; while read -r line; do i=$((i + 1)); [ $i -gt 3 ] && { echo dying >&2; exit 4; }; "
      "echo ok; done",
      kTimeout);
  const std::vector<std::string> requests = numbered(10);
  const Reply reply = program.ask(requests);
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->kind(), Failure::Kind::crash);
  EXPECT_EQ(reply.failure->cause, Cause::exited);
  EXPECT_EQ(reply.failure->ended, "exited with status 4");
  EXPECT_EQ(reply.failure->stderr_tail, "dying");
  EXPECT_EQ(reply.failure->request, requests[3]);
  EXPECT_EQ(reply.lines.size(), 3u);
  EXPECT_FALSE(program.running());
}

TEST(ProgramClient, aProgramThatStopsAnsweringTimesOut) {
  Program program("i=0; while read -r line; do i=$((i + 1)); [ $i -le 2 ] && echo ok; done",
                  std::chrono::milliseconds(300));
  const std::vector<std::string> requests = numbered(5);
  const Reply reply = program.ask(requests);
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->kind(), Failure::Kind::timeout);
  EXPECT_EQ(reply.failure->cause, Cause::timed_out);
  EXPECT_EQ(reply.failure->request, requests[2]);
  EXPECT_EQ(reply.lines.size(), 2u);
}

TEST(ProgramClient, linesBeyondOneAnswerPerRequestFailTheExchange) {
  // Two lines for each request, in one write (so both are there when the first is read).
  Program program("while read -r line; do printf 'one\\ntwo\\n'; done", kTimeout);
  const Reply reply = program.ask(std::string("request"));
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->kind(), Failure::Kind::protocol);
  EXPECT_EQ(reply.failure->cause, Cause::beyond);
  EXPECT_EQ(reply.failure->lines, std::vector<std::string>{"two"});
  program.stop();
}

TEST(ProgramClient, outputLeftFromBeforeFailsTheNextExchange) {
  // After two requests it writes two lines at once; one is read, the other is left over.
  Program program("read -r a; read -r b; printf 'x\\ny\\n'; cat", kTimeout);
  ASSERT_TRUE(program.start());
  program.queue("first\nsecond\n");
  std::vector<std::string> lines;
  ASSERT_FALSE(program.read(1, lines, Clock::now() + kTimeout));
  EXPECT_EQ(lines, std::vector<std::string>{"x"});
  const Reply reply = program.ask(std::string("third"));
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->cause, Cause::left_over);
  EXPECT_EQ(reply.failure->request, "third");
  EXPECT_EQ(reply.failure->lines, std::vector<std::string>{"y"});
  program.stop();
}

TEST(ProgramClient, aLineOverTheLimitIsNotReadWhole) {
  Program program("read -r line; head -c 2000000 /dev/zero | tr '\\0' x; echo", kTimeout);
  const Reply reply = program.ask(std::string("request"));
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->kind(), Failure::Kind::protocol);
  EXPECT_EQ(reply.failure->cause, Cause::overlong);
  ASSERT_EQ(reply.failure->lines.size(), 1u);
  EXPECT_LT(reply.failure->lines[0].size(), 1000000u);
  program.stop();
}

TEST(ProgramClient, aCommandThatCannotRunIsNotACrash) {
  Program program("/nonexistent/oblique-implementation", kTimeout);
  const Reply reply = program.ask(std::string("request"));
  ASSERT_TRUE(reply.failure);
  EXPECT_EQ(reply.failure->kind(), Failure::Kind::protocol);
  EXPECT_EQ(reply.failure->cause, Cause::cannot_run);
  EXPECT_EQ(reply.failure->ended, "exited with status 127");
}

TEST(ProgramClient, queuedRequestsAreAnsweredInThePipeline) {
  Program program("sed -u 's/request/answer/'", kTimeout);
  ASSERT_TRUE(program.start());
  program.queue("request 1\nrequest 2\n");
  program.queue("request 3\n");
  std::vector<std::string> lines;
  EXPECT_FALSE(program.read(2, lines, Clock::now() + kTimeout));
  EXPECT_FALSE(program.read(3, lines, Clock::now() + kTimeout));
  EXPECT_EQ(lines, (std::vector<std::string>{"answer 1", "answer 2", "answer 3"}));
  // A read beyond what was queued times out, and leaves the program running for its caller.
  const std::optional<Failure> more =
      program.read(4, lines, Clock::now() + std::chrono::milliseconds(200));
  ASSERT_TRUE(more);
  EXPECT_EQ(more->kind(), Failure::Kind::timeout);
  EXPECT_TRUE(program.running());
  EXPECT_TRUE(program.finish().empty());
}

TEST(ProgramClient, aProgramRunOnceIsKilledAtItsDeadline) {
  const client::Run quick = run_once("echo done; exit 3", 1024, Clock::now() + kTimeout);
  EXPECT_TRUE(quick.started);
  EXPECT_FALSE(quick.timed_out);
  EXPECT_EQ(quick.output, "done\n");
  EXPECT_EQ(quick.status, 3);
  const auto start = Clock::now();
  const client::Run slow =
      run_once("sleep 30", 1024, Clock::now() + std::chrono::milliseconds(300));
  EXPECT_TRUE(slow.timed_out);
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(10));
}

}  // namespace
}  // namespace oblique::client
