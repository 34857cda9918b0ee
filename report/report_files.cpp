#include "oblique/report/report_files.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <system_error>

namespace oblique::report {

ReportFiles::ReportFiles(std::filesystem::path dir) : dir_(std::move(dir)) {
  staging_ = dir_ / (".oblique-staging-" + std::to_string(::getpid()));
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
  staged_.push_back(Staged{name, std::ofstream()});
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

void ReportFiles::plot(const std::string& script, const std::string& png, std::ostream& log) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    log << "report: gnuplot not found (bash scripts/setup.sh installs it); " << script
        << " is written, " << png << " is not\n";
    return;
  }
  const std::string command = "gnuplot '" + (dir_ / script).string() + "'";
  if (std::system(command.c_str()) == 0) {
    written_.push_back(dir_ / png);
  } else {
    log << "report: gnuplot failed on " << (dir_ / script).string() << "\n";
  }
}

}  // namespace oblique::report
