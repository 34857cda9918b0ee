// What the reports share: an output directory whose files are replaced only by a complete run
// (each file is written into a staging folder inside it, checked, then renamed into place), and
// gnuplot run on a script there when it is installed.
#pragma once

#include <filesystem>
#include <fstream>
#include <iosfwd>
#include <list>
#include <string>
#include <vector>

namespace oblique::report {

class ReportFiles {
 public:
  /// Creates `dir` (and its parents) and a staging folder inside it; a failure is reported by
  /// commit().
  explicit ReportFiles(std::filesystem::path dir);
  /// Removes the staging folder (and whatever a failed run left in it).
  ~ReportFiles();
  ReportFiles(const ReportFiles&) = delete;
  ReportFiles& operator=(const ReportFiles&) = delete;

  /// The stream for dir / name (written to the staging folder until commit()).
  std::ostream& open(const std::string& name);

  /// Moves every staged file into dir when each was written in full; otherwise says why on
  /// `log`, leaves dir's earlier files as they were, and returns false.
  bool commit(std::ostream& log);

  /// Runs gnuplot on dir / script (which writes dir / png); records the PNG when it succeeds,
  /// else says why on `log`. After commit(): the script names the committed files.
  void plot(const std::string& script, const std::string& png, std::ostream& log);

  const std::filesystem::path& dir() const { return dir_; }
  const std::vector<std::filesystem::path>& written() const { return written_; }

 private:
  struct Staged {
    std::string name;
    std::ofstream stream;
  };
  std::filesystem::path dir_, staging_;
  std::string error_;  ///< why the folders could not be made
  std::list<Staged> staged_;
  std::vector<std::filesystem::path> written_;
};

}  // namespace oblique::report
