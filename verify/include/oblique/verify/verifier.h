// `oblique verify`: drives an external implementation (any program that speaks the JSON Lines
// protocol of `oblique apply`) with the property suite's generators, judges every answer with
// the suite's properties and bounds, and shrinks the first violation to a replayable report.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/properties/generators.h"
#include "oblique/protocol/protocol.h"

namespace oblique::verify {

struct VerifyOptions {
  std::string command;  ///< the implementation, run under /bin/sh -c
  std::vector<Convention> conventions{Convention::gl};
  std::vector<generators::Family> families;  ///< empty: every family
  protocol::Precision precision = protocol::Precision::float64;
  long cases = 10000;
  std::uint64_t seed = 0;  ///< 0: a fresh one (printed, so the run can be repeated)
  double time_limit_seconds = 60;
  double request_timeout_seconds = 10;
  std::string report_dir = "oblique-reports";
  std::string self;  ///< how to invoke this tool, for the replay commands in reports
  bool progress = true;
};

/// Exit codes: 0 no violation within the budget, 1 a violation (or a crash or hang of the
/// implementation) with a report written, 2 usage or protocol errors.
int run_verify(const VerifyOptions& options, std::ostream& out, std::ostream& err);

}  // namespace oblique::verify
