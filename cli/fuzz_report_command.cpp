// `oblique fuzz-report`: a fuzz target's crash files, one report per distinct finding.
#include <unistd.h>

#include <iostream>
#include <memory>

#include "commands.h"
#include "oblique/fuzzing/fuzz_report.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/shell_text.h"

namespace oblique::cli {

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
    // A Ctrl-C stops the run and keeps the reports of the inputs that ran (then exits 130).
    oblique::protocol::finish_on_interrupt();
    if (::isatty(STDERR_FILENO)) options->progress = &std::cerr;
    const oblique::Expected<oblique::fuzzing::FuzzReport> report =
        oblique::fuzzing::fuzz_report(*options);
    if (const int sig = oblique::protocol::interrupted(); sig != 0) {
      std::cerr << "oblique fuzz-report: interrupted after "
                << (report ? std::to_string(report->inputs) + " of " +
                                 std::to_string(report->total) + " inputs"
                           : std::string("the run"))
                << (report && !report->index.empty() ? "; their reports: " + report->index : "")
                << (report ? "; " + std::to_string(report->not_run.size()) + " not run" : "");
      if (report && !report->not_run.empty() && report->not_run.size() <= 10) {
        std::string command = options->self + " fuzz-report --target " +
                              oblique::protocol::shell_quote(options->target) + " --report-dir " +
                              oblique::protocol::shell_quote(options->report_dir);
        for (const std::string& input : report->not_run)
          command += " " + oblique::protocol::shell_quote(input);
        std::cerr << "; to go on with them: " << command;
      } else if (report && !report->not_run.empty()) {
        std::cerr << " (listed in the index)";
      }
      std::cerr << "\n";
      oblique::protocol::die_of_interrupt(sig);
    }
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

}  // namespace oblique::cli
