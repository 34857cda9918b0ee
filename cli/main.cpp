// oblique: the command-line tool. `oblique apply` answers JSON Lines requests on standard input;
// `oblique verify` checks another implementation that speaks the same protocol; `oblique check`
// checks the mirrors and clip planes of a scene file.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "accuracy_report.h"
#include "check.h"
#include "depth_report.h"
#include "protocol.h"
#include "verifier.h"

namespace {

int run_apply(const oblique::protocol::ApplyOptions& options) {
  std::ios::sync_with_stdio(false);
  std::cin.tie(nullptr);
  std::string line;
  bool all_ok = true;
  for (;;) {
    // Answer promptly when the writer waits for us; batch when it has sent many lines.
    if (std::cin.rdbuf()->in_avail() <= 0) std::cout.flush();
    if (!std::getline(std::cin, line)) break;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto answer = oblique::protocol::answer_request(line, options);
    all_ok = all_ok && answer.status == oblique::Status::ok;
    std::cout << answer.line << '\n';
  }
  std::cout.flush();
  return all_ok ? 0 : 1;
}

/// Prints the files a report wrote, one per line; exit status 0.
int print_paths(const std::vector<std::filesystem::path>& paths) {
  for (const auto& path : paths) std::cout << path.string() << "\n";
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

/// Fills the conventions and families of `options` from their lists; false with a message.
bool parse_lists(const std::string& conventions, const std::string& families,
                 oblique::verify::VerifyOptions& options) {
  options.conventions.clear();
  for (const std::string& name : split_list(conventions)) {
    if (name == "all") {
      options.conventions.assign(std::begin(oblique::all_conventions),
                                 std::end(oblique::all_conventions));
    } else if (auto c = oblique::parse_convention(name)) {
      options.conventions.push_back(*c);
    } else {
      std::cerr << "oblique verify: unknown convention \"" << name
                << "\" (gl, zero_one, reversed_z or all)\n";
      return false;
    }
  }
  for (const std::string& name : split_list(families)) {
    if (auto f = oblique::generators::parse_family(name)) {
      options.families.push_back(*f);
    } else {
      std::cerr << "oblique verify: unknown family \"" << name << "\" (";
      for (auto f : oblique::generators::all_families)
        std::cerr << (f == oblique::generators::all_families[0] ? "" : ", ")
                  << oblique::generators::family_name(f);
      std::cerr << ")\n";
      return false;
    }
  }
  return !options.conventions.empty();
}

int run_check(const std::string& path, bool as_json) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    std::cerr << "oblique check: cannot read " << path << "\n";
    return 2;
  }
  std::ostringstream text;
  text << file.rdbuf();
  const oblique::scene::ParsedScene parsed = oblique::scene::parse_scene(text.str());
  if (!parsed.scene) {
    std::cerr << "oblique check: " << path << ": " << parsed.error << "\n";
    return 2;
  }
  const oblique::scene::SceneCheck check = oblique::scene::check_scene(*parsed.scene);
  std::cout << (as_json ? oblique::scene::to_json(check) + "\n" : oblique::scene::to_text(check));
  return check.passes() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"oblique: oblique near-plane clipping, verified"};
  app.require_subcommand(1);

  oblique::protocol::ApplyOptions apply_options;
  std::string convention = "gl", method = "auto", precision = "double";
  CLI::App* apply = app.add_subcommand(
      "apply",
      "Read JSON Lines requests {\"projection\": [16 numbers, row-major], \"plane\": [4 numbers], "
      "\"convention\": ...} on standard input; answer one line each: {\"status\": \"ok\", "
      "\"projection\": [...]} or {\"status\": CODE, \"message\": ...}. Exit 0 when every line was "
      "ok, 1 otherwise.");
  apply->add_option("--convention", convention, "Depth convention of requests that name none")
      ->check(CLI::IsMember({"gl", "zero_one", "reversed_z"}))
      ->capture_default_str();
  apply
      ->add_option("--method", method,
                   "auto: closed form for the perspective shape, else general; accurate: every "
                   "entry within 2 ulp of the exact answer (measured: correctly rounded)")
      ->check(CLI::IsMember({"auto", "closed_form", "general", "accurate"}))
      ->capture_default_str();
  apply->add_option("--precision", precision, "Scalar type of the computation")
      ->check(CLI::IsMember({"float", "double", "long_double"}))
      ->capture_default_str();

  oblique::verify::VerifyOptions verify_options;
  std::string verify_conventions = "gl", families, verify_precision = "double";
  bool quiet = false;
  CLI::App* verify = app.add_subcommand(
      "verify",
      "Check another implementation of the oblique modification: start COMMAND once, send it "
      "generated requests in the protocol of `oblique apply` (one JSON line each on its standard "
      "input; it answers one line each, flushed), judge every answer with the property suite, and "
      "shrink the first violation to a report. Exit 0: no violation; 1: a violation (report "
      "written); 2: usage or protocol error.");
  verify->add_option("--impl", verify_options.command, "The implementation's command (run by sh)")
      ->required();
  verify
      ->add_option("--convention", verify_conventions,
                   "Conventions to request: gl, zero_one, reversed_z, a comma list, or all")
      ->capture_default_str();
  verify->add_option("--families", families,
                     "Comma list of projection families (default: all): perspective, off_axis, "
                     "infinite, orthographic, y_flipped, jittered, rotated, general");
  verify->add_option("--precision", verify_precision, "Scalar type of inputs and bounds")
      ->check(CLI::IsMember({"float", "double"}))
      ->capture_default_str();
  verify->add_option("--cases", verify_options.cases, "Number of generated requests")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify->add_option("--seed", verify_options.seed, "Random seed (default: a fresh one, printed)");
  verify
      ->add_option("--time-limit", verify_options.time_limit_seconds,
                   "Stop after this many seconds, shrinking included")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify
      ->add_option("--timeout", verify_options.request_timeout_seconds,
                   "Seconds to wait for one answer before calling the implementation hung")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify
      ->add_option("--report-dir", verify_options.report_dir,
                   "Where the counterexample report goes")
      ->capture_default_str();
  verify->add_flag("--quiet", quiet, "No progress lines on standard error");

  std::string scene_path;
  bool as_json = false;
  CLI::App* check = app.add_subcommand(
      "check",
      "Check the mirrors and clip planes of a scene file: for each surface, render or skip (with "
      "the reason), the pass camera's view and oblique projection, the properties that apply, "
      "and the depth precision left. Exit 0: every rendered pass passes; 1: a property fails; 2: "
      "the scene cannot be read.");
  check->add_option("SCENE", scene_path, "The scene file (JSON; see the README)")->required();
  check->add_flag("--json", as_json, "Print one JSON object instead of a table");

  CLI::App* report =
      app.add_subcommand("report", "Measurement reports (CSV, Markdown, PNG charts)");
  report->require_subcommand(1);
  oblique::report::AccuracyOptions accuracy_options;
  std::string accuracy_out = "report-out";
  CLI::App* accuracy = report->add_subcommand(
      "accuracy",
      "Error against run time: every method x scalar type x input regime (typical, tiny near "
      "planes, f/n to 1e12, infinite, orthographic, planes near the eye, the far corner and the "
      "standard near plane, huge and tiny scales) against the exact oracle; stiffness sweeps; the "
      "checker's bound against the measured error. Writes accuracy.csv, stiffness.csv, "
      "accuracy.md and (with gnuplot) accuracy.png and stiffness.png.");
  accuracy->add_option("--out", accuracy_out, "Output directory")->capture_default_str();
  accuracy
      ->add_option("--cases", accuracy_options.cases_per_step,
                   "Cases per regime and stiffness step")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  accuracy->add_option("--seed", accuracy_options.seed, "Random seed")->capture_default_str();
  accuracy->add_flag("--quiet", quiet, "No progress lines on standard error");
  oblique::report::DepthOptions depth_options;
  std::string depth_out = "report-out";
  CLI::App* depth = report->add_subcommand(
      "depth",
      "Depth precision: the paper's Figure 5 (maximum NDC z along the view axis, Eq. 19, against "
      "the plane's angle and distance), checked against the core's matrices in every convention, "
      "and the bits of a 24-bit fixed-point and a 32-bit float depth buffer still used along view "
      "directions. Writes figure5.csv, depth_bits.csv, depth.md and (with gnuplot) figure5.png.");
  depth->add_option("--out", depth_out, "Output directory")->capture_default_str();
  depth->add_option("--far", depth_options.far_distance, "Far distance of the frustum")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;  // --help exits 0; every usage error exits 2
  }

  if (apply->parsed()) {
    apply_options.convention = *oblique::parse_convention(convention);
    apply_options.method = *oblique::parse_method(method);
    apply_options.precision = *oblique::protocol::parse_precision(precision);
    return run_apply(apply_options);
  }
  if (check->parsed()) return run_check(scene_path, as_json);
  if (depth->parsed()) {
    depth_options.out_dir = depth_out;
    if (!(depth_options.far_distance > depth_options.near_distance)) {
      std::cerr << "oblique report depth: --far must exceed the near distance "
                << depth_options.near_distance << "\n";
      return 2;
    }
    const auto measured = oblique::report::measure_depth(depth_options);
    return print_paths(oblique::report::write_depth_report(measured, depth_options, std::cerr));
  }
  if (accuracy->parsed()) {
    accuracy_options.out_dir = accuracy_out;
    accuracy_options.progress = !quiet;
    const auto measured = oblique::report::measure_accuracy(accuracy_options, std::cerr);
    return print_paths(
        oblique::report::write_accuracy_report(measured, accuracy_options, std::cerr));
  }
  if (verify->parsed()) {
    if (!parse_lists(verify_conventions, families, verify_options)) return 2;
    verify_options.precision = *oblique::protocol::parse_precision(verify_precision);
    verify_options.progress = !quiet;
    verify_options.self = argv[0];
    return oblique::verify::run_verify(verify_options, std::cout, std::cerr);
  }
  return 2;
}
