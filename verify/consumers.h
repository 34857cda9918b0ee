// `oblique verify --consumers`: a program's code around the matrix (the consumer request kinds),
// asked in batches of rounds planned as every tool plans them (oracle::consumer_asks()),
// judged on several threads and counted in order, a violation written as a report that replays
// its round exactly (M and C in exact hex, the round's picks). Internal to oblique::verify.
#pragma once

#include <iosfwd>
#include <string>

#include "oblique/protocol/json.h"
#include "oblique/verify/verifier.h"

namespace oblique::verify {

/// The run: rounds until --time-limit or --cases, stopping at the first violation.
Verdict verify_consumers(const VerifyOptions& options, const ConsumerMode& mode, std::ostream& out,
                         std::ostream& err);

/// --replay of a consumer report: its round again through the program; 0 holds, 1 violated.
Verdict replay_consumer_report(const VerifyOptions& options, const ReplayMode& mode,
                               const protocol::JsonValue& report, std::ostream& out,
                               std::ostream& err);

}  // namespace oblique::verify
