// What the reports share: an output directory whose files are replaced only by a complete run
// (each file is written into a staging folder inside it, checked, then renamed into place), and
// gnuplot run on a script there when it is installed (after the commit, or in the staging folder
// before it, so the pictures come with the rest or not at all).
#pragma once

#include <filesystem>
#include <fstream>
#include <iosfwd>
#include <list>
#include <string>
#include <system_error>
#include <utility>
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

  /// `stem`, or the first of `stem-2`, `stem-3`, ... for which no file `dir/<it><extension>`
  /// exists for any of `extensions`: a name that replaces no earlier report. The name is reserved
  /// at once (`dir/<it><extensions[0]>` created empty, create-exclusive), so two runs writing into
  /// one folder at the same time never pick the same one; commit() replaces the empty file, and
  /// a report that is not committed removes it.
  std::string reserve_stem(const std::string& stem, const std::vector<std::string>& extensions);

  /// The stream for dir / name (written to the staging folder until commit()).
  std::ostream& open(const std::string& name);

  /// Moves every staged file into dir when each was written in full; otherwise says why on
  /// `log`, leaves dir's earlier files as they were, and returns false.
  bool commit(std::ostream& log);

  /// Runs gnuplot on dir / script (which writes dir / png); records the PNG when it succeeds,
  /// else says why on `log`. After commit(): the script names the committed files.
  void plot(const std::string& script, const std::string& png, std::ostream& log);

  /// Before commit(): runs gnuplot on the staged `script` inside the staging folder (so the
  /// script names its data and `png` relative to the folder) and stages the PNG it writes, which
  /// commit() then moves into dir with the rest. Returns whether the PNG was made; otherwise says
  /// why on `log` (gnuplot missing or failing is no error of the report: its script is staged).
  bool plot_staged(const std::string& script, const std::string& png, std::ostream& log);

  /// Files of `dir` named PREFIX...SUFFIX belong to this kind of report: at commit(), those an
  /// earlier run wrote and this one did not (worst-9.json beside a new 3-answer report) are moved
  /// to dir/earlier/ (move_to_earlier()), so the folder holds one run's report.
  void supersede(std::string prefix, std::string suffix) {
    superseded_.emplace_back(std::move(prefix), std::move(suffix));
  }

  const std::filesystem::path& dir() const { return dir_; }
  const std::vector<std::filesystem::path>& written() const { return written_; }

 private:
  struct Staged {
    std::string name;
    std::ofstream stream;
    bool external = false;  ///< written by another program (gnuplot), not through `stream`
  };
  std::filesystem::path dir_, staging_;
  std::string error_;  ///< why the folders could not be made
  std::list<Staged> staged_;
  std::vector<std::filesystem::path> written_;
  std::vector<std::filesystem::path> reserved_;  ///< empty files holding reserve_stem()'s names
  std::vector<std::pair<std::string, std::string>> superseded_;

  /// After an interrupt that reached us while a tool ran: removes what this report staged and
  /// reserved, then dies of `sig` as the interrupt asked (never returns).
  [[noreturn]] void die_of(int sig);
  /// Removes the empty files of names reserved and not written.
  void release_reservations();
};

/// Moves `files` (in `dir`) to dir/earlier/<UTC time>-<pid>/, never deleting one; returns that
/// folder, or the reason in `error` (the files not moved stay where they were).
std::filesystem::path move_to_earlier(const std::filesystem::path& dir,
                                      const std::vector<std::filesystem::path>& files,
                                      std::error_code& error);

}  // namespace oblique::report
