#include "oblique/report/report_files.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <system_error>

namespace oblique::report {

ReportFiles::ReportFiles(std::filesystem::path dir) : dir_(std::move(dir)) {
  // One folder per object: two reports staged at once in one folder never share one.
  static std::atomic<unsigned> count{0};
  staging_ =
      dir_ / (".oblique-staging-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
  std::error_code ec;
  std::filesystem::create_directories(staging_, ec);
  if (ec) error_ = "cannot create " + staging_.string() + ": " + ec.message();
}

ReportFiles::~ReportFiles() {
  staged_.clear();  // closes the streams
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);
}

std::ostream& ReportFiles::open(const std::string& name) {
  staged_.push_back(Staged{name, std::ofstream(), false});
  Staged& s = staged_.back();
  if (error_.empty()) {
    errno = 0;
    s.stream.open(staging_ / name, std::ios::binary);
  } else {
    s.stream.setstate(std::ios::failbit);
  }
  return s.stream;
}

bool ReportFiles::commit(std::ostream& log) {
  if (!error_.empty()) {
    log << "report: " << error_ << "; nothing written\n";
    return false;
  }
  for (Staged& s : staged_) {
    if (s.external) continue;
    errno = 0;
    s.stream.flush();
    s.stream.close();
    if (s.stream.fail()) {
      log << "report: cannot write " << (dir_ / s.name).string() << " ("
          << (errno ? std::strerror(errno) : "write failed")
          << "); nothing written, the folder's earlier files are as they were\n";
      return false;
    }
  }
  for (const Staged& s : staged_) {
    std::error_code ec;
    std::filesystem::rename(staging_ / s.name, dir_ / s.name, ec);
    if (ec) {
      log << "report: cannot move " << s.name << " into " << dir_.string() << ": " << ec.message()
          << "\n";
      return false;
    }
    written_.push_back(dir_ / s.name);
  }
  return true;
}

namespace {

/// How long gnuplot may take on one picture before it is stopped (coreutils' `timeout`, then
/// SIGKILL 5 s later): a hung gnuplot must not hang the report. OBLIQUE_GNUPLOT_SECONDS (a
/// positive integer) overrides it.
int gnuplot_seconds() {
  constexpr int fallback = 60;
  const char* v = std::getenv("OBLIQUE_GNUPLOT_SECONDS");
  if (v == nullptr) return fallback;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return (end != v && *end == '\0' && n > 0 && n <= 86400) ? int(n) : fallback;
}

/// `gnuplot 'SCRIPT'` with the time limit.
std::string gnuplot_command(const std::string& script) {
  return "timeout -k 5 " + std::to_string(gnuplot_seconds()) + " gnuplot '" + script + "'";
}

/// Whether std::system's `status` is `timeout`'s "the time limit ran out" (124, or 137 after
/// the SIGKILL).
bool timed_out(int status) {
  return WIFEXITED(status) && (WEXITSTATUS(status) == 124 || WEXITSTATUS(status) == 137);
}

}  // namespace

void ReportFiles::plot(const std::string& script, const std::string& png, std::ostream& log) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    log << "report: gnuplot not found (bash scripts/setup.sh installs it); " << script
        << " is written, " << png << " is not\n";
    return;
  }
  const std::string command = gnuplot_command((dir_ / script).string());
  const int status = std::system(command.c_str());
  if (status == 0) {
    written_.push_back(dir_ / png);
  } else if (timed_out(status)) {
    log << "report: gnuplot did not finish within " << gnuplot_seconds() << " s on "
        << (dir_ / script).string() << " (stopped)\n";
  } else {
    log << "report: gnuplot failed on " << (dir_ / script).string() << "\n";
  }
}

bool ReportFiles::plot_staged(const std::string& script, const std::string& png,
                              std::ostream& log) {
  if (!error_.empty()) {
    log << "report: " << error_ << "\n";
    return false;
  }
  for (Staged& s : staged_) {
    if (!s.external) s.stream.flush();  // the script and its data whole on disk for gnuplot
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    log << "gnuplot not found (bash scripts/setup.sh installs it); " << script << " is written, "
        << png << " is not";
    return false;
  }
  const std::string errors = script + ".stderr";
  const std::string command = "cd '" + staging_.string() + "' && " + gnuplot_command(script) +
                              " > /dev/null 2> '" + errors + "'";
  const int status = std::system(command.c_str());
  if (timed_out(status)) {
    log << "gnuplot did not finish within " << gnuplot_seconds() << " s on " << script
        << " (stopped; " << png << " is not written)";
    return false;
  }
  std::error_code ec;
  if (status == 0 && std::filesystem::file_size(staging_ / png, ec) > 0 && !ec) {
    staged_.push_back(Staged{png, std::ofstream(), true});
    return true;
  }
  std::ifstream in(staging_ / errors);
  std::string said((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
  if (said.size() > 400) said = "..." + said.substr(said.size() - 400);
  for (char& ch : said) {
    if (ch == '\n') ch = ' ';
  }
  log << "gnuplot failed on " << script << " (" << png << " is not written)"
      << (said.empty() ? "" : ": " + said);
  return false;
}

std::string free_stem(const std::filesystem::path& dir, const std::string& stem,
                      const std::vector<std::string>& extensions) {
  std::string name = stem;
  auto taken = [&] {
    std::error_code ec;
    for (const std::string& extension : extensions) {
      if (std::filesystem::exists(dir / (name + extension), ec)) return true;
    }
    return false;
  };
  for (int n = 2; taken(); ++n) name = stem + "-" + std::to_string(n);
  return name;
}

}  // namespace oblique::report
