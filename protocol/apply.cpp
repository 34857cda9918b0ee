#include "oblique/protocol/apply.h"

#include <algorithm>
#include <istream>
#include <ostream>

namespace oblique::protocol {

namespace {

AnswerLine refusal(Status status, std::string_view message) {
  return AnswerLine{status, refusal_line(status, message)};
}

template <class T>
AnswerLine run(const Request& request, const ApplyOptions& options) {
  Matrix4<T> m;
  Vector4<T> c;
  for (int i = 0; i < 16; ++i) {
    const Expected<T> value = parse_number<T>(request.projection[i]);
    if (!value)
      return refusal(Status::invalid_input,
                     "projection[" + std::to_string(i) + "]: " + value.error());
    m(i / 4, i % 4) = *value;
  }
  for (int i = 0; i < 4; ++i) {
    const Expected<T> value = parse_number<T>(request.plane[i]);
    if (!value)
      return refusal(Status::invalid_input, "plane[" + std::to_string(i) + "]: " + value.error());
    c(i) = *value;
  }
  const Convention convention = request.convention.value_or(options.convention);
  const ObliqueResult<T> result = apply<T>(m, c, convention, options.method);
  if (!result.ok()) return refusal(result.status, result.message());
  return AnswerLine{Status::ok, ok_answer_line(result.projection)};
}

}  // namespace

AnswerLine answer_request(std::string_view line, const ApplyOptions& options) {
  const Expected<Request> parsed = parse_request(line);
  if (!parsed) return refusal(Status::invalid_input, "not a valid request: " + parsed.error());
  switch (options.precision) {
    case Precision::float32: return run<float>(*parsed, options);
    case Precision::float64: return run<double>(*parsed, options);
    case Precision::long_double: return run<long double>(*parsed, options);
  }
  return refusal(Status::invalid_input, "unknown precision");
}

int serve(std::istream& in, std::ostream& out, const ApplyOptions& options) {
  std::streambuf& input = *in.rdbuf();
  std::string line;
  line.reserve(std::min<std::size_t>(options.max_line_bytes, 4096));
  bool all_ok = true;
  for (bool more = true; more;) {
    // One line, at most max_line_bytes of it kept. Before any read that may wait for the
    // writer (nothing buffered), the answers so far are flushed.
    line.clear();
    std::size_t length = 0;
    bool any = false;
    for (;;) {
      if (input.in_avail() <= 0 && !out.flush()) return 2;
      const int ch = input.sbumpc();
      if (ch == std::char_traits<char>::eof()) {
        more = false;
        break;
      }
      any = true;
      if (ch == '\n') break;
      if (length++ < options.max_line_bytes) line.push_back(static_cast<char>(ch));
    }
    if (!any) break;
    AnswerLine answer;
    if (length > options.max_line_bytes) {
      answer = refusal(
          Status::invalid_input,
          "line longer than " + std::to_string(options.max_line_bytes) + " bytes (skipped)");
    } else {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      answer = answer_request(line, options);
    }
    all_ok = all_ok && answer.status == Status::ok;
    if (!(out << answer.line << '\n')) return 2;
  }
  if (!out.flush()) return 2;
  return all_ok ? 0 : 1;
}

}  // namespace oblique::protocol
