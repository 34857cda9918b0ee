#include "oblique/protocol/apply.h"
#include "oblique/protocol/matrix_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "oblique/projection.h"
#include "oblique/protocol/consumer_messages.h"
#include "printers.h"

namespace oblique::protocol {
namespace {

TEST(Protocol, numbersParseExactlyInEveryForm) {
  EXPECT_EQ(parse_number<double>("\"0x1.8p+1").value(), 3.0);
  EXPECT_EQ(parse_number<double>("\"-0x1p-1074").value(),
            -std::numeric_limits<double>::denorm_min());
  EXPECT_TRUE(std::isnan(parse_number<double>("\"nan").value()));
  EXPECT_EQ(parse_number<double>("\"inf").value(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_number<double>("\"-inf").value(), -std::numeric_limits<double>::infinity());
  const auto negative_zero = parse_number<double>("-0");
  ASSERT_TRUE(negative_zero);
  EXPECT_TRUE(std::signbit(*negative_zero));
  EXPECT_EQ(parse_number<long double>("0.1").value(), 0.1L);
}

// Converting text -> double -> float can round twice; parsing per precision rounds once.
// 1 + 2^-24 + tiny lies just above the midpoint of 1 and the next float, so it rounds up.
TEST(Protocol, floatRequestsAreRoundedOnceFromTheirText) {
  const auto value = parse_number<float>("1.00000005960464477539062500000001");
  ASSERT_TRUE(value);
  EXPECT_EQ(*value, std::nextafter(1.0f, 2.0f));
  EXPECT_EQ(static_cast<float>(1.00000005960464477539062500000001), 1.0f);  // the double route
}

TEST(Protocol, badNumbersAreNamed) {
  const Expected<double> word = parse_number<double>("\"abc");
  EXPECT_FALSE(word);
  EXPECT_NE(word.error().find("\"abc\" is not a number"), std::string::npos);
  EXPECT_FALSE(parse_number<double>("\"0x1p"));
  EXPECT_FALSE(parse_number<double>("\"1.5"));  // decimal strings are not in the protocol
  const Expected<float> huge = parse_number<float>("1e39");
  EXPECT_FALSE(huge);
  EXPECT_NE(huge.error().find("overflows"), std::string::npos);
}

TEST(Protocol, printedNumbersReadBackToTheSameBits) {
  std::mt19937_64 random(20261123);
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t bits = random();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    if (!std::isfinite(d)) continue;
    const auto back = parse_number<double>(format_number(d));
    ASSERT_TRUE(back) << back.error();
    EXPECT_EQ(std::memcmp(&*back, &d, sizeof d), 0) << format_number(d);
    const auto f = static_cast<float>(d);
    if (!std::isfinite(f)) continue;
    const auto back_f = parse_number<float>(format_number(f));
    ASSERT_TRUE(back_f);
    EXPECT_EQ(std::memcmp(&*back_f, &f, sizeof f), 0) << format_number(f);
  }
}

TEST(Protocol, malformedRequestsSayWhatIsWrong) {
  const std::string matrix = "[1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0]";
  const std::pair<std::string, std::string> cases[] = {
      {"", "parse error at line 1, column 1"},
      {"{\"projection\": [1,2", "parse error"},
      {"[1, 2]", "must be a JSON object, not an array"},
      {"{\"plane\": [0,0,-1,-1]}", "missing field \"projection\""},
      {"{\"projection\": " + matrix + "}", "missing field \"plane\""},
      {"{\"projection\": [1,2,3], \"plane\": [0,0,-1,-1]}", "must hold 16 numbers, not 3"},
      {"{\"projection\": 5, \"plane\": [0,0,-1,-1]}",
       "must be an array of 16 numbers, not a number"},
      {"{\"projection\": " + matrix + ", \"plane\": [0,0,-1,null]}",
       "\"plane\"[3] must be a number, not null"},
      {"{\"projection\": " + matrix + ", \"plane\": [0,0,-1,-1], \"convention\": \"dx\"}",
       "unknown convention \"dx\""},
      {"{\"projection\": " + matrix + ", \"plane\": [0,0,-1,-1], \"extra\": 1}",
       "unknown field \"extra\""},
      {"[[[[[[[[[[[[1]]]]]]]]]]]]", "nested deeper"},
  };
  for (const auto& [line, expected] : cases) {
    const Expected<Request> parsed = parse_request(line);
    EXPECT_FALSE(parsed) << line;
    EXPECT_NE(parsed.error().find(expected), std::string::npos) << line << " -> " << parsed.error();
    const AnswerLine answer = answer_request(line, ApplyOptions{});
    EXPECT_EQ(answer.status, Status::invalid_input);
    EXPECT_EQ(answer.line.rfind("{\"status\": \"invalid_input\", \"message\": ", 0), 0u)
        << answer.line;
  }
}

TEST(Protocol, answersCarryTheCoreResultExactly) {
  const Matrix4<double> m = frustum<double>(-4, 4, -3, 3, 5, 80, Convention::zero_one);
  const Vector4<double> c(0.25, -0.375, -1, -7);
  std::string line = "{\"projection\": [";
  for (int i = 0; i < 16; ++i) line += (i ? "," : "") + format_number(m(i / 4, i % 4));
  line += "], \"plane\": [0.25, -0.375, -1, \"-0x1.cp+2\"], \"convention\": \"zero_one\"}";
  const AnswerLine answer = answer_request(line, ApplyOptions{});
  ASSERT_EQ(answer.status, Status::ok) << answer.line;
  const auto expected = apply(m, c, Convention::zero_one);
  std::string want = "{\"status\": \"ok\", \"projection\": [";
  for (int i = 0; i < 16; ++i)
    want += (i ? ", " : "") + format_number(expected.projection(i / 4, i % 4));
  want += "]}";
  EXPECT_EQ(answer.line, want);
}

TEST(Protocol, flagsAndRequestFieldsChooseConventionAndPrecision) {
  const std::string line =
      "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1,-1]}";
  ApplyOptions options;
  options.precision = Precision::float32;
  EXPECT_EQ(
      answer_request(line, options).line,
      "{\"status\": \"ok\", \"projection\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -3, -4, 0, 0, -1, 0]}");
  options.method = Method::general;
  options.convention = Convention::zero_one;
  EXPECT_EQ(answer_request(line, options).status, Status::ok);
}

TEST(Protocol, everyWritersNonFiniteTokensReadAsNonFiniteNumbers) {
  // C's printf("%.17g") (nan, -nan, inf, -inf), Python (NaN, Infinity, -Infinity), JavaScript
  // (null), bare or quoted: each is a number to judge, not a protocol error.
  const double inf = std::numeric_limits<double>::infinity();
  const std::pair<const char*, double> tokens[] = {{"nan", NAN},
                                                   {"-nan", NAN},
                                                   {"inf", inf},
                                                   {"-inf", -inf},
                                                   {"NaN", NAN},
                                                   {"Infinity", inf},
                                                   {"-Infinity", -inf},
                                                   {"null", NAN},
                                                   {"\"NaN\"", NAN},
                                                   {"\"Infinity\"", inf},
                                                   {"\"-Infinity\"", -inf},
                                                   {"\"-nan\"", NAN}};
  for (const auto& [token, value] : tokens) {
    std::string line = "{\"status\": \"ok\", \"projection\": [";
    for (int i = 0; i < 16; ++i) line += std::string(i ? ", " : "") + (i == 5 ? token : "1");
    line += "]}";
    const Expected<AnswerText> parsed = parse_answer(normalise_non_finite(line));
    ASSERT_TRUE(parsed) << line << ": " << parsed.error();
    const Expected<double> read = parse_number<double>((*parsed->projection)[5]);
    ASSERT_TRUE(read) << token << ": " << read.error();
    if (std::isnan(value)) {
      EXPECT_TRUE(std::isnan(*read)) << token;
    } else {
      EXPECT_EQ(*read, value) << token;
    }
    EXPECT_EQ(parse_number<double>((*parsed->projection)[0]).value(), 1.0);
  }
  // Inside strings nothing changes.
  EXPECT_EQ(normalise_non_finite("{\"message\": \"nan inf null\"}"),
            "{\"message\": \"nan inf null\"}");
}

}  // namespace
}  // namespace oblique::protocol

namespace oblique::protocol {
namespace {

TEST(Protocol, negativeZeroKeepsItsSignThroughRequestsAndAnswers) {
  const Expected<Request> parsed = parse_request(
      "{\"projection\": [-0, 0, -0.0, 1, 0,1,0,0, 0,0,-3,-4, 0,0,-1,0], \"plane\": [-0,0,-1,-1]}");
  ASSERT_TRUE(parsed) << parsed.error();
  EXPECT_EQ(parsed->projection[0], "-0");
  EXPECT_EQ(parsed->projection[2], "-0.0");
  EXPECT_EQ(parsed->plane[0], "-0");
  const Expected<AnswerText> answer = parse_answer(
      "{\"status\": \"ok\", \"projection\": [-0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,\"-0x1p+0\"]}");
  ASSERT_TRUE(answer) << answer.error();
  EXPECT_TRUE(std::signbit(parse_number<double>((*answer->projection)[0]).value()));
  EXPECT_EQ(parse_number<double>((*answer->projection)[15]).value(), -1.0);
}

TEST(Protocol, answersThatAreNotAnswersAreNamed) {
  EXPECT_FALSE(parse_answer("{\"projection\": []}"));
  EXPECT_NE(parse_answer("{\"status\": \"ok\"}").error().find("needs \"projection\""),
            std::string::npos);
  EXPECT_NE(parse_answer("{\"status\": 3}").error().find("must be a string"), std::string::npos);
  EXPECT_TRUE(parse_answer("{\"status\": \"camera_not_behind_plane\", \"message\": \"x\"}"));
}

const std::string kRequest =
    "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1,-1]}";

TEST(Protocol, longDoubleReadsNumbersBeyondDoubleRange) {
  // 1e400 is a long double but not a double: the request must be read at the precision asked.
  const std::string line =
      "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1e400,-1e400]}";
  const Expected<Request> parsed = parse_request(line);
  ASSERT_TRUE(parsed) << parsed.error();
  EXPECT_EQ(parsed->plane[2], "-1e400");
  ApplyOptions options;
  options.precision = Precision::long_double;
  const AnswerLine answer = answer_request(line, options);
  EXPECT_EQ(answer.status, Status::ok) << answer.line;
  // In double the same number is named as overflowing, not as a JSON error.
  options.precision = Precision::float64;
  const AnswerLine in_double = answer_request(line, options);
  EXPECT_NE(in_double.line.find("plane[2]: -1e400 overflows"), std::string::npos) << in_double.line;
  // An integer beyond every range, too.
  const std::string huge(400, '9');
  const AnswerLine integer = answer_request(
      "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1,-" + huge + "]}",
      options);
  EXPECT_NE(integer.line.find("plane[3]: -" + huge + " overflows"), std::string::npos)
      << integer.line;
}

TEST(Protocol, repeatedFieldsNulBytesAndTooManyValuesAreRefused) {
  const std::string matrix = "[1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0]";
  std::string many_strings = "[\"\"";
  for (int i = 0; i < 300; ++i) many_strings += ",\"\"";
  many_strings += "]";
  const std::pair<std::string, std::string> cases[] = {
      {"{\"projection\": " + matrix + ", \"plane\": [0,0,-1,-1], \"plane\": [0,0,-1,-2]}",
       "field \"plane\" given twice"},
      {"{\"projection\": " + matrix + ", \"projection\": " + matrix + ", \"plane\": [0,0,-1,-1]}",
       "field \"projection\" given twice"},
      {"{\"convention\": \"gl\", \"projection\": " + matrix +
           ", \"plane\": [0,0,-1,-1], \"convention\": \"zero_one\"}",
       "field \"convention\" given twice"},
      {kRequest + std::string(1, '\0') + "{\"anything\": 1}",
       "a NUL byte at column " + std::to_string(kRequest.size() + 1)},
      {std::string(1, '\0'), "a NUL byte at column 1"},
      {many_strings, "more than 256 JSON values"},
  };
  for (const auto& [line, expected] : cases) {
    const Expected<Request> parsed = parse_request(line);
    EXPECT_FALSE(parsed) << line;
    EXPECT_NE(parsed.error().find(expected), std::string::npos) << line << " -> " << parsed.error();
    EXPECT_EQ(answer_request(line, ApplyOptions{}).status, Status::invalid_input);
  }
  // Numbers are counted before any parsing: a line of a million numbers is refused at once.
  std::string numbers = "{\"projection\": [1";
  for (int i = 0; i < 1000000; ++i) numbers += ",1";
  const Expected<Request> parsed = parse_request(numbers + "]}");
  EXPECT_NE(parsed.error().find("more than 256 numbers"), std::string::npos) << parsed.error();
}

/// Input that arrives in chunks, as from a pipe: `underflow` hands out the next chunk and, before
/// it does, records what the reader had delivered to its output at that point.
class ChunkedInput : public std::streambuf {
 public:
  ChunkedInput(std::vector<std::string> chunks, const std::string* delivered)
      : chunks_(std::move(chunks)), delivered_(delivered) {}
  std::vector<std::string> seen_before_chunk;  ///< the output delivered before each chunk

 protected:
  int_type underflow() override {
    if (next_ == chunks_.size()) return traits_type::eof();
    seen_before_chunk.push_back(*delivered_);
    std::string& chunk = chunks_[next_++];
    setg(chunk.data(), chunk.data(), chunk.data() + chunk.size());
    return traits_type::to_int_type(chunk[0]);
  }

 private:
  std::vector<std::string> chunks_;
  std::size_t next_ = 0;
  const std::string* delivered_;
};

/// Output that reaches the other side only when flushed (like a pipe behind a buffer), or never
/// (like /dev/full) when `fails`.
class DeliveredOutput : public std::streambuf {
 public:
  explicit DeliveredOutput(bool fails = false) : fails_(fails) {}
  std::string delivered;

 protected:
  int_type overflow(int_type ch) override {
    if (fails_) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof()))
      pending_ += traits_type::to_char_type(ch);
    return traits_type::not_eof(ch);
  }
  int sync() override {
    if (fails_) return -1;
    delivered += pending_;
    pending_.clear();
    return 0;
  }

 private:
  bool fails_;
  std::string pending_;
};

TEST(Serve, answersEachCompleteRequestBeforeWaitingForMoreInput) {
  DeliveredOutput output;
  // One complete request and the start of the next; the rest arrives only later.
  ChunkedInput input({kRequest + "\n{\"projection\"", ": [1]}\n"}, &output.delivered);
  std::istream in(&input);
  std::ostream out(&output);
  EXPECT_EQ(serve(in, out, ApplyOptions{}), 1);
  ASSERT_EQ(input.seen_before_chunk.size(), 2u);
  EXPECT_EQ(input.seen_before_chunk[1].find("{\"status\": \"ok\""), 0u)
      << "the first answer was held back until the second line completed";
  EXPECT_EQ(std::count(output.delivered.begin(), output.delivered.end(), '\n'), 2);
}

TEST(Serve, aLineLongerThanTheLimitIsAnsweredAndSkipped) {
  ApplyOptions options;
  options.max_line_bytes = 100;
  std::istringstream in(kRequest + "\n" + std::string(101, ' ') + "\n" + kRequest + "\n" +
                        std::string(100, ' ') + "\n");
  std::ostringstream out;
  EXPECT_EQ(serve(in, out, options), 1);
  std::istringstream answers(out.str());
  std::vector<std::string> lines;
  for (std::string line; std::getline(answers, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u) << out.str();
  EXPECT_EQ(parse_answer(lines[0])->status, "ok");
  EXPECT_NE(lines[1].find("line longer than 100 bytes"), std::string::npos) << lines[1];
  EXPECT_EQ(parse_answer(lines[2])->status, "ok");
  EXPECT_NE(lines[3].find("parse error"), std::string::npos) << lines[3];  // 100 bytes: read
  // The default limit is 1 MiB: a 2 MiB line is skipped, the request after it answered.
  std::istringstream big(std::string(2 << 20, '1') + "\n" + kRequest + "\n");
  std::ostringstream big_out;
  EXPECT_EQ(serve(big, big_out, ApplyOptions{}), 1);
  EXPECT_NE(big_out.str().find("line longer than 1048576 bytes"), std::string::npos);
  EXPECT_NE(big_out.str().find("\n{\"status\": \"ok\""), std::string::npos) << big_out.str();
}

TEST(Serve, anOutputErrorEndsTheRunWithStatusTwo) {
  DeliveredOutput full(true);
  std::istringstream in(kRequest + "\n" + kRequest + "\n");
  std::ostream out(&full);
  EXPECT_EQ(serve(in, out, ApplyOptions{}), 2);
}

}  // namespace
}  // namespace oblique::protocol

namespace oblique::protocol {
namespace {

TEST(Protocol, jsonErrorsNameTheirPlaceWithoutTheParsersId) {
  EXPECT_EQ(json_error_text("[json.exception.parse_error.101] parse error at line 1, column 2: x"),
            "parse error at line 1, column 2: x");
  EXPECT_EQ(json_error_text("no id here"), "no id here");
  const Expected<Request> parsed = parse_request("{\"projection\": [1,");
  EXPECT_EQ(parsed.error().find("[json.exception"), std::string::npos) << parsed.error();
  EXPECT_NE(parsed.error().find("line 1"), std::string::npos) << parsed.error();
}

}  // namespace
}  // namespace oblique::protocol

namespace oblique::protocol {

TEST(ConsumerMessages, requestsCarryTheirKindAndNumbersExactly) {
  Matrix4<double> view = Matrix4<double>::Identity();
  view(0, 3) = 0.1;
  view(2, 2) = -0.0;
  ConsumerRequest r(ConsumerKind::mirror_view);
  r.numbers("view", view).numbers("plane", Vector4<double>(0, 1, 0, -2.5));
  EXPECT_EQ(r.line(),
            "{\"kind\": \"mirror_view\", \"view\": [1, 0, 0, 0.1, 0, 1, 0, 0, 0, 0, -0.0, 0, 0, 0, "
            "0, 1], \"plane\": [0, 1, 0, -2.5]}");
  EXPECT_EQ(ConsumerRequest(ConsumerKind::linear_depth).number("depth", 0.5f).line(),
            "{\"kind\": \"linear_depth\", \"depth\": 0.5}");
  for (const ConsumerKind k : all_consumer_kinds)
    EXPECT_EQ(parse_consumer_kind(consumer_kind_name(k)), k);
  EXPECT_FALSE(parse_consumer_kind("corner"));
}

TEST(ConsumerMessages, answersReadFlatNestedAndNonFinite) {
  const auto planes = read_consumer_answer<double>(
      "{\"planes\": [[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, -1, -1], "
      "[0, 0, 1, 100]]}",
      ConsumerKind::culling_planes, 24, 4);
  ASSERT_TRUE(planes) << planes.error();
  EXPECT_EQ((*planes)[23], 100);
  const auto flat = read_consumer_answer<float>("{\"position\": [1, NaN, \"-inf\"]}",
                                                ConsumerKind::view_position, 3, 3);
  ASSERT_TRUE(flat) << flat.error();
  EXPECT_TRUE(std::isnan((*flat)[1]));
  EXPECT_EQ((*flat)[2], -std::numeric_limits<float>::infinity());
  // Beyond float's range: an infinity to judge, not a protocol error.
  const auto huge =
      read_consumer_answer<float>("{\"depth\": 1e300}", ConsumerKind::linear_depth, 1, 1);
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->front(), std::numeric_limits<float>::infinity());
  const auto none = read_consumer_answer<double>("{\"corners\": []}", ConsumerKind::corners, 0, 3);
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->empty());
}

TEST(ConsumerMessages, answersThatAreNotAnswersSayWhy) {
  auto why = [](std::string_view line, ConsumerKind kind, std::size_t count, std::size_t group) {
    const auto a = read_consumer_answer<double>(line, kind, count, group);
    return a ? std::string("read") : a.error();
  };
  EXPECT_EQ(why("{\"status\": \"camera_not_behind_plane\"}", ConsumerKind::mirror_view, 16, 16),
            "a mirror_view answer needs \"view\" (it has status \"camera_not_behind_plane\": these "
            "requests have no refusal)");
  EXPECT_EQ(why("{\"plane\": [1, 2, 3]}", ConsumerKind::camera_plane, 4, 4),
            "\"plane\" must hold 4 numbers, not 3");
  EXPECT_EQ(why("{\"corners\": [[1, 2], [3, 4]]}", ConsumerKind::corners, 0, 3),
            "\"corners\"[0] must hold 3 numbers, not 2");
  EXPECT_EQ(why("{\"corners\": [1, 2, 3, 4]}", ConsumerKind::corners, 0, 3),
            "\"corners\" must hold a multiple of 3 numbers, not 4");
  EXPECT_EQ(why("{\"depth\": true}", ConsumerKind::linear_depth, 1, 1),
            "\"depth\" must be a number, not a boolean");
  EXPECT_EQ(why("[1]", ConsumerKind::linear_depth, 1, 1),
            "an answer must be a JSON object, not an array");
}

// --layout: every matrix of a line (a flat array of 16) transposed, its number tokens moved whole;
// planes, nested arrays, objects and strings left as they are; twice gives the line back.
TEST(MatrixOrder, transposesEveryMatrixAndNothingElse) {
  const std::string request =
      R"({"projection": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 1.5e-300], )"
      R"("plane": [0.1, 0.2, 0.3, -4], "convention": "gl", "note": "[1, 2], {3}"})";
  const std::string reordered = other_matrix_order(request);
  EXPECT_EQ(reordered,
            R"({"projection": [1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 4, 8, 12, 1.5e-300], )"
            R"("plane": [0.1, 0.2, 0.3, -4], "convention": "gl", "note": "[1, 2], {3}"})");
  EXPECT_EQ(other_matrix_order(reordered), request);
  // Two matrices on one line (a world_position request's projection and view), a nested list
  // of planes, and an answer's non-finite tokens.
  const std::string two = R"({"a": [0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15], "planes": [[1,2,3,4],)"
                          R"([5,6,7,8]], "b": ["NaN",1,2,3,4,5,6,7,8,9,10,11,12,13,14,"-inf"]})";
  EXPECT_EQ(other_matrix_order(two),
            R"({"a": [0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15], "planes": )"
            R"([[1,2,3,4],[5,6,7,8]], "b": ["NaN", 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, )"
            R"(11, "-inf"]})");
  EXPECT_EQ(other_matrix_order(other_matrix_order(two)),
            R"({"a": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15], "planes": )"
            R"([[1,2,3,4],[5,6,7,8]], "b": ["NaN", 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, )"
            R"(14, "-inf"]})");
}

TEST(MatrixOrder, leavesWhatIsNoMatrixAndSurvivesHostileText) {
  // 16 elements of which one is an array or an object: no matrix.
  const std::string nested = R"([[1],2,3,4,5,6,7,8,9,10,11,12,13,14,15,16])";
  EXPECT_EQ(other_matrix_order(nested), nested);
  const std::string object = R"([{"x":1},2,3,4,5,6,7,8,9,10,11,12,13,14,15,16])";
  EXPECT_EQ(other_matrix_order(object), object);
  // 15 or 17 elements: no matrix.
  EXPECT_EQ(other_matrix_order("[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15]"),
            "[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15]");
  // Unbalanced, unterminated strings, stray closers, deep nesting: returned, never a crash.
  for (const std::string& hostile :
       {std::string("]]]}}}"),
        std::string("[[[[\"), std::string("
                    "unterminated [1,2"),
        std::string(100000, '['), std::string("[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16")}) {
    EXPECT_NO_THROW((void)other_matrix_order(hostile));
  }
  EXPECT_EQ(in_matrix_order("[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16]", MatrixOrder::rows),
            "[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16]");
  EXPECT_EQ(matrix_order_of_layout("row_vectors"), MatrixOrder::columns);
  EXPECT_EQ(matrix_order_of_layout("column_major"), MatrixOrder::columns);
  EXPECT_EQ(matrix_order_of_layout("row_major"), MatrixOrder::rows);
  EXPECT_FALSE(matrix_order_of_layout("rows").has_value());
}

}  // namespace oblique::protocol

namespace oblique::protocol {
namespace {

/// Whether two readings of one line agree: both refused, or the same status, message and
/// entries, each the same value with the same sign (every NaN alike).
template <class T>
bool same_reading(const Expected<Answer<T>>& a, const Expected<Answer<T>>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return a.error() == b.error();
  if (a->status != b->status || a->message != b->message) return false;
  for (int i = 0; i < 16; ++i) {
    const T x = a->projection(i / 4, i % 4), y = b->projection(i / 4, i % 4);
    if (std::isnan(x) != std::isnan(y)) return false;
    // (Compared by value and sign: a long double's padding bytes are not its value.)
    if (!std::isnan(x) && (x != y || std::signbit(x) != std::signbit(y))) return false;
  }
  return true;
}

// read_answer() reads the common ok line with a cursor of its own; on every line, written as
// programs write them and then spoiled a character at a time, it reads what the JSON tree reads
// (read_answer_in_full(), the reference), the refusals' words included.
template <class T>
void readsAsTheJsonTreeDoes() {
  std::mt19937_64 rng(20261207);
  const std::vector<std::string> tokens = {"0",
                                           "-0",
                                           "1",
                                           "-1.5",
                                           "0.1",
                                           "1e308",
                                           "-1e309",
                                           "1e-400",
                                           "2.5E+3",
                                           "3e-2",
                                           "01",
                                           "+1",
                                           ".5",
                                           "1.",
                                           "1e",
                                           "--1",
                                           "NaN",
                                           "-inf",
                                           "Infinity",
                                           "\"nan\"",
                                           "\"0x1p3\"",
                                           "null",
                                           "1.0e",
                                           "0.0000001",
                                           "123456789012345678901234567890",
                                           "-3.4028235677973366e+38",
                                           "4.9406564584124654e-324"};
  const std::vector<std::string> spaces = {"", " ", "  ", "\t", "\r\n", "\n"};
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  long fast = 0, checked = 0;
  for (int round = 0; round < 4000; ++round) {
    std::string line;
    const auto sp = [&] { return spaces[pick(spaces.size())]; };
    if (round % 4 == 0) {
      // As the core's programs write it: every entry a number of T.
      Matrix4<T> m;
      for (int i = 0; i < 16; ++i)
        m(i / 4, i % 4) = static_cast<T>(std::ldexp(static_cast<double>(rng() % 2000) - 1000.0,
                                                    static_cast<int>(pick(80)) - 40));
      line = ok_answer_line<T>(m);
    } else {
      line = sp() + "{" + sp() + "\"status\"" + sp() + ":" + sp() + "\"ok\"" + sp() + "," + sp() +
             "\"projection\"" + sp() + ":" + sp() + "[";
      for (int i = 0; i < 16; ++i)
        line += (i ? sp() + "," + sp() : sp()) +
                (pick(5) == 0 ? tokens[pick(tokens.size())]
                              : std::to_string(static_cast<double>(rng() % 100000) / 64.0 - 700));
      line += sp() + "]" + sp() + "}" + sp();
    }
    // Spoiled: a character removed, replaced, or a field added.
    switch (pick(6)) {
      case 0: line.erase(pick(line.size()), 1); break;
      case 1: line[pick(line.size())] = "{}[],:\"e-.0x "[pick(13)]; break;
      case 2: line.insert(line.size() - 1, ", \"message\": \"m\""); break;
      default: break;
    }
    const Expected<Answer<T>> quick = read_answer<T>(line), full = read_answer_in_full<T>(line);
    EXPECT_TRUE(same_reading<T>(quick, full)) << line;
    ++checked;
    fast += full.has_value() && full->status == Status::ok;
  }
  EXPECT_EQ(checked, 4000);
  EXPECT_GT(fast, 1000);  // most lines are ok answers: the comparison is not of refusals alone
}

TEST(Protocol, answersReadByTheShortcutReadAsTheJsonTreeDoes) {
  readsAsTheJsonTreeDoes<float>();
  readsAsTheJsonTreeDoes<double>();
  readsAsTheJsonTreeDoes<long double>();
}

}  // namespace
}  // namespace oblique::protocol
