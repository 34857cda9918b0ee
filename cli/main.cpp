// oblique: the command-line tool. `oblique apply` answers JSON Lines requests on standard input.
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "protocol.h"

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
  apply->add_option("--method", method, "auto: closed form for the perspective shape, else general")
      ->check(CLI::IsMember({"auto", "closed_form", "general"}))
      ->capture_default_str();
  apply->add_option("--precision", precision, "Scalar type of the computation")
      ->check(CLI::IsMember({"float", "double", "long_double"}))
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
  return 2;
}
