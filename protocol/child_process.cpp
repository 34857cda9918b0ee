#include "oblique/protocol/child_process.h"

#include "oblique/protocol/interrupts.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

namespace oblique::protocol {

namespace {

constexpr std::size_t kStderrKept = 4096;

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

bool set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  return flags >= 0 && ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

/// Our children (processes whose parent we are), from /proc: the implementation's descendants
/// that were orphaned to us as their subreaper.
std::vector<pid_t> own_children() {
  std::vector<pid_t> out;
  DIR* proc = ::opendir("/proc");
  if (!proc) return out;
  const pid_t self = ::getpid();
  while (const dirent* entry = ::readdir(proc)) {
    char* end = nullptr;
    const long pid = std::strtol(entry->d_name, &end, 10);
    if (pid <= 0 || *end != '\0') continue;
    std::ifstream stat("/proc/" + std::string(entry->d_name) + "/stat");
    std::string text;
    std::getline(stat, text);
    // pid (comm) state ppid ...: comm may hold spaces and parentheses, so read after the last ')'.
    const std::size_t close = text.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(text.substr(close + 1));
    char state = 0;
    long ppid = 0;
    if (rest >> state >> ppid && ppid == self) out.push_back(static_cast<pid_t>(pid));
  }
  ::closedir(proc);
  return out;
}

}  // namespace

ChildProcess::ChildProcess(std::string command) : command_(std::move(command)) {}

ChildProcess::~ChildProcess() {
  stop();
}

Expected<Done> ChildProcess::start() {
  stop();
  // Descendants that leave the process group (setsid) are orphaned to us, not to init, so stop()
  // can still end them.
  static const bool subreaper = ::prctl(PR_SET_CHILD_SUBREAPER, 1) == 0;
  (void)subreaper;
  // A child that exits before reading all we send must not take us with it: a write then fails
  // with EPIPE (handled in exchange()), never SIGPIPE. (`report accuracy --impl true` died of
  // SIGPIPE, exit 141, about one run in eight under load.)
  static const bool no_sigpipe = ::signal(SIGPIPE, SIG_IGN) != SIG_ERR;
  (void)no_sigpipe;
  handle_interrupts();
  int in[2], out[2], err[2];
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) {
    return Expected<Done>::failure(std::string("cannot create pipes: ") + std::strerror(errno));
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    const std::string why = std::string("cannot fork: ") + std::strerror(errno);
    for (int fd : {in[0], in[1], out[0], out[1], err[0], err[1]}) ::close(fd);
    return Expected<Done>::failure(why);
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    ::signal(SIGPIPE, SIG_DFL);
    // The pipe ends may themselves be fds 0..2 (when we were started with those closed): move
    // them above 2 first, so each dup2 below gives fds 0, 1, 2 a pipe that survives exec.
    const int child_in = ::fcntl(in[0], F_DUPFD, 3);
    const int child_out = ::fcntl(out[1], F_DUPFD, 3);
    const int child_err = ::fcntl(err[1], F_DUPFD, 3);
    if (child_in < 0 || child_out < 0 || child_err < 0 || ::dup2(child_in, STDIN_FILENO) < 0 ||
        ::dup2(child_out, STDOUT_FILENO) < 0 || ::dup2(child_err, STDERR_FILENO) < 0)
      ::_exit(126);
    ::close(child_in);
    ::close(child_out);
    ::close(child_err);
    ::execl("/bin/sh", "sh", "-c", command_.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also done by the child; whichever runs first wins the race harmlessly
  remember_child_group(pid);
  ::close(in[0]);
  ::close(out[1]);
  ::close(err[1]);
  pid_ = pid;
  in_ = in[1];
  out_ = out[0];
  err_ = err[0];
  reaped_ = false;
  wait_status_ = 0;
  pending_.clear();
  unwritten_.clear();
  written_ = 0;
  stderr_tail_.clear();
  overlong_.clear();
  last_line_ = Clock::now();
  set_nonblocking(in_);
  set_nonblocking(out_);
  set_nonblocking(err_);
  return Done{};
}

void ChildProcess::keep_stderr(const char* data, std::size_t size) {
  stderr_tail_.append(data, size);
  if (stderr_tail_.size() > 2 * kStderrKept)
    stderr_tail_.erase(0, stderr_tail_.size() - kStderrKept);
}

ChildProcess::Outcome ChildProcess::exchange(std::string_view input, std::size_t want,
                                             std::vector<std::string>& lines,
                                             std::chrono::milliseconds idle,
                                             Clock::time_point deadline) {
  if (written_ > 0) {
    unwritten_.erase(0, written_);
    written_ = 0;
  }
  unwritten_.append(input);
  auto last_progress = Clock::now();
  char buffer[1 << 16];
  for (;;) {
    // Complete lines already read count first.
    for (std::size_t nl; lines.size() < want && (nl = pending_.find('\n')) != std::string::npos;) {
      std::string line = pending_.substr(0, nl);
      pending_.erase(0, nl + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines.push_back(std::move(line));
      last_progress = last_line_ = Clock::now();
    }
    if (lines.size() >= want) return Outcome::done;
    if (pending_.size() > kMaxLineBytes) {
      overlong_ = pending_.substr(0, 200);
      pending_.clear();  // not kept: memory per line stays bounded
      return Outcome::too_long;
    }
    if (out_ < 0) return Outcome::exited;

    // Once the wait is over, one last look at what the pipe holds already: an answer that came
    // while we were busy elsewhere (judging, drawing) is an answer, not a hang.
    const auto now = Clock::now();
    const auto until = std::min(deadline, last_progress + idle);
    const bool last_look = now >= until;
    const auto wait =
        last_look ? -1 : std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count();

    pollfd fds[3];
    int n = 0;
    const int out_index = n;
    fds[n++] = {out_, POLLIN, 0};
    const int err_index = err_ >= 0 ? n : -1;
    if (err_ >= 0) fds[n++] = {err_, POLLIN, 0};
    const bool writing = written_ < unwritten_.size() && in_ >= 0;
    const int in_index = writing ? n : -1;
    if (writing) fds[n++] = {in_, POLLOUT, 0};
    const int ready = ::poll(fds, static_cast<nfds_t>(n), static_cast<int>(wait) + 1);
    if (ready < 0) {
      if (errno == EINTR) continue;
      return Outcome::exited;
    }
    if (last_look && !(fds[out_index].revents & (POLLIN | POLLHUP | POLLERR)))
      return Outcome::timed_out;
    if (in_index >= 0 && (fds[in_index].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t w = ::write(in_, unwritten_.data() + written_, unwritten_.size() - written_);
      if (w > 0) {
        written_ += static_cast<std::size_t>(w);
      } else if (w < 0 && errno != EAGAIN && errno != EINTR) {
        close_fd(in_);  // the child closed its input (EPIPE): read what it still says
      }
    }
    if (err_index >= 0 && (fds[err_index].revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t r = ::read(err_, buffer, sizeof buffer);
      if (r > 0)
        keep_stderr(buffer, static_cast<std::size_t>(r));
      else if (r == 0 || (errno != EAGAIN && errno != EINTR))
        close_fd(err_);
    }
    if (fds[out_index].revents & (POLLIN | POLLHUP | POLLERR)) read_output(buffer, sizeof buffer);
  }
}

bool ChildProcess::read_output(char* buffer, std::size_t size) {
  const ssize_t r = ::read(out_, buffer, size);
  if (r > 0) {
    pending_.append(buffer, static_cast<std::size_t>(r));
    return true;
  }
  if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
    close_fd(out_);
    if (!pending_.empty()) pending_ += '\n';  // a last line without its newline still counts
  }
  return false;
}

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t nl = text.find('\n', from);
    if (nl == std::string::npos) nl = text.size();
    std::string line = text.substr(from, nl - from);
    if (line.size() > 400) line = line.substr(0, 400) + "...";
    out.push_back(std::move(line));
    from = nl + 1;
  }
  return out;
}

}  // namespace

std::vector<std::string> ChildProcess::unasked_output() {
  char buffer[1 << 12];
  // What the pipe holds now, up to one line's worth (a babbling child must not keep us here).
  while (out_ >= 0 && pending_.size() <= kMaxLineBytes) {
    pollfd fd{out_, POLLIN, 0};
    if (::poll(&fd, 1, 0) <= 0 || !(fd.revents & (POLLIN | POLLHUP | POLLERR))) break;
    if (!read_output(buffer, sizeof buffer)) break;
  }
  return split_lines(pending_);
}

std::vector<std::string> ChildProcess::close_and_drain(Clock::time_point until) {
  close_fd(in_);
  char buffer[1 << 12];
  while (out_ >= 0 && pending_.size() <= kMaxLineBytes) {
    const auto now = Clock::now();
    if (now >= until) break;
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count();
    pollfd fd{out_, POLLIN, 0};
    const int ready = ::poll(&fd, 1, static_cast<int>(wait) + 1);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) break;
    read_output(buffer, sizeof buffer);
  }
  return split_lines(pending_);
}

ChildProcess::Outcome ChildProcess::run_to_end(std::string& output, std::size_t keep,
                                               Clock::time_point deadline, int& status) {
  close_fd(in_);
  char buffer[1 << 12];
  auto take = [&](int& fd, bool is_output) {
    const ssize_t r = ::read(fd, buffer, sizeof buffer);
    if (r > 0) {
      if (!is_output)
        keep_stderr(buffer, static_cast<std::size_t>(r));
      else if (output.size() < keep)
        output.append(buffer, std::min(static_cast<std::size_t>(r), keep - output.size()));
    } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
      close_fd(fd);
    }
  };
  // Until the child has exited and its output is read to the end (or, once it has exited, for
  // a moment more: what a descendant still holds open is not waited for).
  Clock::time_point after_exit{};
  for (;;) {
    const auto now = Clock::now();
    if (now >= deadline) {
      stop();
      status = 124;
      return Outcome::timed_out;
    }
    if (reap(false)) {
      if (after_exit == Clock::time_point{}) after_exit = now + std::chrono::milliseconds(200);
      if (out_ < 0 || now >= after_exit) break;
    }
    pollfd fds[2];
    int n = 0;
    if (out_ >= 0) fds[n++] = {out_, POLLIN, 0};
    if (err_ >= 0) fds[n++] = {err_, POLLIN, 0};
    // Short waits: a child that exits is noticed soon even while a descendant holds the pipes.
    const int ready = ::poll(fds, static_cast<nfds_t>(n), n == 0 ? 10 : 20);
    if (ready < 0) continue;  // interrupted: the deadline still ends the wait
    for (int i = 0; i < n && ready > 0; ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      if (fds[i].fd == out_)
        take(out_, true);
      else
        take(err_, false);
    }
  }
  const int raw = wait_status_;
  stop();  // what it left behind
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
  return Outcome::exited;
}

bool ChildProcess::reap(bool wait) {
  if (pid_ <= 0 || reaped_) return reaped_;
  const pid_t r = ::waitpid(pid_, &wait_status_, wait ? 0 : WNOHANG);
  if (r == pid_) reaped_ = true;
  return reaped_;
}

void ChildProcess::close_fds() {
  close_fd(in_);
  close_fd(out_);
  close_fd(err_);
}

void ChildProcess::stop() {
  if (pid_ <= 0) return;
  if (!reap(false)) {
    ::kill(-pid_, SIGKILL);
    ::kill(pid_, SIGKILL);
    reap(true);
  }
  // The group may outlive its leader (a shell's children): end it too.
  ::kill(-pid_, SIGKILL);
  // Descendants that left the group (setsid) and lost their parent are now our children: end
  // them, and theirs as they are orphaned to us in turn.
  for (int round = 0; round < 100; ++round) {
    const std::vector<pid_t> orphans = own_children();
    if (orphans.empty()) break;
    for (pid_t orphan : orphans) {
      ::kill(orphan, SIGKILL);
      ::waitpid(orphan, nullptr, 0);
    }
  }
  close_fds();
  forget_child_group(pid_);
  pid_ = -1;
  unwritten_.clear();
  written_ = 0;
  pending_.clear();
}

std::string ChildProcess::end_description() {
  if (pid_ <= 0) return "not running";
  // Give a child that is exiting a moment to finish, then report what happened.
  close_fd(in_);
  for (int i = 0; i < 50 && !reap(false); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (!reaped_)
    return out_ < 0 ? "closed its standard output and is still running"
                    : "still running (it stopped answering)";
  if (WIFEXITED(wait_status_))
    return "exited with status " + std::to_string(WEXITSTATUS(wait_status_));
  if (WIFSIGNALED(wait_status_)) {
    const int sig = WTERMSIG(wait_status_);
    const char* name = sigabbrev_np(sig);
    return "killed by signal " + std::to_string(sig) +
           (name ? std::string(" (SIG") + name + ")" : "");
  }
  return "ended";
}

}  // namespace oblique::protocol
