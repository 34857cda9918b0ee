// ConsumerProgram::answer(): a batch of requests written at once, one answer line read for each,
// and where the program stops answering (it exits, hangs, or writes a line that is not an
// answer) the answers before it kept and the request it stopped at named.
#include "oblique/client/consumer_program.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

namespace oblique::client {
namespace {

using oracle::ConsumerAsk;
using protocol::ConsumerKind;
using protocol::ConsumerRequest;

/// A linear_depth request carrying its place in the batch (programs below answer it blindly).
ConsumerAsk<double> depth_ask(int i) {
  ConsumerAsk<double> a;
  a.kind = ConsumerKind::linear_depth;
  a.request = [i] {
    ConsumerRequest r(ConsumerKind::linear_depth);
    r.number("depth", static_cast<double>(i));
    return r;
  };
  return a;
}

struct Asked {
  std::vector<ConsumerAsk<double>> asks;
  std::vector<const ConsumerAsk<double>*> pointers;
  explicit Asked(int n) {
    for (int i = 0; i < n; ++i) asks.push_back(depth_ask(i));
    for (const auto& a : asks) pointers.push_back(&a);
  }
};

constexpr auto kTimeout = std::chrono::milliseconds(2000);

TEST(ConsumerProgramBatch, everyRequestGetsItsAnswerInOrder) {
  // Echoes each request's depth back as its answer.
  ConsumerProgram<double> program("sed -u 's/.*\"depth\": \\([^}]*\\)}.*/{\"depth\": \\1}/'",
                                  kTimeout);
  const Asked asked(300);
  const auto batch = program.answer(asked.pointers);
  ASSERT_FALSE(batch.failure) << batch.failure->what << " " << batch.failure->request;
  ASSERT_EQ(batch.numbers.size(), 300u);
  ASSERT_EQ(batch.requests.size(), 300u);
  for (std::size_t i = 0; i < batch.numbers.size(); ++i) {
    ASSERT_EQ(batch.numbers[i], std::vector<double>{static_cast<double>(i)}) << batch.lines[i];
  }
  EXPECT_EQ(program.answered(), 300);
  EXPECT_TRUE(program.finish().empty());
}

TEST(ConsumerProgramBatch, aProgramThatExitsMidBatchKeepsTheAnswersBeforeAndNamesItsRequest) {
  ConsumerProgram<double> program(
      "i=0; while read -r line; do i=$((i + 1)); [ $i -gt 3 ] && exit 4; "
      "echo '{\"depth\": 1}'; done",
      kTimeout);
  const Asked asked(10);
  const auto batch = program.answer(asked.pointers);
  ASSERT_TRUE(batch.failure);
  EXPECT_EQ(batch.failure->kind(), Failure::Kind::crash);
  EXPECT_NE(batch.failure->what.find("exited with status 4"), std::string::npos)
      << batch.failure->what;
  EXPECT_EQ(batch.numbers.size(), 3u);
  EXPECT_EQ(batch.failure->request, batch.requests[3]);
}

TEST(ConsumerProgramBatch, aLineThatIsNotAnAnswerEndsTheBatchThere) {
  ConsumerProgram<double> program(
      "i=0; while read -r line; do i=$((i + 1)); if [ $i -eq 5 ]; then echo '{\"planes\": 1}'; "
      "else echo '{\"depth\": 2}'; fi; done",
      kTimeout);
  const Asked asked(8);
  const auto batch = program.answer(asked.pointers);
  ASSERT_TRUE(batch.failure);
  EXPECT_EQ(batch.failure->kind(), Failure::Kind::protocol);
  EXPECT_EQ(batch.numbers.size(), 4u);
  EXPECT_EQ(batch.lines.size(), 4u);
  EXPECT_EQ(batch.failure->request, batch.requests[4]);
  ASSERT_EQ(batch.failure->lines.size(), 1u);
  EXPECT_EQ(batch.failure->lines[0], "{\"planes\": 1}");
  program.stop();
}

TEST(ConsumerProgramBatch, aProgramThatStopsAnsweringTimesOutAtTheFirstUnansweredRequest) {
  ConsumerProgram<double> program(
      "i=0; while read -r line; do i=$((i + 1)); [ $i -le 2 ] && echo '{\"depth\": 1}'; done",
      std::chrono::milliseconds(300));
  const Asked asked(6);
  const auto batch = program.answer(asked.pointers);
  ASSERT_TRUE(batch.failure);
  EXPECT_EQ(batch.failure->kind(), Failure::Kind::timeout);
  EXPECT_EQ(batch.numbers.size(), 2u);
  EXPECT_EQ(batch.failure->request, batch.requests[2]);
}

}  // namespace
}  // namespace oblique::client
