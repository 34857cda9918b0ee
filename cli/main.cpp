// oblique: the command-line tool. `oblique apply` answers JSON Lines requests on standard input;
// `oblique verify` checks another implementation that speaks the same protocol; `oblique check`
// checks the mirrors and clip planes of a scene file.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/fuzzing/fuzz_report.h"
#include "oblique/properties/contract.h"
#include "oblique/protocol/apply.h"
#include "oblique/protocol/names.h"
#include "oblique/report/accuracy_report.h"
#include "oblique/report/depth_report.h"
#include "oblique/scene/check.h"
#include "oblique/scene/plot.h"
#include "oblique/verify/verifier.h"
#include "oblique_version.h"

namespace {

/// Prints the files a report wrote, one per line: exit status 0; 2 when it could not write them
/// (the reason is on standard error already).
int print_paths(const std::optional<std::vector<std::filesystem::path>>& paths) {
  if (!paths) return 2;
  for (const auto& path : *paths) std::cout << path.string() << "\n";
  return 0;
}

/// Splits "a,b,c" (spaces ignored).
std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

/// A check that the value is one of `names` (a name table's), saying otherwise which is closest:
/// `unknown convention "opengl" (known: gl, zero_one, reversed_z)`. Its description in the help
/// lists the names.
CLI::Validator one_of(const std::vector<std::string>& names, const std::string& what) {
  return CLI::Validator(
      [names, what](std::string& value) {
        if (std::find(names.begin(), names.end(), value) != names.end()) return std::string();
        return oblique::protocol::unknown_name(what, value, names);
      },
      "{" + oblique::protocol::name_list(names) + "}");
}

/// --precision: the protocol's scalar names (float, double, long_double), the same option for
/// apply, verify and check; `allowed` are those the subcommand computes or judges in.
CLI::Option* add_precision_option(CLI::App* app, std::string& precision, const std::string& what,
                                  std::vector<oblique::protocol::Precision> allowed) {
  std::vector<std::string> names;
  for (const oblique::protocol::Precision p : allowed)
    names.emplace_back(oblique::protocol::precision_name(p));
  return app->add_option("--precision", precision, what)
      ->check(one_of(names, "precision"))
      ->capture_default_str();
}

struct CheckSettings {
  std::string scene_path;
  bool as_json = false;
  std::string precision = "double";  ///< --precision: of the requests --impl gets, and its bounds
  std::string impl;      ///< --impl CMD: the user's implementation, over the apply protocol
  std::string plot_dir;  ///< --plot DIR
  double timeout_seconds = 10;
};

int run_check(const CheckSettings& settings) {
  const std::string& path = settings.scene_path;
  const oblique::scene::ParsedScene parsed = oblique::scene::read_scene_file(path);
  if (!parsed.scene) {
    std::cerr << "oblique check: " << path << ": " << parsed.error << "\n";
    return 2;
  }
  oblique::scene::SceneCheck check = oblique::scene::check_scene(*parsed.scene);
  check.impl_precision = *oblique::protocol::parse_precision(settings.precision);
  if (!settings.impl.empty()) {
    const oblique::Expected<std::size_t> judged = oblique::scene::judge_implementation(
        *parsed.scene, check, settings.impl, settings.timeout_seconds);
    if (!judged) {
      std::cerr << "oblique check: " << judged.error() << "\n";
      return 2;
    }
  }
  std::cout << (settings.as_json ? oblique::scene::to_json(check) + "\n"
                                 : oblique::scene::to_text(check));
  if (!settings.plot_dir.empty()) {
    const oblique::scene::PlotResult plot =
        oblique::scene::write_plot(*parsed.scene, check, settings.plot_dir);
    if (!plot.error.empty()) {
      std::cerr << "oblique check: cannot write the picture to " << settings.plot_dir << ": "
                << plot.error << "\n";
      return 2;
    }
    // With --json, standard output stays one JSON object: the paths go to standard error.
    std::ostream& paths = settings.as_json ? std::cerr : std::cout;
    if (!settings.as_json) paths << "\n";
    // The view across the first mirror or portal first: it shows the pass.
    if (!plot.across.empty())
      paths << "picture: " << plot.across.string() << " (across " << plot.across_surface << ")\n";
    for (const auto& file : plot.written) {
      if (file.extension() == ".png" && file != plot.across)
        paths << "picture: " << file.string() << "\n";
    }
  }
  return check.passes() ? 0 : 1;
}

/// Each subcommand: its options and what it runs once parsed (CLI11's callbacks). A callback
/// stores its exit status in `exit_code`.

void setup_apply(CLI::App& app, int& exit_code) {
  struct Settings {
    std::string convention = "gl", method = "auto", precision = "double";
  };
  auto settings = std::make_shared<Settings>();
  CLI::App* apply = app.add_subcommand(
      "apply",
      "Read JSON Lines requests {\"projection\": [16 numbers, row-major], \"plane\": [4 numbers], "
      "\"convention\": ...} on standard input; answer one line each: {\"status\": \"ok\", "
      "\"projection\": [...]} or {\"status\": CODE, \"message\": ...}. Exit 0 when every line was "
      "ok, 1 otherwise, 2 when the answers could not be written. A line longer than 1 MiB is "
      "answered invalid_input and skipped.");
  apply
      ->add_option("--convention", settings->convention,
                   "Depth convention of requests that name none")
      ->check(one_of(oblique::convention_names(), "convention"))
      ->capture_default_str();
  apply
      ->add_option("--method", settings->method,
                   "auto: closed form for the perspective shape, else general; accurate: every "
                   "entry within 2 ulp of the exact answer (measured: correctly rounded)")
      ->check(one_of(
          oblique::protocol::names_of<oblique::Method>(oblique::all_methods, oblique::method_name),
          "method"))
      ->capture_default_str();
  add_precision_option(
      apply, settings->precision, "Scalar type of the computation",
      {std::begin(oblique::protocol::all_precisions), std::end(oblique::protocol::all_precisions)});
  apply->callback([settings, &exit_code] {
    oblique::protocol::ApplyOptions options;
    options.convention = *oblique::parse_convention(settings->convention);
    options.method = *oblique::parse_method(settings->method);
    options.precision = *oblique::protocol::parse_precision(settings->precision);
    std::ios::sync_with_stdio(false);
    std::cin.tie(nullptr);
    errno = 0;
    exit_code = oblique::protocol::serve(std::cin, std::cout, options);
    if (exit_code == 2) {
      std::cerr << "oblique apply: cannot write the answers to standard output"
                << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
    }
  });
}

void setup_verify(CLI::App& app, int& exit_code, int argc, char** argv) {
  const char* self = argv[0];
  struct Settings {
    oblique::verify::VerifyOptions options;
    std::string precision = "double", contract;
    /// The contract's fields given as flags: the JSON field's name, the flag, its list.
    struct Field {
      std::string name, flag, list;
    };
    std::vector<Field> fields;
    bool answers_only = false;
    std::vector<std::string> arguments;  // after "verify", for the replay command
    bool quiet = false;
  };
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
  verify->add_option("--impl", options.command, "The implementation's command (run by sh)")
      ->required();
  // The contract's fields, each a flag taking a comma list of the names its JSON field takes.
  auto contract_flag = [&](const std::string& flag, const std::string& field,
                           const std::string& what) {
    verify->add_option_function<std::string>(
        flag,
        [settings, field, flag](const std::string& list) {
          settings->fields.push_back({field, flag, list});
        },
        what);
  };
  using oblique::protocol::name_list;
  contract_flag("--convention", "conventions",
                "Conventions to request, a comma list or all (default gl): " +
                    name_list(oblique::convention_names()));
  contract_flag(
      "--families", "families",
      "Comma list of projection families (default: all): " + name_list(oblique::family_names()));
  add_precision_option(
      verify, settings->precision, "Scalar type of inputs and bounds",
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
                "How its statuses are judged: " + name_list(oblique::status_contract_names()) +
                    " (default any_refusal), or a comma list of the refusal codes it implements "
                    "(inputs needing others are not sent, these must be exact): " +
                    name_list(oblique::refusal_names()));
  contract_flag("--planes", "planes", "unit: planes with a unit normal; any (default)");
  contract_flag(
      "--places", "places",
      "Comma list of hard places to send (default: all): " + name_list(oblique::place_names()));
  contract_flag("--defects", "defects",
                "Comma list of kinds of input without an answer to send (default: all): " +
                    name_list(oblique::defect_names()));
  contract_flag("--properties", "properties",
                "Comma list of the properties judged (default: all): " +
                    name_list(oblique::property_names()));
  contract_flag("--exclude", "exclude",
                "Comma list of families, hard places and kinds of input without an answer to "
                "leave out");
  verify->add_option("--contract", settings->contract,
                     "A JSON contract file (fields: families, conventions, places, planes, "
                     "statuses, defects, properties, row3_accuracy, exclude; see the README); "
                     "flags replace the fields they name");
  verify->add_flag("--keep-going", options.keep_going,
                   "Go on after a finding; report each kind (property x family x place) once");
  verify->add_option("--replay", options.replay,
                     "Re-judge the case of a report (its .json) with --impl: exit 0 or 1");
  verify->add_option("--regressions", options.regressions,
                     "Replay every report (.json) in this folder before the run");
  verify->add_option("--save-regressions", options.save_regressions,
                     "Keep each new shrunk case's report in this folder too");
  verify->callback([settings, &exit_code, self] {
    oblique::verify::VerifyOptions& options = settings->options;
    oblique::Expected<oblique::Contract> contract = oblique::Contract{};
    if (!settings->contract.empty()) contract = oblique::read_contract_file(settings->contract);
    if (contract && settings->answers_only)
      contract = oblique::with_field(std::move(*contract), "statuses", {"answers_only"});
    for (const auto& field : settings->fields) {
      if (!contract) break;
      contract = oblique::with_field(std::move(*contract), field.name, split_list(field.list));
      if (!contract) {  // say it in the flag's words, not the JSON field's
        std::string error = contract.error();
        for (const std::string& json_name : {"\"" + field.name + "\"", field.name}) {
          if (error.rfind(json_name + ": ", 0) == 0) {
            error = field.flag + error.substr(json_name.size());
            break;
          }
        }
        contract = oblique::Expected<oblique::Contract>::failure(error);
      }
    }
    if (!contract) {
      std::cerr << "oblique verify: " << contract.error() << "\n";
      exit_code = 2;
      return;
    }
    options.contract = std::move(*contract);
    options.precision = *oblique::protocol::parse_precision(settings->precision);
    options.progress = !settings->quiet;
    options.self = self;
    options.arguments = settings->arguments;
    exit_code = oblique::verify::run_verify(options, std::cout, std::cerr);
  });
}

void setup_check(CLI::App& app, int& exit_code) {
  auto settings = std::make_shared<CheckSettings>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Check the mirrors, portals and clip planes of a scene file: for each pass (recursively up "
      "to the scene's max_depth), render or skip (with the reason), the pass camera's view and "
      "oblique projection, the properties that apply, the depth precision left and the scissor "
      "rectangle. Exit 0: every rendered pass passes; 1: a property fails (ours, or the "
      "implementation's with --impl); 2: the scene cannot be read, the implementation does not "
      "answer, or the output or picture cannot be written.");
  check->add_option("SCENE", settings->scene_path, "The scene file (JSON; see the README)")
      ->required();
  check->add_flag("--json", settings->as_json, "Print one JSON object instead of a table");
  check->add_option("--impl", settings->impl,
                    "Send each rendered pass's request to this command (run by /bin/sh, speaking "
                    "the apply protocol) and judge its answers as oblique verify does");
  add_precision_option(
      check, settings->precision,
      "With --impl: the scalar type the implementation computes in; its requests "
      "are rounded to it and its answers judged with its bounds (as oblique "
      "verify --precision)",
      {std::begin(oblique::protocol::all_precisions), std::end(oblique::protocol::all_precisions)});
  check
      ->add_option("--timeout", settings->timeout_seconds,
                   "With --impl: seconds to wait for each answer")
      ->check(CLI::PositiveNumber);
  check->add_option("--plot", settings->plot_dir,
                    "Write a top and a side view (gnuplot PNG) of the scene and its passes here");
  check->callback([settings, &exit_code] { exit_code = run_check(*settings); });
}

void setup_fuzz_report(CLI::App& app, int& exit_code, const char* self) {
  auto options = std::make_shared<oblique::fuzzing::FuzzReportOptions>();
  options->self = self;
  CLI::App* sub = app.add_subcommand(
      "fuzz-report",
      "Run each input (crash files of a fuzz target; directories are walked) alone through the "
      "target and write one report per distinct finding: a property (by property, "
      "implementation, projection family and convention, with the report verify writes), a "
      "sanitizer's error (by kind and function), a crash or a hang; and an index. Exit 0: no "
      "input fails now; 1: findings (reports written); 2: the target or the inputs cannot be "
      "run, or the reports cannot be written.");
  sub->add_option("--target", options->target,
                  "The fuzz target's command (its libFuzzer binary or replay build), run by sh "
                  "with one input file")
      ->required();
  sub->add_option("INPUTS", options->inputs, "Input files or directories")->required();
  sub->add_option("--report-dir", options->report_dir, "Where the reports go")
      ->capture_default_str();
  sub->add_option("--timeout", options->timeout_seconds, "Seconds one input may take")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->callback([options, &exit_code] {
    const oblique::Expected<oblique::fuzzing::FuzzReport> report =
        oblique::fuzzing::fuzz_report(*options);
    if (!report) {
      std::cerr << "oblique fuzz-report: " << report.error() << "\n";
      exit_code = 2;
      return;
    }
    std::cout << "oblique fuzz-report: " << report->inputs << " inputs, " << report->findings.size()
              << " distinct findings, " << report->holds << " run without a finding now"
              << (report->index.empty() ? "" : "; index: " + report->index) << "\n";
    for (const auto& f : report->findings)
      std::cout << "  " << f.key << ": " << f.inputs.size() << " inputs, report " << f.report
                << "\n";
    exit_code = report->findings.empty() ? 0 : 1;
  });
}

void setup_report(CLI::App& app, int& exit_code) {
  struct Settings {
    oblique::report::AccuracyOptions accuracy;
    std::string accuracy_out = "report-out";
    bool quiet = false;
    oblique::report::DepthOptions depth;
    std::string depth_out = "report-out";
  };
  auto settings = std::make_shared<Settings>();
  CLI::App* report =
      app.add_subcommand("report", "Measurement reports (CSV, Markdown, PNG charts)");
  report->require_subcommand(1);
  CLI::App* accuracy = report->add_subcommand(
      "accuracy",
      "Error against run time: every method x scalar type x input regime (typical, tiny near "
      "planes, f/n to 1e12, infinite, orthographic, planes near the eye, the far corner and the "
      "standard near plane, huge and tiny scales) against the exact oracle; stiffness sweeps; the "
      "checker's bound against the measured error. Writes accuracy.csv, stiffness.csv, "
      "accuracy.md and (with gnuplot) accuracy.png and stiffness.png.");
  accuracy->add_option("--out", settings->accuracy_out, "Output directory")->capture_default_str();
  accuracy
      ->add_option("--cases", settings->accuracy.cases_per_step,
                   "Cases per regime and stiffness step")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  accuracy->add_option("--seed", settings->accuracy.seed, "Random seed")->capture_default_str();
  accuracy->add_flag("--quiet", settings->quiet, "No progress lines on standard error");
  accuracy->callback([settings, &exit_code] {
    oblique::report::AccuracyOptions& options = settings->accuracy;
    options.out_dir = settings->accuracy_out;
    options.progress = !settings->quiet;
    const auto measured = oblique::report::measure_accuracy(options, std::cerr);
    exit_code = print_paths(oblique::report::write_accuracy_report(measured, options, std::cerr));
  });
  CLI::App* depth = report->add_subcommand(
      "depth",
      "Depth precision: the paper's Figure 5 (maximum NDC z along the view axis, Eq. 19, against "
      "the plane's angle and distance), checked against the core's matrices in every convention, "
      "and the bits of a 24-bit fixed-point and a 32-bit float depth buffer still used along view "
      "directions. Writes figure5.csv, depth_bits.csv, depth.md and (with gnuplot) figure5.png.");
  depth->add_option("--out", settings->depth_out, "Output directory")->capture_default_str();
  depth->add_option("--far", settings->depth.far_distance, "Far distance of the frustum")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  depth->callback([settings, &exit_code] {
    oblique::report::DepthOptions& options = settings->depth;
    options.out_dir = settings->depth_out;
    if (!(options.far_distance > options.near_distance)) {
      std::cerr << "oblique report depth: --far must exceed the near distance "
                << options.near_distance << "\n";
      exit_code = 2;
      return;
    }
    const auto measured = oblique::report::measure_depth(options);
    exit_code = print_paths(oblique::report::write_depth_report(measured, options, std::cerr));
  });
}

/// The deepest subcommand the parse reached (`report accuracy`), or the app.
CLI::App* deepest(CLI::App* app) {
  while (!app->get_subcommands().empty()) app = app->get_subcommands().front();
  return app;
}

/// Says what was not understood, with the closest known name: a word where a subcommand goes
/// (`oblique verfy`: "did you mean verify?"), a flag the subcommand does not have.
void explain_unknown(CLI::App* where, const std::vector<std::string>& unexpected) {
  std::vector<std::string> subcommands, flags;
  for (const CLI::App* sub : where->get_subcommands([](CLI::App*) { return true; }))
    subcommands.push_back(sub->get_name());
  for (const CLI::Option* option : where->get_options()) {
    for (const std::string& name : option->get_lnames()) flags.push_back("--" + name);
  }
  const std::string who =
      where->get_parent() ? "oblique " + where->get_name() : std::string("oblique");
  // A flag's value follows it: with an unknown flag, only the flags are named.
  const bool any_flag = std::any_of(unexpected.begin(), unexpected.end(),
                                    [](const std::string& a) { return a.rfind("-", 0) == 0; });
  for (const std::string& arg : unexpected) {
    const bool is_flag = arg.rfind("-", 0) == 0;
    if (any_flag && !is_flag) continue;
    const std::string name = is_flag ? arg.substr(0, arg.find('=')) : arg;
    if (!is_flag && subcommands.empty()) {
      std::cerr << who << ": unexpected argument \"" << arg << "\"\n";
      continue;
    }
    std::cerr << who << ": "
              << oblique::protocol::unknown_name(is_flag ? "flag" : "subcommand", name,
                                                 is_flag ? flags : subcommands)
              << "\n";
  }
  std::cerr << "Run " << who << " --help for the usage.\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"oblique: oblique near-plane clipping, verified"};
  app.set_version_flag(
      "--version", std::string("oblique ") + OBLIQUE_VERSION + " (commit " + OBLIQUE_COMMIT + ")",
      "Print the version and the commit it was built from");
  app.require_subcommand(1);
  int exit_code = 2;
  setup_apply(app, exit_code);
  setup_verify(app, exit_code, argc, argv);
  setup_check(app, exit_code);
  setup_fuzz_report(app, exit_code, argv[0]);
  setup_report(app, exit_code);
  // A first word that is no subcommand: say so, with the closest, before CLI11 asks for one.
  const std::string first = argc > 1 ? argv[1] : "";
  if (!first.empty() && first[0] != '-' &&
      app.get_subcommands([&](CLI::App* s) { return s->get_name() == first; }).empty()) {
    explain_unknown(&app, {first});
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // What was left unparsed (a mistyped flag or subcommand): named, with the closest.
    CLI::App* where = deepest(&app);
    if (e.get_exit_code() != 0 && !where->remaining().empty()) {
      explain_unknown(where, where->remaining());
      return 2;
    }
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // --help exits 0; every usage error exits 2
  }
  // What a subcommand printed must have reached standard output (a full disk, a closed pipe).
  if (exit_code != 2 && !std::cout.flush()) {
    std::cerr << "oblique: cannot write to standard output"
              << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
    return 2;
  }
  return exit_code;
}
