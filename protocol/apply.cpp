#include "oblique/protocol/apply.h"

#include <istream>
#include <ostream>

namespace oblique::protocol {

namespace {

Answer refusal(Status status, std::string_view message) {
  return Answer{status, refusal_line(status, message)};
}

template <class T>
Answer run(const Request& request, const ApplyOptions& options) {
  Matrix4<T> m;
  Vector4<T> c;
  std::string error;
  for (int i = 0; i < 16; ++i) {
    auto value = parse_number<T>(request.projection[i], &error);
    if (!value)
      return refusal(Status::invalid_input, "projection[" + std::to_string(i) + "]: " + error);
    m(i / 4, i % 4) = *value;
  }
  for (int i = 0; i < 4; ++i) {
    auto value = parse_number<T>(request.plane[i], &error);
    if (!value) return refusal(Status::invalid_input, "plane[" + std::to_string(i) + "]: " + error);
    c(i) = *value;
  }
  const Convention convention = request.convention.value_or(options.convention);
  const ObliqueResult<T> result = apply<T>(m, c, convention, options.method);
  if (!result.ok()) return refusal(result.status, result.message());
  return Answer{Status::ok, ok_answer_line(result.projection)};
}

}  // namespace

Answer answer_request(std::string_view line, const ApplyOptions& options) {
  ParsedLine parsed = parse_request(line);
  if (!parsed.request)
    return refusal(Status::invalid_input, "not a valid request: " + parsed.error);
  switch (options.precision) {
    case Precision::float32: return run<float>(*parsed.request, options);
    case Precision::float64: return run<double>(*parsed.request, options);
    case Precision::long_double: return run<long double>(*parsed.request, options);
  }
  return refusal(Status::invalid_input, "unknown precision");
}

int serve(std::istream& in, std::ostream& out, const ApplyOptions& options) {
  std::string line;
  bool all_ok = true;
  for (;;) {
    // Answer promptly when the writer waits for us; batch when it has sent many lines.
    if (in.rdbuf()->in_avail() <= 0) out.flush();
    if (!std::getline(in, line)) break;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const Answer answer = answer_request(line, options);
    all_ok = all_ok && answer.status == Status::ok;
    out << answer.line << '\n';
  }
  out.flush();
  return all_ok ? 0 : 1;
}

}  // namespace oblique::protocol
