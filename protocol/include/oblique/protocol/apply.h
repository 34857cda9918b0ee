// `oblique apply`: answers protocol requests with the core.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>

#include "oblique/oblique.h"
#include "oblique/protocol/protocol.h"

namespace oblique::protocol {

/// Options of one `oblique apply` run.
struct ApplyOptions {
  Convention convention = Convention::gl;  ///< used when a request names none
  Method method = Method::automatic;
  Precision precision = Precision::float64;
  /// The longest request line read (bytes, without the newline); a longer line is answered
  /// invalid_input and skipped without being held in memory.
  std::size_t max_line_bytes = kDefaultMaxLineBytes;
  static constexpr std::size_t kDefaultMaxLineBytes = std::size_t{1} << 20;
};

/// One answer line (no trailing newline) and the status it carries.
struct AnswerLine {
  Status status = Status::invalid_input;
  std::string line;
};

/// Parses one request line, runs the core, and formats the answer.
AnswerLine answer_request(std::string_view line, const ApplyOptions& options);

/// Answers every line of `in` on `out`, one line each, in order. Each answer is flushed before
/// reading input that is not yet there, so a client that writes one request and waits gets its
/// answer; a client that streams many gets them in large writes. Returns 0 when every answer was
/// ok, 1 otherwise, and 2 as soon as `out` fails (a full disk, a closed pipe): reading stops.
int serve(std::istream& in, std::ostream& out, const ApplyOptions& options);

}  // namespace oblique::protocol
