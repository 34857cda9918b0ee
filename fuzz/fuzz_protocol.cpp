// libFuzzer target: the JSON Lines protocol of `oblique apply`, through its request loop serve().
// The first byte picks precision, convention and method; the rest is the input text, read with a
// 4 KiB line limit. Every line must get one answer, in order, that is itself a valid answer line:
// the line's own answer_request() answer when within the limit ("line longer than" otherwise), a
// message when refused, numbers that read back finite when ok; the exit status must match.
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>

#include "oblique/protocol/apply.h"

namespace {

constexpr std::size_t kFuzzMaxLineBytes = 4096;

[[noreturn]] void fail(const char* what, std::string_view line) {
  std::fprintf(stderr, "protocol contract violated: %s\nanswer: %.*s\n", what,
               static_cast<int>(line.size()), line.data());
  std::abort();
}

template <class T>
void numbers_read_back(const oblique::protocol::AnswerText& answer, std::string_view line) {
  for (const std::string& token : *answer.projection) {
    const auto value = oblique::protocol::parse_number<T>(token);
    if (!value || !std::isfinite(*value))
      fail("an ok answer holds a number that does not read back", line);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace oblique::protocol;
  if (size == 0) return 0;
  ApplyOptions options;
  options.precision = static_cast<Precision>(data[0] % 3);
  options.convention = oblique::all_conventions[(data[0] / 3) % 3];
  options.method = oblique::all_methods[(data[0] / 9) % std::size(oblique::all_methods)];
  // A line limit small enough for the fuzzer's inputs (-max_len in fuzz_protocol.options) to
  // cross it, so lines over the limit are explored as well as the ones under it.
  options.max_line_bytes = kFuzzMaxLineBytes;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::istringstream in(text);
  std::ostringstream out;
  const int status = serve(in, out, options);
  if (status != 0 && status != 1) fail("serve failed on a string stream", out.str());
  // One answer per input line, in order; a line within the limit answered as answer_request()
  // answers it alone, a longer one refused.
  std::istringstream answers(out.str());
  std::string_view rest(text);
  bool all_ok = true;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    std::string answer_line;
    if (!std::getline(answers, answer_line)) fail("an input line without an answer", line);
    const oblique::Expected<AnswerText> parsed = parse_answer(answer_line);
    if (!parsed) fail("the answer is not a valid answer line", answer_line);
    const AnswerText& back = *parsed;
    all_ok = all_ok && back.status == "ok";
    if (line.size() > options.max_line_bytes) {
      if (back.status != "invalid_input" || back.message.find("line longer than") != 0)
        fail("a line over the limit not refused as too long", answer_line);
    } else {
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      const AnswerLine alone = answer_request(line, options);
      if (alone.line != answer_line)
        fail("serve's answer differs from answer_request's", answer_line);
      if (alone.status == oblique::Status::ok) {
        switch (options.precision) {
          case Precision::float32: numbers_read_back<float>(back, answer_line); break;
          case Precision::float64: numbers_read_back<double>(back, answer_line); break;
          case Precision::long_double: numbers_read_back<long double>(back, answer_line); break;
        }
      } else if (back.message.empty()) {
        fail("a refusal without a message", answer_line);
      }
    }
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  std::string extra;
  if (std::getline(answers, extra)) fail("an answer without an input line", extra);
  if (status != (all_ok ? 0 : 1)) fail("the exit status disagrees with the answers", out.str());
  return 0;
}
