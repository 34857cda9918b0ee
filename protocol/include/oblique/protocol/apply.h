// `oblique apply`: answers protocol requests with the core.
#pragma once

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
};

/// One answer line (no trailing newline) and the status it carries.
struct Answer {
  Status status = Status::invalid_input;
  std::string line;
};

/// Parses one request line, runs the core, and formats the answer.
Answer answer_request(std::string_view line, const ApplyOptions& options);

/// Answers every line of `in` on `out`, one line each, in order. Returns 0 when every answer was
/// ok, 1 otherwise.
int serve(std::istream& in, std::ostream& out, const ApplyOptions& options);

}  // namespace oblique::protocol
