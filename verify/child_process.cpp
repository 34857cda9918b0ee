#include "oblique/verify/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <thread>

namespace oblique::verify {

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

}  // namespace

ChildProcess::ChildProcess(std::string command) : command_(std::move(command)) {}

ChildProcess::~ChildProcess() {
  stop();
}

bool ChildProcess::start(std::string* error) {
  stop();
  int in[2], out[2], err[2];
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) {
    *error = std::string("cannot create pipes: ") + std::strerror(errno);
    return false;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    *error = std::string("cannot fork: ") + std::strerror(errno);
    for (int fd : {in[0], in[1], out[0], out[1], err[0], err[1]}) ::close(fd);
    return false;
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    ::signal(SIGPIPE, SIG_DFL);
    ::dup2(in[0], STDIN_FILENO);
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err[1], STDERR_FILENO);
    ::execl("/bin/sh", "sh", "-c", command_.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also done by the child; whichever runs first wins the race harmlessly
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
  set_nonblocking(in_);
  set_nonblocking(out_);
  set_nonblocking(err_);
  return true;
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
      last_progress = Clock::now();
    }
    if (lines.size() >= want) return Outcome::done;
    if (out_ < 0) return Outcome::exited;

    const auto now = Clock::now();
    const auto until = std::min(deadline, last_progress + idle);
    if (now >= until) return Outcome::timed_out;
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count();

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
    if (fds[out_index].revents & (POLLIN | POLLHUP | POLLERR)) {
      const ssize_t r = ::read(out_, buffer, sizeof buffer);
      if (r > 0) {
        pending_.append(buffer, static_cast<std::size_t>(r));
      } else if (r == 0 || (errno != EAGAIN && errno != EINTR)) {
        close_fd(out_);
        if (!pending_.empty()) pending_ += '\n';  // a last line without its newline still counts
      }
    }
  }
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
  close_fds();
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
  if (!reaped_) return "still running (it stopped answering)";
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

}  // namespace oblique::verify
