#include "reporter.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>
#include <set>
#include <sstream>
#include <utility>

#include "failure_database.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/numbers.h"
#include "oblique/raster/case_scene.h"
#include "oblique/report/counterexample_report.h"
#include "oblique/report/report_files.h"

namespace oblique::verify {

namespace {

std::string seconds_text(double seconds) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(2);
  text << seconds;
  return text.str();
}

}  // namespace

template <class T>
Reporter<T>::Reporter(const VerifyOptions& options, std::string save_regressions,
                      const Draws<T>& draws, std::ostream& out, std::ostream& err)
    : options_(options),
      save_regressions_(std::move(save_regressions)),
      draws_(draws),
      out_(out),
      err_(err) {}

template <class T>
Verdict Reporter<T>::finding(const cases::Case<T>& v, const Found<T>& found, int steps,
                             bool out_of_time, long found_after_cases, double found_after_seconds,
                             const mistakes::Diagnosis& diagnosis) {
  const oracle::Finding& f = found.finding;
  // One report per cause: a cause the diagnosis names (not "no known mistake", which may be any
  // number of bugs) that has a report already.
  const std::string cause = mistakes::cause_names(diagnosis);
  const bool named = diagnosis.ran && (!diagnosis.causes.empty() || !diagnosis.families.empty() ||
                                       diagnosis.numerical);
  if (one_per_cause_ && named) {
    if (const auto earlier = cause_reports_.find(cause); earlier != cause_reports_.end()) {
      last_report_ = earlier->second;
      last_kind_ = std::string(check_name(f.check));
      last_cause_ = cause;
      last_report_new_ = false;
      out_ << "  " << check_name(f.check) << " (" << cases::family_name(v.family) << ", "
           << convention_name(v.convention) << ", " << cases::case_kind(v)
           << "): the same likely cause as an earlier finding (" << cause
           << "); no second report\n  report: " << earlier->second << "\n";
      return Verdict::violated;
    }
  }
  set_reporting_line(options_);
  report::Counterexample ce = report::make_counterexample(v.matrix, v.plane, v.convention);
  ce.finding = f;
  ce.implementation = options_.command;
  ce.family = std::string(cases::family_name(v.family));
  const oracle::Problem<T> problem(v.matrix, v.plane, v.convention);
  // "no answer: DEFECT" only where the input has none (a near_singular one may well have one).
  ce.place = v.defect && problem.exact_status() == Status::ok
                 ? std::string(cases::defect_name(*v.defect)) + " (has an answer)"
                 : cases::case_kind(v);
  if (found.result) report::set_result(ce, *found.result);
  if (diagnosis.ran) ce.diagnosis = diagnosis;
  report::set_views(ce, problem, found.result ? &*found.result : nullptr);
  ce.notes.emplace_back("implementation", options_.command);
  ce.notes.emplace_back("exact status", std::string(status_code(problem.exact_status())));
  if (problem.exact_status() == Status::ok) {
    std::string row;
    const oracle::exact::Vec exact_row = problem.exact_row3();
    for (int i = 0; i < 4; ++i) {
      T rounded = static_cast<T>(exact_row[i].get_d());
      row += (i ? ", " : "") + protocol::format_number(rounded);
    }
    ce.notes.emplace_back("exact third row (rounded)", "(" + row + ")");
  }
  if (!found.answer_line.empty())
    ce.notes.emplace_back("answer", escape_bytes(found.answer_line.substr(0, 2000)));
  if (!found.process.empty()) ce.notes.emplace_back("process", found.process);
  // A float engine judged under double's bounds: every entry a float, and the answer holds under
  // float's bounds on the input as a float engine reads it.
  const bool float_like = found.result && consistent_with_float(v, *found.result, draws_.checks());
  const std::string float_hint =
      "the answer's entries are floats (9 significant digits or fewer), and it holds under "
      "float's bounds on this input "
      "rounded to float: if your code computes in float, run with --precision float";
  if (float_like) ce.notes.emplace_back("precision", float_hint);
  ce.notes.emplace_back("shrinking", std::to_string(steps) + " steps" +
                                         (out_of_time ? ", stopped by the time limit" : ""));
  ce.notes.emplace_back("found after", std::to_string(found_after_cases) + " cases, " +
                                           seconds_text(found_after_seconds) + " s");

  const std::string request = request_text(v);
  report::ReportContext context;
  context.directory = options_.report_dir;
  context.stem = "verify-" + std::string(check_name(f.check));
  context.seed = options_.seed;
  context.replay_run = replay_run_command();
  context.replay_case = "echo " +
                        shell_quote(protocol::in_matrix_order(request, options_.matrix_order())) +
                        " | " + options_.command;
  context.contract = contract_json(draws_.contract());
  context.keep_existing = true;
  context.draw_case = [](report::ReportFiles& files, const std::string& stem,
                         const report::CaseViews& views, std::vector<report::StagedPicture>& staged,
                         report::RenderSummary& summary) {
    // Where the finding is: the far corner Q and a vertex the answer clips.
    std::vector<Eigen::Vector4d> hints;
    for (const auto& point : {views.far_corner, views.clipped})
      if (point) hints.push_back(*point);
    return raster::stage_case_renders(files, stem, views.projection, views.plane, *views.expected,
                                      *views.answer, views.convention, hints, staged, summary);
  };
  std::string path;
  try {
    path = report::write_report(ce, context);
  } catch (const std::exception& e) {
    path = "(not written: " + std::string(e.what()) + ")";
  }
  last_report_ = path;
  last_kind_ = std::string(check_name(f.check));
  last_cause_ = cause;
  last_report_new_ = true;
  if (one_per_cause_ && named) cause_reports_[cause] = path;
  const std::string json_path = path.size() > 3 && path.compare(path.size() - 3, 3, ".md") == 0
                                    ? path.substr(0, path.size() - 3) + ".json"
                                    : "";
  if (!json_path.empty() && !save_regressions_.empty())
    save_regression(json_path, save_regressions_, out_, err_);

  out_ << "  " << check_name(f.check) << ": " << relation_text(f) << "\n" << sides_text(f, "  ");
  if (diagnosis.ran) out_ << "  " << mistakes::likely_cause_line(diagnosis) << "\n";
  if (float_like) out_ << "  hint: " << float_hint << "\n";
  out_ << "  input (" << ce.family << ", " << ce.convention << ", " << ce.place << "): " << request
       << "\n  found after " << found_after_cases << " cases, " << seconds_text(found_after_seconds)
       << " s\n";
  if (!found.answer_line.empty())
    out_ << "  answer: " << escape_bytes(found.answer_line.substr(0, 400)) << "\n";
  out_ << "  report: " << path << "\n  replay: " << context.replay_case << "\n";
  if (!json_path.empty()) out_ << "  re-judge: " << replay_case_command(json_path) << "\n";
  return Verdict::violated;
}

template <class T>
Verdict Reporter<T>::passed(long done, double elapsed, const run::Tally& tally,
                            bool stopped_by_time, long dropped) {
  out_ << "oblique verify: " << done << " cases, no violation (" << protocol::scalar_name<T>()
       << ", seed " << options_.seed << ", " << std::fixed;
  out_.precision(1);
  out_ << elapsed << " s, " << static_cast<long>(elapsed > 0 ? done / elapsed : 0)
       << " requests per second)\n";
  out_.unsetf(std::ios::floatfield);
  out_.precision(6);
  out_ << "  contract: " << contract_json(draws_.contract()) << "\n";
  out_ << "  families: " << run::counts_text(tally.by("family"))
       << "\n  conventions: " << run::counts_text(tally.by("convention"))
       << "\n  places (with an answer): " << run::counts_text(tally.by("place"))
       << "\n  inputs without an answer: " << run::counts_text(tally.by("defect")) << "\n";
  if (!tally.reasons().empty() || !draws_.notes().empty()) {
    out_ << "  left out by the contract:";
    std::string sep = " ";
    for (const std::string& note : draws_.notes()) {
      out_ << sep << note;
      sep = ", ";
    }
    for (const auto& [why, n] : tally.reasons()) {
      out_ << sep << why << " " << n << " drawn";
      sep = ", ";
    }
    out_ << "\n";
  }
  const long limit = options_.cases > 0 ? options_.cases : std::numeric_limits<long>::max();
  if (stopped_by_time || done < limit)
    out_ << "  stopped by the time limit (" << options_.time_limit_seconds << " s)"
         << (options_.cases > 0 ? " before " + std::to_string(options_.cases) + " cases" : "")
         << (dropped > 0 ? "; the implementation was still answering (" + std::to_string(dropped) +
                               " requests in flight not judged)"
                         : "")
         << "\n";
  // Judged in part only: a claimed kind with more than the warning share of its cases left out.
  if (const std::string partly = run::partly_judged(tally, run::claims_of(draws_.contract()));
      !partly.empty()) {
    out_ << run::partly_judged_warning(partly, options_.strict);
    if (options_.strict) return Verdict::error;
  }
  return Verdict::holds;
}

template <class T>
Verdict Reporter<T>::index(const std::map<std::string, Kind>& kinds, long done) {
  std::ostringstream index;
  std::set<std::string> reports;
  for (const auto& entry : kinds) reports.insert(entry.second.report);
  index << "# oblique verify: " << kinds.size() << " kinds of finding, " << reports.size()
        << (reports.size() == 1 ? " report" : " reports") << "\n\n"
        << "Implementation `" << options_.command << "`, " << protocol::scalar_name<T>()
        << ", seed " << options_.seed << ", " << done << " cases judged.\n\n"
        << "| likely cause | kind (property x family x place) | cases | report |\n"
        << "|---|---|---|---|\n";
  // Grouped by likely cause: one mistake usually breaks several properties.
  std::map<std::string, std::vector<const std::pair<const std::string, Kind>*>> by_cause;
  for (const auto& entry : kinds)
    by_cause[entry.second.cause.empty() ? "(not diagnosed)" : entry.second.cause].push_back(&entry);
  for (const auto& [cause, entries] : by_cause) {
    for (const auto* entry : entries)
      index << "| " << cause << " | " << entry->first << " | " << entry->second.repeats << " | "
            << entry->second.report << " |\n";
  }
  index << "\nThe whole run again:\n\n```sh\n" << replay_run_command() << "\n```\n";
  namespace fs = std::filesystem;
  report::ReportFiles files(options_.report_dir);
  const std::string name = files.reserve_stem("verify-index", {".md"}) + ".md";
  files.open(name) << index.str();
  std::ostringstream log;
  std::string path = (fs::path(options_.report_dir) / name).string();
  if (!files.commit(log)) path = "(not written: " + log.str() + ")";
  out_ << "oblique verify: " << kinds.size() << " kinds of finding in " << done
       << " cases (--keep-going), " << reports.size()
       << (reports.size() == 1 ? " report (one per likely cause)"
                               : " reports (one per likely cause)")
       << "; index: " << path << "\n";
  for (const auto& [cause, entries] : by_cause) {
    out_ << "  likely cause " << cause << ":\n";
    for (const auto* entry : entries)
      out_ << "    " << entry->first << ": " << entry->second.repeats << " cases, report "
           << entry->second.report << "\n";
  }
  return Verdict::violated;
}

template <class T>
Verdict Reporter<T>::protocol_error(const std::string& request, const std::string& answer,
                                    const std::string& why) {
  err_ << "oblique verify: protocol error: the implementation's answer is not an answer of the "
          "protocol ("
       << escape_bytes(why) << ")\n  request: " << request
       << "\n  answer:  " << escape_bytes(answer.substr(0, 400))
       << (answer.size() > 400 ? "..." : "") << "\n";
  return Verdict::error;
}

template <class T>
Verdict Reporter<T>::count_error(const std::string& what, const std::vector<std::string>& requests,
                                 const std::vector<std::string>& lines) {
  err_ << "oblique verify: protocol error: " << what << "\n";
  for (const std::string& r : requests) err_ << "  request: " << r << "\n";
  for (const std::string& l : lines)
    err_ << "  line:    " << escape_bytes(l.substr(0, 400)) << (l.size() > 400 ? "..." : "")
         << "\n";
  err_ << "  (each request gets exactly one answer line, in order)\n";
  return Verdict::error;
}

template <class T>
Verdict Reporter<T>::overlong_line(const std::string& request, const std::string& line_start) {
  err_ << "oblique verify: protocol error: an answer line longer than " << client::kMaxLineBytes
       << " bytes (1 MiB, not read further)\n  request: " << request
       << "\n  line starts: " << escape_bytes(line_start) << "...\n";
  return Verdict::error;
}

template <class T>
Verdict Reporter<T>::issue(const Issue& issue) {
  const std::string what =
      issue.what.empty() ? "the implementation could not be restarted" : issue.what;
  return count_error(
      what,
      issue.request.empty() ? std::vector<std::string>{} : std::vector<std::string>{issue.request},
      issue.lines);
}

std::string rerun_command(const VerifyOptions& options) {
  std::string command = options.self + " verify";
  bool has_seed = false;
  for (const std::string& a : options.arguments) {
    if (a == "--seed" || a.rfind("--seed=", 0) == 0) has_seed = true;
    command += " " + shell_quote(a);
  }
  if (options.arguments.empty()) command += " " + impl_flags(options);
  if (!has_seed) command += " --seed " + std::to_string(options.seed);
  return command;
}

std::string impl_flags(const VerifyOptions& options) {
  return "--impl " + shell_quote(options.command) +
         (options.layout == "row_major" ? "" : " --layout " + options.layout);
}

void set_interrupted_line(const VerifyOptions& options, long judged, const std::string& what,
                          double seconds) {
  char time[32];
  std::snprintf(time, sizeof time, "%.1f", seconds);
  protocol::set_interrupt_line(
      "oblique verify: interrupted after " + std::to_string(judged) + " " + what + " in " + time +
      " s, no violation so far (seed " + std::to_string(options.seed) +
      "); to repeat it: " + rerun_command(options) + " (without --seed: fresh cases)");
}

void set_shrinking_line(const VerifyOptions& options) {
  protocol::set_interrupt_line(
      "oblique verify: interrupted while shrinking a violation, before its report was written "
      "(seed " +
      std::to_string(options.seed) + "); to repeat it: " + rerun_command(options));
}

void set_reporting_line(const VerifyOptions& options) {
  protocol::set_interrupt_line(
      "oblique verify: interrupted while writing a violation's report; nothing of it was kept "
      "(seed " +
      std::to_string(options.seed) + "); to repeat it: " + rerun_command(options));
}

Verdict commit_report(report::ReportFiles& files, const std::string& stem, std::ostream& err) {
  std::ostringstream log;
  if (!files.commit(log)) {
    std::string why = log.str();
    while (!why.empty() && why.back() == '\n') why.pop_back();
    err << "oblique verify: the report could not be written: " << why << "\n";
    return Verdict::error;
  }
  err << "report: " << (files.dir() / (stem + ".md")).string() << "\n";
  return Verdict::violated;
}

template <class T>
std::string Reporter<T>::replay_run_command() const {
  return rerun_command(options_);
}

template <class T>
std::string Reporter<T>::replay_case_command(const std::string& report_json) const {
  std::string command =
      options_.self + " verify --replay " + shell_quote(report_json) + " " + impl_flags(options_);
  // The flags that decide how one case is judged (which properties, which statuses are right,
  // whether it is sent at all); those that only steer what is drawn do not matter here.
  static const char* const kept[] = {"--answers-only", "--statuses", "--planes",   "--properties",
                                     "--contract",     "--timeout",  "--precision"};
  const auto& args = options_.arguments;
  for (std::size_t i = 0; i < args.size(); ++i) {
    for (const char* flag : kept) {
      if (args[i] == flag) {
        command += " " + args[i];
        if (std::string(flag) != "--answers-only" && i + 1 < args.size())
          command += " " + shell_quote(args[++i]);
      } else if (args[i].rfind(std::string(flag) + "=", 0) == 0) {
        command += " " + shell_quote(args[i]);
      }
    }
  }
  return command;
}

template class Reporter<float>;
template class Reporter<double>;

}  // namespace oblique::verify
