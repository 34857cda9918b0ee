#include "oblique/report/report_files.h"

#include <cstdlib>
#include <ostream>

namespace oblique::report {

ReportFiles::ReportFiles(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::filesystem::create_directories(dir_);
}

std::filesystem::path ReportFiles::add(const std::string& name) {
  written_.push_back(dir_ / name);
  return written_.back();
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
