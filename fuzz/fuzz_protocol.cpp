// libFuzzer target: the JSON Lines protocol of `oblique apply`. The first byte picks precision,
// convention and method; the rest is the input text. Every line must get an answer that is itself
// a valid answer line carrying the same status, and an ok answer's numbers must read back finite.
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string_view>

#include "oblique/protocol/apply.h"

namespace {

[[noreturn]] void fail(const char* what, std::string_view line) {
  std::fprintf(stderr, "protocol contract violated: %s\nanswer: %.*s\n", what,
               static_cast<int>(line.size()), line.data());
  std::abort();
}

template <class T>
void numbers_read_back(const oblique::protocol::ParsedAnswer& answer, std::string_view line) {
  std::string error;
  for (const std::string& token : *answer.projection) {
    const auto value = oblique::protocol::parse_number<T>(token, &error);
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
  std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    const Answer answer = answer_request(line, options);
    const ParsedAnswer back = parse_answer(answer.line);
    if (!back.valid) fail("the answer is not a valid answer line", answer.line);
    if (back.status != oblique::status_code(answer.status))
      fail("the answer's status differs", answer.line);
    if (answer.status == oblique::Status::ok) {
      switch (options.precision) {
        case Precision::float32: numbers_read_back<float>(back, answer.line); break;
        case Precision::float64: numbers_read_back<double>(back, answer.line); break;
        case Precision::long_double: numbers_read_back<long double>(back, answer.line); break;
      }
    } else if (back.message.empty()) {
      fail("a refusal without a message", answer.line);
    }
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return 0;
}
