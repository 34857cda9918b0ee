#include "oblique/fuzzing/fuzz_report.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "oblique/client/program.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/numbers.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/report/counterexample_report.h"
#include "oblique/report/report_files.h"

namespace oblique::fuzzing {

namespace {

namespace fs = std::filesystem;

/// What one input did: its output (at most 64 KiB) and how the target ended.
struct Run {
  std::string output;
  int status = 0;  ///< the shell's exit status; 124: the time ran out
};

Run run(const FuzzReportOptions& options, const std::string& input) {
  // The target gets the file as its one argument, in a process group of its own: at the time
  // limit the group is killed (a target that ignores SIGTERM too), and what it leaves behind
  // holding its output open is ended once it has exited, not waited for.
  const auto limit = std::chrono::duration<double>(options.timeout_seconds);
  client::Run ran = client::run_once(
      options.target + " " + protocol::shell_quote(input) + " 2>&1", 64u << 10,
      client::Clock::now() + std::chrono::duration_cast<client::Clock::duration>(limit));
  Run r;
  r.output = std::move(ran.output);
  r.status = ran.started ? ran.status : -1;
  return r;
}

/// The line of `text` that contains `marker`, from the marker on ("" when none does).
std::string line_from(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  if (at == std::string::npos) return "";
  const auto end = text.find('\n', at + 1);  // a marker may start with the newline before it
  return text.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

/// The words between `open` and `close` after position `from` of `line`.
std::string between(const std::string& line, const std::string& open, const std::string& close,
                    std::size_t from = 0) {
  const auto a = line.find(open, from);
  if (a == std::string::npos) return "";
  const auto b = line.find(close, a + open.size());
  return line.substr(a + open.size(),
                     b == std::string::npos ? std::string::npos : b - a - open.size());
}

/// A property violation as the fuzz driver prints it.
struct Violation {
  std::string property, implementation, scalar, convention, family, answered;
};

std::optional<Violation> violation_of(const std::string& output) {
  const std::string line = line_from(output, "oblique property violated: ");
  if (line.empty()) return std::nullopt;
  Violation v;
  v.property = between(line, "violated: ", " by ");
  const auto by = line.find(" by ");
  const auto open = by == std::string::npos ? by : line.find(" (", by);
  if (by == std::string::npos || open == std::string::npos || open < by) return std::nullopt;
  v.implementation = line.substr(by + 4, open - by - 4);
  std::istringstream words(between(line, " (", ")", open));
  std::getline(words, v.scalar, ',');
  words >> std::ws;
  std::getline(words, v.convention, ',');
  words >> std::ws >> v.family;
  v.answered = between(line, "): it ", "\n");
  return v;
}

/// What an input found, as the key its group goes by; empty when it holds.
std::string key_of(const Run& r) {
  if (r.status == 0) return "";
  if (const auto v = violation_of(r.output))
    return v->property + " x " + v->implementation + " x " + v->family + " x " + v->convention;
  if (const std::string asan = line_from(r.output, "ERROR: AddressSanitizer: "); !asan.empty()) {
    std::istringstream words(asan.substr(std::string("ERROR: AddressSanitizer: ").size()));
    std::string kind;
    words >> kind;
    // The first frame of the program's own code: not the sanitizer's interceptors.
    std::string where;
    for (std::size_t at = r.output.find(" in "); at != std::string::npos && where.empty();
         at = r.output.find(" in ", at + 4)) {
      std::istringstream frame(r.output.substr(at + 4, 200));
      std::string function;
      frame >> function;
      if (function.rfind("__", 0) != 0 && function.find("asan") == std::string::npos)
        where = function;
    }
    return "AddressSanitizer " + kind + (where.empty() ? "" : " in " + where);
  }
  if (const std::string ubsan = line_from(r.output, "runtime error: "); !ubsan.empty()) {
    const auto start = r.output.rfind('\n', r.output.find("runtime error: "));
    const std::string place = r.output.substr(
        start == std::string::npos ? 0 : start + 1,
        r.output.find(": runtime error") - (start == std::string::npos ? 0 : start + 1));
    return "UndefinedBehaviorSanitizer at " + place;
  }
  if (r.status == 124) return "timeout";
  if (const std::string fuzzer = line_from(r.output, "ERROR: libFuzzer: "); !fuzzer.empty())
    return "libFuzzer " + fuzzer.substr(std::string("ERROR: libFuzzer: ").size());
  return r.status > 128 ? "crash: signal " + std::to_string(r.status - 128)
                        : "crash: exit status " + std::to_string(r.status);
}

/// A file name from a key: letters, digits and _ kept, the rest one '-'.
std::string stem_of(const std::string& key) {
  std::string out;
  for (char ch : key) {
    const bool plain = std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
    if (plain)
      out += ch;
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.substr(0, 80);
}

/// The numbers in parentheses after `label` on the line that starts with it (the exact hex the
/// driver prints), or the decimals after it when there are none.
template <class T>
std::optional<std::vector<T>> numbers_after(const std::string& output, const std::string& label,
                                            std::size_t count) {
  const auto at = output.find("\n" + label);
  if (at == std::string::npos) return std::nullopt;
  const std::string line =
      output.substr(at + 1 + label.size(), output.find('\n', at + 1) - at - 1 - label.size());
  const auto paren = line.find('(');
  std::istringstream tokens(paren == std::string::npos ? line : between(line, "(", ")"));
  std::vector<T> out;
  for (std::string token; tokens >> token && out.size() < count;) {
    const Expected<T> value = protocol::parse_number<T>(token);
    if (!value) return std::nullopt;
    out.push_back(*value);
  }
  if (out.size() != count) return std::nullopt;
  return out;
}

/// The status the driver's words say the function gave ("answered ok", "answered" for a
/// function without statuses, "answered STATUS", "refused (returned false)": the adapter's
/// invalid_input).
std::optional<Status> status_answered(const std::string& words) {
  if (words == "answered" || words == "answered ok") return Status::ok;
  if (words.rfind("refused", 0) == 0) return Status::invalid_input;
  if (words.rfind("answered ", 0) == 0) return parse_status(words.substr(9));
  return std::nullopt;
}

/// The case a violation's output prints (the exact hex the driver prints) and what was answered:
/// the matrix, or the refusal; none when the output cannot be read back.
template <class T>
struct PrintedCase {
  Matrix4<T> m;
  Vector4<T> c;
  Convention convention = Convention::gl;
  std::optional<Matrix4<T>> answer;
};

template <class T>
std::optional<PrintedCase<T>> printed_case(const Violation& v, const std::string& output) {
  PrintedCase<T> out;
  for (int i = 0; i < 4; ++i) {
    const auto row = numbers_after<T>(output, "  M row " + std::to_string(i + 1) + ":", 4);
    if (!row) return std::nullopt;
    for (int j = 0; j < 4; ++j) out.m(i, j) = (*row)[static_cast<std::size_t>(j)];
  }
  const auto plane = numbers_after<T>(output, "  C:", 4);
  const auto convention = parse_convention(v.convention);
  if (!plane || !convention) return std::nullopt;
  out.convention = *convention;
  for (int i = 0; i < 4; ++i) out.c(i) = (*plane)[static_cast<std::size_t>(i)];
  Matrix4<T> rows;
  bool all_rows = true;
  for (int i = 0; i < 4 && all_rows; ++i) {
    const auto row = numbers_after<T>(output, "M' row " + std::to_string(i + 1) + ":", 4);
    all_rows = row.has_value();
    if (row)
      for (int j = 0; j < 4; ++j) rows(i, j) = (*row)[static_cast<std::size_t>(j)];
  }
  if (all_rows) out.answer = rows;
  return out;
}

/// What the answer shows of the implementation, for the diagnosis: none where the output cannot
/// be read back or (a status finding) its words name no status.
template <class T>
std::optional<mistakes::Observation<T>> observation_of(const Violation& v,
                                                       const std::string& output) {
  const std::optional<PrintedCase<T>> k = printed_case<T>(v, output);
  if (!k) return std::nullopt;
  mistakes::Observation<T> seen{
      k->m, k->c, k->convention, Status::ok, k->m, true, cases::parse_family(v.family)};
  if (k->answer) {
    seen.projection = *k->answer;
  } else {
    const std::optional<Status> answered = status_answered(v.answered);
    if (!answered) return std::nullopt;
    seen.status = *answered;
  }
  return seen;
}

/// A diagnosis that names `causes`, for its words.
mistakes::Diagnosis named(const std::vector<std::vector<mistakes::Mistake>>& causes) {
  mistakes::Diagnosis d;
  d.ran = true;
  d.causes = causes;
  return d;
}

/// The causes the diagnosis names for one input's answer (empty: none, or no diagnosis).
std::vector<std::vector<mistakes::Mistake>> causes_of(const Violation& v,
                                                      const std::string& output) {
  auto causes = [&](auto observation) -> std::vector<std::vector<mistakes::Mistake>> {
    if (!observation) return {};
    using T = std::decay_t<decltype(observation->matrix(0, 0))>;
    return mistakes::diagnose<T>({*observation}).causes;
  };
  try {
    if (v.scalar == "float") return causes(observation_of<float>(v, output));
    if (v.scalar == "double") return causes(observation_of<double>(v, output));
    if (v.scalar == "long_double") return causes(observation_of<long double>(v, output));
  } catch (const std::exception&) {
  }
  return {};
}

/// The report of a property violation: the input in its scalar type, the answer, the property's
/// relation, pictures and the command that replays it; "" when the output cannot be read back.
template <class T>
std::string violation_report(const FuzzReportOptions& options, const Violation& v,
                             const FuzzFinding& finding, const std::string& output) {
  const std::optional<PrintedCase<T>> printed = printed_case<T>(v, output);
  if (!printed) return "";
  const Matrix4<T>& m = printed->m;
  const Vector4<T>& c = printed->c;
  const Convention convention = printed->convention;
  const std::optional<Matrix4<T>>& answer = printed->answer;
  report::Counterexample ce = report::make_counterexample(m, c, convention);
  ce.implementation = v.implementation;
  ce.family = v.family;
  ce.place = "fuzz input";
  if (answer) report::set_result(ce, *answer);
  // The finding judged again here, from the numbers the driver printed (they round-trip): the
  // checker's own, not the driver's words read back.
  const std::optional<oracle::Check> check = oracle::parse_check(v.property);
  if (!check) return "";
  const oracle::Problem<T> problem(m, c, convention);
  if (*check == oracle::Check::status) {
    ce.finding.check = *check;
    ce.finding.shows = oracle::Shows::statuses;
    ce.finding.exact = problem.exact_status();
    ce.finding.allowed = problem.acceptable_statuses();
    const std::optional<Status> answered = status_answered(v.answered);
    if (!answered) return "";
    ce.finding.answered = *answered;
  } else if (*check == oracle::Check::finite_result) {
    ce.finding.check = *check;
    ce.finding.shows = oracle::Shows::non_finite_answer;
  } else {
    if (!answer) return "";
    cases::Checks every;
    every.every = true;
    every.row3_accuracy = true;
    bool found = false;
    for (const oracle::Finding& f :
         oracle::judge(problem, Answer<T>{Status::ok, *answer}, every).checks) {
      if (f.check == *check && !f.holds) {
        ce.finding = f;
        found = true;
        break;
      }
    }
    if (!found) return "";
  }
  // The likely cause, from this one case (the target is not asked again here).
  if (const std::optional<mistakes::Observation<T>> seen = observation_of<T>(v, output))
    ce.diagnosis = mistakes::diagnose<T>({*seen});
  report::set_views(ce, problem, answer ? &*answer : nullptr);
  ce.notes.emplace_back("fuzz input", finding.inputs.front());
  ce.notes.emplace_back("inputs with this finding", std::to_string(finding.inputs.size()));
  if (finding.kinds.size() > 1) {
    std::string kinds;
    for (const auto& [kind, count] : finding.kinds)
      kinds += (kinds.empty() ? "" : "; ") + kind + ": " + std::to_string(count);
    ce.notes.emplace_back("what they found (property x family x convention)", kinds);
  }
  ce.notes.emplace_back("what it did", "it " + v.answered);
  ce.notes.emplace_back("what the input allows", line_from(output, "the input has"));
  ce.notes.emplace_back("output", protocol::escape_bytes(output.substr(0, 2000)));
  report::ReportContext context;
  context.directory = options.report_dir;
  context.stem = "fuzz-" + stem_of(v.property + " " + v.family + " " + v.convention);
  context.replay_case = options.target + " " + protocol::shell_quote(finding.inputs.front());
  context.replay_run = options.self + " fuzz-report --target " +
                       protocol::shell_quote(options.target) + " " +
                       protocol::shell_quote(finding.inputs.front());
  context.keep_existing = true;
  return report::write_report(ce, context);
}

/// The report of any other finding (a sanitizer's error, a crash, a hang): the target's output
/// and the command that replays it.
Expected<std::string> plain_report(const FuzzReportOptions& options, const FuzzFinding& finding,
                                   const std::string& output) {
  report::ReportFiles files(options.report_dir);
  const std::string name = files.reserve_stem("fuzz-" + stem_of(finding.key), {".md"}) + ".md";
  std::ostream& md = files.open(name);
  md << "# Fuzz finding: " << finding.key << "\n\n"
     << finding.inputs.size() << " input(s); the smallest, `" << finding.inputs.front()
     << "`, replayed:\n\n```sh\n"
     << options.target << " " << protocol::shell_quote(finding.inputs.front())
     << "\n```\n\nIts output:\n\n```\n"
     << protocol::escape_bytes(output.substr(0, 8000)) << "\n```\n\nEvery input:\n\n";
  for (const std::string& input : finding.inputs) md << "- `" << input << "`\n";
  std::ostringstream log;
  if (!files.commit(log)) return Expected<std::string>::failure(log.str());
  return (fs::path(options.report_dir) / name).string();
}

}  // namespace

Expected<FuzzReport> fuzz_report(const FuzzReportOptions& options) {
  using Result = Expected<FuzzReport>;
  if (options.target.empty()) return Result::failure("no target command");
  if (!(options.timeout_seconds > 0 && options.timeout_seconds <= 1e6))
    return Result::failure("the timeout must be more than 0 and at most 1e6 seconds");
  std::vector<std::pair<std::uintmax_t, std::string>> files;
  for (const std::string& input : options.inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec)) {
      for (const auto& entry : fs::directory_iterator(input, ec)) {
        if (entry.is_regular_file(ec))
          files.emplace_back(entry.file_size(ec), entry.path().string());
      }
    } else if (fs::is_regular_file(input, ec)) {
      files.emplace_back(fs::file_size(input, ec), input);
    } else {
      return Result::failure("cannot read the input " + input);
    }
  }
  if (files.empty()) return Result::failure("no input to run");
  std::sort(files.begin(), files.end());  // smallest first: each group's report is its smallest
  FuzzReport out;
  std::map<std::string, std::size_t> group;  // findings without a named cause, by key_of()
  struct CauseGroup {
    std::string implementation;
    std::vector<std::vector<mistakes::Mistake>> causes;
    std::size_t finding = 0;
  };
  std::vector<CauseGroup> cause_groups;
  std::vector<std::string> first_output;  // per finding: its smallest input's output
  out.total = static_cast<long>(files.size());
  auto last_progress = std::chrono::steady_clock::now();
  for (const auto& [size, path] : files) {
    if (options.progress &&
        std::chrono::steady_clock::now() - last_progress >= std::chrono::seconds(1)) {
      last_progress = std::chrono::steady_clock::now();
      *options.progress << "oblique fuzz-report: input " << out.inputs + 1 << " of " << out.total
                        << ", " << out.findings.size() << " distinct findings so far\n"
                        << std::flush;
    }
    // An interrupt (protocol::finish_on_interrupt()) stops the run: the inputs run so far are
    // reported, the rest named.
    if (protocol::interrupted() != 0) break;
    const Run r = run(options, path);
    if (protocol::interrupted() != 0) break;  // its run was cut short: not counted
    ++out.inputs;
    if (r.status == -1) return Result::failure("cannot start /bin/sh to run the target");
    if (r.status == 127 || r.status == 126)
      return Result::failure("cannot run the target (" + options.target + "): " + r.output);
    std::string key = key_of(r);
    if (key.empty()) {
      ++out.holds;
      continue;
    }
    // A property violation whose cause the diagnosis names joins the group of that cause (for
    // the same implementation, in any scalar type) whatever its property, family and convention:
    // one bug, one report. Where one input's answer fits several causes, it joins a group that
    // shares one, and the group keeps the causes every input fits.
    const std::optional<Violation> v = violation_of(r.output);
    const auto causes = v ? causes_of(*v, r.output) : decltype(causes_of(*v, r.output)){};
    std::size_t at = out.findings.size();
    if (!causes.empty()) {
      for (CauseGroup& g : cause_groups) {
        if (g.implementation != v->implementation) continue;
        std::vector<std::vector<mistakes::Mistake>> shared;
        for (const auto& cause : g.causes) {
          if (std::find(causes.begin(), causes.end(), cause) != causes.end())
            shared.push_back(cause);
        }
        if (shared.empty()) continue;
        g.causes = shared;
        at = g.finding;
        break;
      }
      if (at == out.findings.size()) {
        cause_groups.push_back(CauseGroup{v->implementation, causes, at});
        out.findings.push_back(FuzzFinding{key, {}, "", {}});
        first_output.push_back(r.output);
      }
    } else {
      if (!group.count(key)) {
        group[key] = out.findings.size();
        out.findings.push_back(FuzzFinding{key, {}, "", {}});
        first_output.push_back(r.output);
      }
      at = group[key];
    }
    FuzzFinding& f = out.findings[at];
    f.inputs.push_back(path);
    if (v) {
      const std::string kind =
          v->property + " x " + v->family + " x " + v->convention + " (" + v->scalar + ")";
      auto it = std::find_if(f.kinds.begin(), f.kinds.end(),
                             [&](const auto& k) { return k.first == kind; });
      if (it == f.kinds.end())
        f.kinds.emplace_back(kind, 1);
      else
        ++it->second;
    }
  }
  out.interrupted = protocol::interrupted();
  for (std::size_t i = static_cast<std::size_t>(out.inputs); i < files.size(); ++i)
    out.not_run.push_back(files[i].second);
  // Groups that end with the same causes are one cause: the later merged into the earlier (whose
  // first input is the smaller: inputs come smallest first).
  std::vector<bool> merged(out.findings.size(), false);
  for (std::size_t i = 0; i < cause_groups.size(); ++i) {
    if (merged[cause_groups[i].finding]) continue;
    for (std::size_t j = i + 1; j < cause_groups.size(); ++j) {
      const CauseGroup &a = cause_groups[i], &b = cause_groups[j];
      if (merged[b.finding] || a.implementation != b.implementation || a.causes != b.causes)
        continue;
      FuzzFinding &into = out.findings[a.finding], &from = out.findings[b.finding];
      into.inputs.insert(into.inputs.end(), from.inputs.begin(), from.inputs.end());
      for (const auto& [kind, count] : from.kinds) {
        auto it = std::find_if(into.kinds.begin(), into.kinds.end(),
                               [&](const auto& k) { return k.first == kind; });
        if (it == into.kinds.end())
          into.kinds.emplace_back(kind, count);
        else
          it->second += count;
      }
      merged[b.finding] = true;
    }
  }
  for (const CauseGroup& g : cause_groups) {
    out.findings[g.finding].key =
        "likely cause " + mistakes::cause_names(named(g.causes)) + " x " + g.implementation;
  }
  {
    std::vector<FuzzFinding> kept;
    std::vector<std::string> kept_output;
    for (std::size_t i = 0; i < out.findings.size(); ++i) {
      if (merged[i]) continue;
      kept.push_back(std::move(out.findings[i]));
      kept_output.push_back(std::move(first_output[i]));
    }
    out.findings = std::move(kept);
    first_output = std::move(kept_output);
  }
  for (std::size_t i = 0; i < out.findings.size(); ++i) {
    FuzzFinding& f = out.findings[i];
    const std::string& output = first_output[i];
    std::string path;
    try {
      if (const auto v = violation_of(output)) {
        if (v->scalar == "float") path = violation_report<float>(options, *v, f, output);
        if (v->scalar == "double") path = violation_report<double>(options, *v, f, output);
        if (v->scalar == "long_double")
          path = violation_report<long double>(options, *v, f, output);
      }
    } catch (const std::exception& e) {
      return Result::failure(e.what());
    }
    if (path.empty()) {
      const Expected<std::string> plain = plain_report(options, f, output);
      if (!plain) return Result::failure(plain.error());
      path = *plain;
    }
    f.report = path;
  }
  if (out.findings.empty()) return out;
  report::ReportFiles files_out(options.report_dir);
  const std::string name = files_out.reserve_stem("fuzz-index", {".md"}) + ".md";
  std::ostream& index = files_out.open(name);
  index << "# Fuzz findings: " << out.findings.size() << " distinct, in " << out.inputs
        << " inputs\n\n";
  if (out.interrupted)
    index << "**Interrupted** after " << out.inputs << " of " << out.total
          << " inputs: these are the findings of the inputs that ran; " << out.not_run.size()
          << " were not run (listed at the end).\n\n";
  index << "Target `" << options.target << "`; " << out.holds
        << " inputs run without a finding now. A finding whose likely cause the diagnosis names "
           "groups every input of that cause (one bug, one report), with what they found listed "
           "inside.\n\n| finding | inputs | what they found (property x family x convention) | "
           "report |\n|---|---|---|---|\n";
  for (const FuzzFinding& f : out.findings) {
    std::string kinds;
    for (const auto& [kind, count] : f.kinds)
      kinds += (kinds.empty() ? "" : "; ") + kind + ": " + std::to_string(count);
    index << "| " << f.key << " | " << f.inputs.size() << " | " << kinds << " | " << f.report
          << " |\n";
  }
  if (!out.not_run.empty()) {
    index << "\n## Not run (interrupted)\n\n";
    for (const std::string& input : out.not_run) index << "- `" << input << "`\n";
  }
  std::ostringstream log;
  if (!files_out.commit(log)) return Result::failure(log.str());
  out.index = (fs::path(options.report_dir) / name).string();
  return out;
}

}  // namespace oblique::fuzzing
