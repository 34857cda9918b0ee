// oblique: the command-line tool. It wires the subcommands (commands.h: apply, verify, check,
// fuzz-report, report), says --version, and names what it did not understand with the closest
// known name.
#include <fcntl.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "oblique/protocol/names.h"
#include "oblique/protocol/shell_text.h"
#include "oblique_version.h"

namespace {

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

/// Standard input, output and error closed when we were started get /dev/null, before anything
/// opens a file: the pipes to a program under test (verify, check --impl, report accuracy,
/// fuzz-report) then never take fds 0..2, and our output never goes into its input.
void give_closed_standard_fds_dev_null() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) < 0 && errno == EBADF) {
      const int null = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
      if (null >= 0 && null != fd) {
        ::dup2(null, fd);
        ::close(null);
      }
    }
  }
}

/// The commands allocate and free buffers of megabytes hundreds of times a second (a raster
/// frame and its read-back, a batch's requests and answers). glibc serves each from fresh mapped
/// pages and gives them back when freed (mmap and heap trimming), so the kernel zeroes them again
/// every time: a third of `verify --rasterize`'s time went to page faults. Kept instead, up to a
/// bound: blocks under 64 MiB come from the heap, and its top is given back beyond 256 MiB free.
void keep_freed_buffers() {
#if defined(__GLIBC__)
  ::mallopt(M_MMAP_THRESHOLD, 64 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  give_closed_standard_fds_dev_null();
  keep_freed_buffers();
  // Every message echoes paths, names and programs' output: their control characters are shown
  // escaped, never obeyed by the terminal. (Never freed: std::cerr may be written at exit.)
  std::cerr.rdbuf(new oblique::protocol::EscapingBuffer(std::cerr.rdbuf()));
  std::clog.rdbuf(std::cerr.rdbuf());
  CLI::App app{"oblique: oblique near-plane clipping, verified"};
  app.set_version_flag(
      "--version", std::string("oblique ") + OBLIQUE_VERSION + " (commit " + OBLIQUE_COMMIT + ")",
      "Print the version and the commit it was built from");
  app.require_subcommand(1);
  int exit_code = 2;
  using namespace oblique::cli;
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
  // The stream may have failed long before (errno since overwritten): its state is cleared and
  // what is left written again, so the reason printed is this write's.
  const bool failed_before = !std::cout;
  std::cout.clear();
  errno = 0;
  const bool flushed = static_cast<bool>(std::cout.flush());
  if (exit_code != 2 && (failed_before || !flushed)) {
    std::cerr << "oblique: cannot write to standard output"
              << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
    return 2;
  }
  return exit_code;
}
