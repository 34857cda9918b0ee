#include "oblique/report/report_files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <system_error>

#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/shell_text.h"

namespace oblique::report {

ReportFiles::ReportFiles(std::filesystem::path dir) : dir_(std::move(dir)) {
  // One new folder per object, its name not guessable (mkdtemp): two reports staged at once in
  // one folder never share one, and a folder or a link found under that name is never used.
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  std::string pattern = (dir_ / ".oblique-staging-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    error_ = "cannot create a staging folder in " + dir_.string() + ": " + std::strerror(errno);
    return;
  }
  staging_ = pattern;
  // An interrupt (while a picture is drawn, say) removes it, and the names reserved.
  protocol::handle_interrupts();
  protocol::remove_on_interrupt(staging_.string(), true);
}

ReportFiles::~ReportFiles() {
  staged_.clear();  // closes the streams
  std::error_code ec;
  if (!staging_.empty()) {
    std::filesystem::remove_all(staging_, ec);
    protocol::keep_on_interrupt(staging_.string());
  }
  release_reservations();
}

void ReportFiles::release_reservations() {
  // A name reserved but never written: its empty file goes (one written in its place stays).
  std::error_code ec;
  for (const std::filesystem::path& held : reserved_) {
    if (std::find(written_.begin(), written_.end(), held) == written_.end() &&
        std::filesystem::file_size(held, ec) == 0 && !ec)
      std::filesystem::remove(held, ec);
    protocol::keep_on_interrupt(held.string());
  }
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
  std::vector<std::filesystem::path> earlier;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    for (const auto& [prefix, suffix] : superseded_) {
      if (name.size() >= prefix.size() + suffix.size() && name.rfind(prefix, 0) == 0 &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          std::find(written_.begin(), written_.end(), it->path()) == written_.end())
        earlier.push_back(it->path());
    }
  }
  if (!earlier.empty()) {
    std::sort(earlier.begin(), earlier.end());
    const std::filesystem::path moved = move_to_earlier(dir_, earlier, ec);
    if (ec)
      log << "report: could not move an earlier run's " << earlier.front().filename().string()
          << " to " << moved.string() << " (" << ec.message() << ")\n";
    else
      log << "report: " << earlier.size() << " file(s) of an earlier run moved to "
          << moved.string() << "\n";
  }
  return true;
}

std::filesystem::path move_to_earlier(const std::filesystem::path& dir,
                                      const std::vector<std::filesystem::path>& files,
                                      std::error_code& error) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", std::gmtime(&now));
  const std::filesystem::path target =
      dir / "earlier" / (std::string(stamp) + "-" + std::to_string(::getpid()));
  error.clear();
  std::filesystem::create_directories(target, error);
  for (const std::filesystem::path& file : files) {
    if (!error) std::filesystem::rename(file, target / file.filename(), error);
  }
  return target;
}

namespace {

/// How long gnuplot may take on one picture before its process group is killed: a hung gnuplot
/// must not hang the report. OBLIQUE_GNUPLOT_SECONDS (a
/// positive integer) overrides it.
int gnuplot_seconds() {
  constexpr int fallback = 60;
  const char* v = std::getenv("OBLIQUE_GNUPLOT_SECONDS");
  if (v == nullptr) return fallback;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return (end != v && *end == '\0' && n > 0 && n <= 86400) ? int(n) : fallback;
}

/// Whether `program` is an executable file in one of PATH's folders.
bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string folders = path ? path : "/usr/bin:/bin";
  for (std::size_t from = 0; from <= folders.size();) {
    std::size_t colon = folders.find(':', from);
    if (colon == std::string::npos) colon = folders.size();
    const std::string folder = folders.substr(from, colon - from);
    const std::string file = (folder.empty() ? "." : folder) + "/" + program;
    if (::access(file.c_str(), X_OK) == 0) return true;
    from = colon + 1;
  }
  return false;
}

/// Set by the handler below while a tool runs: the signal that asked us to stop, 0 if none.
volatile std::sig_atomic_t interrupted_by = 0;
void note_interrupt(int sig) {
  interrupted_by = sig;
}

/// How a tool's run ended.
struct ToolRun {
  int status = -1;         ///< waitpid's status; -1: it could not be started
  bool timed_out = false;  ///< it ran past its time and was killed
  int interrupt = 0;       ///< SIGINT / SIGTERM / SIGHUP that reached us while it ran (killed)
};

/// Runs `command` under /bin/sh in `folder`, in a process group of its own, for at most
/// `seconds` (then the group is killed). Unlike std::system(), an interrupt is not ignored: a
/// Ctrl-C or SIGTERM while the tool runs kills its group and is returned, so the caller can
/// leave its files as they were and then die of the signal as the user asked.
ToolRun run_tool(const std::string& command, const std::filesystem::path& folder, int seconds) {
  ToolRun out;
  interrupted_by = 0;
  struct sigaction old[3];
  const int signals[3] = {SIGINT, SIGTERM, SIGHUP};
  for (int i = 0; i < 3; ++i) {
    ::sigaction(signals[i], nullptr, &old[i]);
    if (old[i].sa_handler == SIG_IGN) continue;  // not ours to take (a background job's SIGINT)
    struct sigaction noted {};
    noted.sa_handler = note_interrupt;
    sigemptyset(&noted.sa_mask);
    ::sigaction(signals[i], &noted, nullptr);
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::signal(sig, SIG_DFL);
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  if (pid > 0) {
    ::setpgid(pid, pid);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    for (;;) {
      const pid_t r = ::waitpid(pid, &out.status, WNOHANG);
      if (r == pid) break;
      if (r < 0 && errno != EINTR) break;
      const bool late = std::chrono::steady_clock::now() >= deadline;
      if (interrupted_by != 0 || late) {
        ::kill(-pid, SIGKILL);
        ::waitpid(pid, &out.status, 0);
        out.interrupt = interrupted_by;
        out.timed_out = late && out.interrupt == 0;
        break;
      }
      ::usleep(10000);
    }
    ::kill(-pid, SIGKILL);  // what it left in its group
  }
  for (int i = 0; i < 3; ++i) ::sigaction(signals[i], &old[i], nullptr);
  return out;
}

}  // namespace

void ReportFiles::die_of(int sig) {
  // Nothing of this report is committed after an interrupt: the folder stays as it was.
  staged_.clear();
  std::error_code ec;
  if (!staging_.empty()) std::filesystem::remove_all(staging_, ec);
  release_reservations();
  ::raise(sig);  // with the handler that was there before (or the default: the exit is 128 + sig)
  ::signal(sig, SIG_DFL);  // (a handler that returned: one that finishes on a first interrupt)
  ::raise(sig);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
  std::_Exit(128 + sig);  // the signal blocked: the status a shell gives its death
}

void ReportFiles::plot(const std::string& script, const std::string& png, std::ostream& log) {
  if (!on_path("gnuplot")) {
    log << "report: gnuplot not found (bash scripts/setup.sh installs it); " << script
        << " is written, " << png << " is not\n";
    return;
  }
  // Run in the folder itself, where the script's names are (a relative folder included).
  const ToolRun run = run_tool("gnuplot " + protocol::shell_quote(script), dir_, gnuplot_seconds());
  if (run.interrupt) die_of(run.interrupt);
  if (run.status == 0) {
    written_.push_back(dir_ / png);
  } else if (run.timed_out) {
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
  if (!on_path("gnuplot")) {
    log << "gnuplot not found (bash scripts/setup.sh installs it); " << script << " is written, "
        << png << " is not";
    return false;
  }
  const std::string errors = script + ".stderr";
  const ToolRun run = run_tool("gnuplot " + protocol::shell_quote(script) + " > /dev/null 2> " +
                                   protocol::shell_quote(errors),
                               staging_, gnuplot_seconds());
  if (run.interrupt) die_of(run.interrupt);
  if (run.timed_out) {
    log << "gnuplot did not finish within " << gnuplot_seconds() << " s on " << script
        << " (stopped; " << png << " is not written)";
    return false;
  }
  const int status = run.status;
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

std::string ReportFiles::reserve_stem(const std::string& stem,
                                      const std::vector<std::string>& extensions) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  for (int n = 1; n < 100000; ++n) {
    const std::string name = n == 1 ? stem : stem + "-" + std::to_string(n);
    bool taken = false;
    for (const std::string& extension : extensions)
      taken = taken || std::filesystem::exists(dir_ / (name + extension), ec);
    if (taken || extensions.empty()) {
      if (extensions.empty()) return name;
      continue;
    }
    const std::filesystem::path held = dir_ / (name + extensions.front());
    const int fd = ::open(held.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      reserved_.push_back(held);
      protocol::remove_on_interrupt(held.string(), false);
      return name;
    }
    if (errno != EEXIST) return name;  // the folder cannot take it: commit() says why
  }
  return stem;
}

}  // namespace oblique::report
