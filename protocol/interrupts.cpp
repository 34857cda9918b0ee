#include "oblique/protocol/interrupts.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "oblique/protocol/shell_text.h"

namespace oblique::protocol {

namespace {

/// The process groups of the programs running now (a fixed table of lock-free atomics: all a
/// signal handler may read).
constexpr int kMaxRunning = 16;
std::atomic<pid_t> running_groups[kMaxRunning];

/// The interrupted line, twice: set_interrupt_line() writes the buffer not shown and then
/// publishes it, so the handler never reads a line half written.
constexpr std::size_t kLineBytes = 4096;
char lines[2][kLineBytes];
std::size_t lengths[2];
std::atomic<int> shown{-1};  ///< the buffer the handler writes; -1: none
std::mutex writing;
std::atomic<bool> finishing{false};
std::atomic<int> noted{0};

/// The paths to remove (remove_on_interrupt()): a slot is 0 free, 1 being written, 2 set.
struct Removal {
  std::atomic<int> state{0};
  bool folder = false;
  char path[kMaxRemovalPath];
};
Removal removals[kMaxRemovals];

/// Removes what the slots name; only async-signal-safe calls (getdents64 through syscall()).
void remove_what_is_half_made() {
  for (Removal& r : removals) {
    if (r.state.load() != 2) continue;
    if (!r.folder) {
      struct stat st {};
      if (::lstat(r.path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size == 0) ::unlink(r.path);
      continue;
    }
    const int dir = ::open(r.path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (dir < 0) continue;
    alignas(8) char buffer[4096];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, dir, buffer, sizeof buffer);
      if (n <= 0) break;
      bool removed = false;
      for (long at = 0; at < n;) {
        struct Entry {
          ino64_t ino;
          off64_t off;
          unsigned short reclen;
          unsigned char type;
          char name[1];
        };
        const auto* e = reinterpret_cast<const Entry*>(buffer + at);
        at += e->reclen;
        if (std::strcmp(e->name, ".") == 0 || std::strcmp(e->name, "..") == 0) continue;
        if (::unlinkat(dir, e->name, 0) == 0 || ::unlinkat(dir, e->name, AT_REMOVEDIR) == 0)
          removed = true;
      }
      if (!removed) break;  // what is left cannot go: stop rather than loop
      ::lseek(dir, 0, SEEK_SET);
    }
    ::close(dir);
    ::rmdir(r.path);
  }
}

void end_groups_and_die(int sig);

/// The handler: in finish mode, the first interrupt ends the programs' groups and is noted.
void on_interrupt(int sig) {
  if (finishing.load() && noted.load() == 0) {
    noted.store(sig);
    for (auto& g : running_groups) {
      const pid_t pid = g.load();
      if (pid > 0) ::kill(-pid, SIGKILL);
    }
    return;
  }
  end_groups_and_die(sig);
}

void end_groups_and_die(int sig) {
  const int which = shown.load();
  if (which >= 0) {
    const char* p = lines[which];
    std::size_t left = lengths[which];
    while (left > 0) {
      const ssize_t n = ::write(STDERR_FILENO, p, left);
      if (n <= 0) break;
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  for (auto& g : running_groups) {
    const pid_t pid = g.load();
    if (pid > 0) ::kill(-pid, SIGKILL);
  }
  remove_what_is_half_made();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

void handle_interrupts() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
      struct sigaction action {};
      action.sa_handler = on_interrupt;
      sigemptyset(&action.sa_mask);
      ::sigaction(sig, &action, nullptr);
    }
    return true;
  }();
  (void)installed;
}

void finish_on_interrupt() {
  handle_interrupts();
  finishing.store(true);
}

int interrupted() {
  return noted.load();
}

void die_of_interrupt(int sig) {
  end_groups_and_die(sig);
  std::abort();  // (raise() of a default handler does not return)
}

void set_interrupt_line(const std::string& line) {
  std::lock_guard<std::mutex> lock(writing);
  if (line.empty()) {
    shown.store(-1);
    return;
  }
  const int next = shown.load() == 0 ? 1 : 0;
  // A line too long for the buffer keeps its end (the command to run), marked as cut.
  std::string text = escape_bytes(line) + "\n";
  if (text.size() > kLineBytes) text = "..." + text.substr(text.size() - (kLineBytes - 3));
  std::memcpy(lines[next], text.data(), text.size());
  lengths[next] = text.size();
  shown.store(next);
}

void remove_on_interrupt(const std::string& path, bool folder) {
  if (path.empty() || path.size() >= kMaxRemovalPath) return;
  for (Removal& r : removals) {
    int expected = 0;
    if (!r.state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(r.path, path.c_str(), path.size() + 1);
    r.folder = folder;
    r.state.store(2);
    return;
  }
}

void keep_on_interrupt(const std::string& path) {
  for (Removal& r : removals) {
    int expected = 2;
    if (r.state.load() != 2 || path != r.path) continue;
    if (r.state.compare_exchange_strong(expected, 1)) {
      r.path[0] = '\0';
      r.state.store(0);
      return;
    }
  }
}

void remember_child_group(pid_t group) {
  for (auto& g : running_groups) {
    pid_t expected = 0;
    if (g.compare_exchange_strong(expected, group)) return;
  }
}

void forget_child_group(pid_t group) {
  for (auto& g : running_groups) {
    pid_t expected = group;
    if (g.compare_exchange_strong(expected, 0)) return;
  }
}

}  // namespace oblique::protocol
