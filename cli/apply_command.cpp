// `oblique apply`: JSON Lines requests on standard input, one answer line each.
#include <cerrno>
#include <cstring>
#include <iostream>
#include <memory>

#include "commands.h"
#include "oblique/cases/contract.h"
#include "oblique/protocol/apply.h"
#include "oblique/protocol/names.h"

namespace oblique::cli {

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
      ->check(one_of(oblique::names_in(oblique::convention_names), "convention"))
      ->capture_default_str();
  apply
      ->add_option("--method", settings->method,
                   "auto: closed form for the perspective shape, else general; accurate: every "
                   "entry within 2 ulp of the exact answer (measured: correctly rounded)")
      ->check(one_of(oblique::names_in(oblique::method_names), "method"))
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

}  // namespace oblique::cli
