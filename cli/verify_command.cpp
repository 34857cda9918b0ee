// `oblique verify`: another implementation, over the apply protocol; the contract from its file
// and flags.
#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "oblique/cases/contract.h"
#include "oblique/protocol/names.h"
#include "oblique/shader/shader_function.h"
#include "oblique/verify/verifier.h"

namespace oblique::cli {

namespace {

/// What the command line says, before it is read whole.
struct Settings {
  oblique::verify::VerifyOptions options;
  std::string precision = "double";
  std::shared_ptr<ContractFlags> contract = std::make_shared<ContractFlags>();
  bool answers_only = false;
  std::vector<std::string> arguments;  // after "verify", for the replay command
  bool quiet = false;
  std::string consumers;  // --consumers LIST
  // Each mode's own flags, gathered into its options when the command line is read whole.
  oblique::verify::MatrixMode matrix;
  bool rasterize = false;
  oblique::verify::RasterOptions raster;
  std::optional<oblique::oracle::MirrorDesign> mirror_design;
  std::string replay;
};

/// The mode the flags ask for, with its own options: --replay (the report says its mode),
/// --consumers KINDS, or the matrix; a flag of another mode is an error, not ignored.
oblique::Expected<oblique::verify::Mode> verify_mode(
    const Settings& s, std::vector<oblique::protocol::ConsumerKind> kinds) {
  using oblique::verify::Mode;
  using Failure = oblique::Expected<Mode>;
  const oblique::oracle::MirrorDesign design =
      s.mirror_design.value_or(oblique::oracle::MirrorDesign::reflected_view);
  if (!s.replay.empty()) {
    // The report says its mode: the flags of a run's modes would be left unread.
    if (!kinds.empty() || s.rasterize || !s.matrix.accuracy_dir.empty() || s.matrix.keep_going ||
        !s.matrix.regressions.empty() || !s.matrix.save_regressions.empty())
      return Failure::failure(
          "--replay judges one report's case again, in the report's own mode: --consumers, "
          "--rasterize, --accuracy, --keep-going and the regression folders do not apply to it");
    return Mode(oblique::verify::ReplayMode{s.replay, s.raster.device, design});
  }
  if (!kinds.empty()) {
    if (!s.matrix.accuracy_dir.empty())
      return Failure::failure(
          "--accuracy profiles oblique matrices; it does not apply to --consumers");
    if (s.rasterize)
      return Failure::failure(
          "--rasterize draws oblique matrices; it does not apply to --consumers");
    if (s.matrix.keep_going || !s.matrix.regressions.empty() || !s.matrix.save_regressions.empty())
      return Failure::failure(
          "--keep-going, --regressions and --save-regressions do not apply to --consumers (a "
          "consumer run stops at its first violation; replay its report with --replay)");
    return Mode(oblique::verify::ConsumerMode{std::move(kinds), design});
  }
  if (s.mirror_design)
    return Failure::failure(
        "--mirror-design is the design of a consumer program's mirror_view; it applies to "
        "--consumers (and to --replay of an older consumer report)");
  oblique::verify::MatrixMode matrix = s.matrix;
  if (s.rasterize) matrix.rasterize = s.raster;
  return Mode(std::move(matrix));
}

}  // namespace

void setup_verify(CLI::App& app, int& exit_code, int argc, char** argv) {
  const char* self = argv[0];
  auto settings = std::make_shared<Settings>();
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) != "verify") continue;
    settings->arguments.assign(argv + i + 1, argv + argc);
    break;
  }
  oblique::verify::VerifyOptions& options = settings->options;
  CLI::App* verify = app.add_subcommand(
      "verify",
      "Check another implementation of the oblique modification: start COMMAND once, send it "
      "generated requests in the protocol of `oblique apply` (one JSON line each on its standard "
      "input; it answers one line each, flushed), judge every answer with the property suite, and "
      "shrink the first violation to a report. Exit 0: no violation; 1: a violation (report "
      "written); 2: usage or protocol error.");
  // --impl, or --shader for depth functions: run_verify() says when neither is given.
  verify->add_option("--impl", options.command, "The implementation's command (run by sh)");
  verify
      ->add_option("--layout", options.layout,
                   "How the implementation takes and writes its matrices: row_major (M by rows, "
                   "the protocol's order; the default), column_major (M by columns, OpenGL's "
                   "storage) or row_vectors (a row-vector engine's R = M^T by rows: Direct3D, "
                   "DirectXMath; the same numbers as column_major). Every 4x4 matrix of a request "
                   "is put in that order at the program's end, and every one it answers read so")
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(oblique::protocol::kLayoutNames),
                                                     std::end(oblique::protocol::kLayoutNames))));
  // The contract's fields, each a flag taking a comma list of the names its JSON field takes.
  auto contract_flag = [&](const std::string& flag, const std::string& field,
                           const std::string& what) {
    add_contract_flag(verify, settings->contract, flag, field, what);
  };
  using oblique::protocol::name_list;
  contract_flag("--preset", "preset",
                "A contract preset to start from (it replaces --contract's fields; the other "
                "contract flags change it): engine (the projections an engine builds, flipped ones "
                "included; unit planes; "
                "answers only)");
  contract_flag("--convention", "conventions",
                "Conventions to request, a comma list or all (default gl): " +
                    name_list(oblique::names_in(oblique::convention_names)));
  contract_flag("--families", "families",
                "Comma list of projection families (default: all): " +
                    name_list(oblique::names_in(oblique::cases::family_names)));
  CLI::Option* const precision_flag = add_precision_option(
      verify, settings->precision, "Scalar type of inputs and bounds (float with --shader)",
      {oblique::protocol::Precision::float32, oblique::protocol::Precision::float64});
  verify
      ->add_option("--cases", options.cases,
                   "Number of generated requests (default: no limit, --time-limit ends the run)")
      ->check(CLI::PositiveNumber);
  verify->add_option("--seed", options.seed, "Random seed (default: a fresh one, printed)");
  verify
      ->add_option("--time-limit", options.time_limit_seconds,
                   "Stop after this many seconds, shrinking included")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify
      ->add_option("--timeout", options.request_timeout_seconds,
                   "Seconds to wait for one answer before calling the implementation hung")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify->add_option("--report-dir", options.report_dir, "Where the counterexample report goes")
      ->capture_default_str();
  verify->add_flag("--quiet", settings->quiet, "No progress lines on standard error");
  verify
      ->add_option("--threads", options.threads,
                   "Threads that judge the answers (default: the machine's hardware threads)")
      ->capture_default_str();
  // The rest of the contract: what the implementation promises.
  verify->add_flag("--answers-only", settings->answers_only,
                   "Send only inputs with an exact answer (an implementation without statuses; "
                   "the same as --statuses answers_only)");
  contract_flag("--statuses", "statuses",
                "How its statuses are judged: " +
                    name_list(oblique::names_in(oblique::status_contract_names)) +
                    " (default any_refusal), or a comma list of the refusal codes it implements "
                    "(inputs needing others are not sent, these must be exact): " +
                    name_list(oblique::refusal_names()));
  contract_flag("--planes", "planes", "unit: planes with a unit normal; any (default)");
  contract_flag("--places", "places",
                "Comma list of hard places to send (default: all): " +
                    name_list(oblique::names_in(oblique::cases::place_names)));
  contract_flag("--defects", "defects",
                "Comma list of kinds of input without an answer to send (default: all): " +
                    name_list(oblique::names_in(oblique::cases::defect_names)));
  contract_flag("--properties", "properties",
                "Comma list of the properties judged (default: all): " +
                    name_list(oblique::property_names()));
  contract_flag("--exclude", "exclude",
                "Comma list of families, hard places and kinds of input without an answer to "
                "leave out");
  verify->add_option("--contract", settings->contract->file,
                     "A JSON contract file (fields: families, conventions, places, planes, "
                     "statuses, defects, properties, row3_accuracy, exclude; see the README); "
                     "flags replace the fields they name");
  verify->add_flag("--strict", options.strict,
                   "A claimed family, convention or consumer kind with more than 10% of its "
                   "cases left out fails the run (exit 2) instead of a warning");
  verify->add_flag("--keep-going", settings->matrix.keep_going,
                   "Go on after a finding; report each kind (property x family x place) once");
  CLI::Option* const consumers_flag = verify->add_option(
      "--consumers", settings->consumers,
      "Ask the code around the matrix instead: a comma list of request kinds, or all: " +
          name_list(oblique::names_in(oblique::protocol::consumer_kind_names)) +
          " (docs/verify.md)");
  verify
      ->add_option_function<std::string>(
          "--mirror-design",
          [settings](const std::string& name) {
            settings->mirror_design = oblique::oracle::parse_mirror_design(name);
          },
          "With --consumers mirror_view: the design its mirror pass's camera has: reflected_view "
          "(view R, the default) or proper_camera (diag(-1, 1, 1, 1) view R, the horizontal flip "
          "done in the projection or the texture lookup)")
      ->check(CLI::IsMember({"reflected_view", "proper_camera"}));
  verify->add_option(
      "--shader", options.shader,
      "With --consumers view_position,linear_depth: a GLSL or HLSL file whose functions answer "
      "them on the GPU path instead of --impl (FILE:FUNCTION for one kind; FILE alone: functions "
      "named after the kinds); parameters are bound by name (docs/shaders.md); float");
  verify
      ->add_option_function<std::string>(
          "--shader-language",
          [settings](const std::string& name) {
            settings->options.shader_language = oblique::shader::parse_language(name);
          },
          "glsl or hlsl (default: by the file's extension, .hlsl and .fx HLSL)")
      ->check(CLI::IsMember({"glsl", "hlsl"}));
  add_uv_v_option(verify, options.shader_v);
  add_vectors_option(verify, options.shader_vectors);
  add_sampling_option(verify, options.sampling);
  verify->add_option("-D,--define", options.shader_defines,
                     "With --shader: a define of the engine's, NAME or NAME=VALUE (repeat it): the "
                     "shader's #if variants are chosen under them and OBLIQUE_CONVENTION");
  verify->add_flag("--rasterize", settings->rasterize,
                   "Also draw answers on a real rasterizer (EGL + OpenGL 4.5, llvmpipe): the "
                   "first, one in --raster-every, and every finding's; an answer that passes the "
                   "properties but fails there is a finding of its own (docs/raster.md). Exit 3 "
                   "when the rasterizer cannot judge");
  verify
      ->add_option("--device", settings->raster.device,
                   "With --rasterize or --shader: software (llvmpipe, the default) or gpu")
      ->check(CLI::IsMember({"software", "gpu"}));
  verify
      ->add_option("--raster-size", settings->raster.size,
                   "With --rasterize: frames of N x N pixels, one sample each (default 256)")
      ->check(CLI::Range(16, 4096));
  verify
      ->add_option("--raster-every", settings->raster.every,
                   "With --rasterize: draw one answer in N (default 1000)")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            char* end = nullptr;
            errno = 0;
            const long n = std::strtol(v.c_str(), &end, 10);
            return v.empty() || *end != '\0' || errno == ERANGE || n < 1
                       ? "must be a whole number of at least 1, not " + v
                       : "";
          },
          "N >= 1"));
  verify
      ->add_option("--accuracy", settings->matrix.accuracy_dir,
                   "Profile every answer that passes: row 3's error against the exact answer "
                   "by family, place and stiffness, the round trip timed, beside the core's "
                   "methods on the same cases; the report (accuracy.md, .csv, charts) written "
                   "into this folder when the run holds")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            return v.empty() ? "names no folder (an empty --accuracy would turn the profile off)"
                             : "";
          },
          "DIR"));
  verify->add_option("--replay", settings->replay,
                     "Re-judge the case of a report (its .json) with --impl: exit 0 or 1 (3: a "
                     "raster report the rasterizer cannot judge)");
  verify->add_option("--regressions", settings->matrix.regressions,
                     "Replay every report (.json) in this folder before the run");
  verify->add_option("--save-regressions", settings->matrix.save_regressions,
                     "Keep each new shrunk case's report in this folder too");
  verify->callback([settings, &exit_code, self, consumers_flag, precision_flag] {
    oblique::verify::VerifyOptions& options = settings->options;
    const oblique::Expected<oblique::Contract> contract = settings->contract->read(
        settings->answers_only
            ? std::vector<ContractFlags::Field>{{"statuses", "--answers-only", "answers_only"}}
            : std::vector<ContractFlags::Field>{});
    if (!contract) {
      std::cerr << "oblique verify: " << contract.error() << "\n";
      exit_code = 2;
      return;
    }
    options.contract = *contract;
    std::vector<oblique::protocol::ConsumerKind> kinds;
    for (const std::string& name : split_list(settings->consumers)) {
      if (name == "all") {
        kinds.assign(std::begin(oblique::protocol::all_consumer_kinds),
                     std::end(oblique::protocol::all_consumer_kinds));
      } else if (const auto kind = oblique::protocol::parse_consumer_kind(name)) {
        if (std::find(kinds.begin(), kinds.end(), *kind) == kinds.end()) kinds.push_back(*kind);
      } else {
        std::cerr << "oblique verify: --consumers: "
                  << oblique::protocol::unknown_name(
                         "request kind", name,
                         oblique::names_in(oblique::protocol::consumer_kind_names))
                  << "\n";
        exit_code = 2;
        return;
      }
    }
    if (consumers_flag->count() > 0 && kinds.empty()) {  // `--consumers ""`: not the matrix
      std::cerr << "oblique verify: --consumers names no request kind (a comma list of "
                << oblique::protocol::name_list(
                       oblique::names_in(oblique::protocol::consumer_kind_names))
                << ", or all)\n";
      exit_code = 2;
      return;
    }
    // The mode, with its own flags; a flag of another mode is an error, not ignored.
    const oblique::Expected<oblique::verify::Mode> mode = verify_mode(*settings, std::move(kinds));
    if (!mode) {
      std::cerr << "oblique verify: " << mode.error() << "\n";
      exit_code = 2;
      return;
    }
    options.precision = *oblique::protocol::parse_precision(settings->precision);
    if (!options.shader.empty()) {
      // A shader computes in float: the default precision is float, and another is an error.
      if (!precision_flag->count()) options.precision = oblique::protocol::Precision::float32;
      options.shader_device = settings->raster.device;
    }
    options.progress = !settings->quiet;
    options.self = self;
    options.arguments = settings->arguments;
    exit_code = static_cast<int>(oblique::verify::run_verify(options, *mode, std::cout, std::cerr));
  });
}

}  // namespace oblique::cli
