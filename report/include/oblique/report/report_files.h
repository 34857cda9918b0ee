// What the reports share: an output directory that remembers the files written into it, and
// gnuplot run on a script there when it is installed.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace oblique::report {

class ReportFiles {
 public:
  /// Creates `dir` (and its parents) if needed.
  explicit ReportFiles(std::filesystem::path dir);

  /// dir / name, recorded as written.
  std::filesystem::path add(const std::string& name);

  /// Runs gnuplot on dir / script (which writes dir / png); records the PNG when it succeeds,
  /// else says why on `log`.
  void plot(const std::string& script, const std::string& png, std::ostream& log);

  const std::filesystem::path& dir() const { return dir_; }
  const std::vector<std::filesystem::path>& written() const { return written_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> written_;
};

}  // namespace oblique::report
