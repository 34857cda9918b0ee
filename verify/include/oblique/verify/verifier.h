// `oblique verify`: drives an external implementation (any program that speaks the JSON Lines
// protocol of `oblique apply`) with the property suite's generators, judges every answer with
// the suite's properties and bounds, and shrinks the first violation to a replayable report.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "oblique/cases/contract.h"
#include "oblique/oracle/consumers.h"
#include "oblique/protocol/consumer_messages.h"
#include "oblique/protocol/matrix_order.h"
#include "oblique/protocol/protocol.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/shader/shader_function.h"
#include "oblique/status.h"

namespace oblique::verify {

/// The machine's hardware threads (at least 1).
int default_threads();

/// What every mode of `oblique verify` has: the program, what it promises, the budget, where the
/// reports go.
struct VerifyOptions {
  std::string command;  ///< the implementation, run under /bin/sh -c
  /// --layout: how the program takes and writes its matrices (column_major and row_vectors: by
  /// columns, each request and answer put in that order at the program's end alone).
  std::string layout = "row_major";
  protocol::MatrixOrder matrix_order() const {
    return protocol::matrix_order_of_layout(layout).value_or(protocol::MatrixOrder::rows);
  }
  /// --shader FILE[:FUNCTION]: with --consumers view_position, linear_depth, the user's GLSL or
  /// HLSL function answers them on the GPU path (oblique/shader; float, judged with the GPU's
  /// arithmetic) instead of a program; `command` then only names it in reports.
  std::string shader;
  std::optional<shader::Language> shader_language;  ///< none: by the file's extension
  std::string shader_device = "software";           ///< software (llvmpipe) or gpu
  /// --define NAME[=VALUE]: the engine's defines the shader is preprocessed and compiled under.
  std::vector<std::string> shader_defines;
  /// --uv-v: which way the shader's v runs (none: its language's default, GLSL up, HLSL down).
  std::optional<shader::VDirection> shader_v;
  /// --vectors: how the shader's matrices multiply vectors (row: it is handed M^T).
  shader::Vectors shader_vectors = shader::Vectors::column;
  /// --sampling: where depth functions are asked, pixel centres of real targets or arbitrary
  /// positions.
  oracle::Sampling sampling = oracle::Sampling::pixels;
  /// What the implementation promises, and so which inputs it is sent and how its answers are
  /// judged (the summary says what was left out). Its empty conventions mean gl (the protocol's
  /// default), its unset statuses any_refusal (a program need not name our refusals).
  Contract contract;
  protocol::Precision precision = protocol::Precision::float64;
  long cases = 0;                       ///< 0: no limit (the time limit ends the run)
  std::uint64_t seed = 0;               ///< 0: a fresh one (printed, so the run can be repeated)
  double time_limit_seconds = 60;       ///< (0, 1e8]
  double request_timeout_seconds = 10;  ///< [0.001, 1e8]
  std::string report_dir = "oblique-reports";
  std::string self;  ///< how to invoke this tool, for the replay commands in reports
  /// The run's own arguments after `verify`, for the replay command (which carries every flag).
  std::vector<std::string> arguments;
  bool progress = true;
  /// Threads that judge answers (default: the machine's hardware threads).
  int threads = default_threads();

  /// A claimed family, convention or consumer kind with more than run::kLeftOutWarning of
  /// its drawn cases left out fails the run (exit 2) instead of a warning line.
  bool strict = false;
};

/// --rasterize: the first answer, one in `every` after it, and every finding's answer drawn on a
/// real rasterizer (oblique::raster) in `size` x `size` frames.
struct RasterOptions {
  std::string device = "software";  ///< software (llvmpipe) or gpu
  int size = 256;                   ///< [16, 4096]
  long every = 1000;                ///< at least 1
  DepthBuffer buffer = DepthBuffer::fixed24;
};

/// The default mode: the oblique matrix asked and judged by the properties.
struct MatrixMode {
  /// Go on after a finding: each distinct kind (property x family x place) is shrunk once and
  /// reported, plus an index; the exit status is 1 if any was found.
  bool keep_going = false;
  std::string regressions;       ///< replay every report kept here before the run
  std::string save_regressions;  ///< keep each new shrunk case here
  std::optional<RasterOptions> rasterize;
  /// --accuracy DIR: every answer that passes profiled (row 3's error against the exact answer),
  /// the round trip timed, the core's methods measured on the same cases; the report written
  /// into DIR at the end of a run that holds (docs/accuracy-and-performance.md).
  std::string accuracy_dir;
};

/// --consumers: these request kinds of the code around the matrix (consumer_messages.h) asked
/// instead of the oblique matrix, round by round, judged by the consumer properties; the run
/// stops at its first violation.
struct ConsumerMode {
  std::vector<protocol::ConsumerKind> kinds;
  /// --mirror-design: the design the program's mirror_view builds (oracle/consumers.h).
  oracle::MirrorDesign mirror_design = oracle::MirrorDesign::reflected_view;
};

/// --replay: the case of one report (its JSON) judged again: exit 0 holds, 1 violated. The
/// report says its mode, scalar type and, for a raster report, its frame.
struct ReplayMode {
  std::string report;
  std::string raster_device = "software";  ///< where a raster report's frame is drawn
  /// The design a consumer report's mirror_view is judged by where the report records none.
  oracle::MirrorDesign mirror_design = oracle::MirrorDesign::reflected_view;
};

using Mode = std::variant<MatrixMode, ConsumerMode, ReplayMode>;

/// How a run ended; the CLI exits with its value.
enum class Verdict {
  holds = 0,     ///< no violation within the budget (or the kept regressions hold)
  violated = 1,  ///< a violation, or a crash or hang of the implementation: a report written
  /// usage, protocol or I/O errors: nothing was verified; or the run did not judge what the
  /// contract claims (a claimed family, convention or consumer kind with no case judged, or with
  /// too many left out under --strict)
  error = 2,
  inconclusive = 3,  ///< --rasterize: the rasterizer cannot judge (no EGL, a self-check tripped)
};

/// Runs `oblique verify` in `mode`, saying on `out` and `err` what it did.
[[nodiscard]] Verdict run_verify(const VerifyOptions& options, const Mode& mode, std::ostream& out,
                                 std::ostream& err);

}  // namespace oblique::verify
