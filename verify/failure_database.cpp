#include "failure_database.h"

#include <algorithm>
#include <filesystem>
#include <ostream>
#include <vector>

#include "accuracy.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/json.h"
#include "oblique/protocol/protocol.h"

namespace oblique::verify {

/// A report's JSON, or why it cannot be read (reports hold pictures' data: generous limits).
Expected<protocol::JsonValue> read_report(const std::string& path) {
  // A report holds its pictures' data, a few MiB at most.
  const Expected<std::string> text = protocol::read_text_file(path, 64u << 20);
  if (!text) return Expected<protocol::JsonValue>::failure(path + ": " + text.error());
  Expected<protocol::JsonValue> j = protocol::parse_json(*text, {1u << 22, 32});
  if (!j || !j->is(protocol::JsonValue::Kind::object))
    return Expected<protocol::JsonValue>::failure(
        path + " is not a report of oblique verify (" +
        (j ? std::string("not a JSON object") : j.error()) + ")");
  return j;
}

bool report_is(const protocol::JsonValue& report, std::string_view type) {
  const protocol::JsonValue* found = report.find("type");
  return found && found->is_string() && found->text == type;
}

Expected<std::optional<protocol::Precision>> report_precision(const std::string& path) {
  const Expected<protocol::JsonValue> j = read_report(path);
  if (!j) return Expected<std::optional<protocol::Precision>>::failure(j.error());
  const protocol::JsonValue* precision = j->find("precision");
  if (!precision || !precision->is(protocol::JsonValue::Kind::string))
    return std::optional<protocol::Precision>{};
  return protocol::parse_precision(precision->text);
}

template <class T>
Expected<cases::Case<T>> read_report_case(const std::string& path) {
  using Result = Expected<cases::Case<T>>;
  const Expected<protocol::JsonValue> j = read_report(path);
  if (!j) return Result::failure(j.error());
  const protocol::JsonValue* request = j->find("request");
  if (!request || !request->is(protocol::JsonValue::Kind::string))
    return Result::failure(path + " is not a report of oblique verify (no \"request\")");
  const protocol::JsonValue* precision = j->find("precision");
  if (precision && precision->text != protocol::scalar_name<T>()) {
    return Result::failure(path + " is a \"" + precision->text + "\" case, not " +
                           std::string(protocol::scalar_name<T>()));
  }
  const Expected<protocol::Request> parsed = protocol::parse_request(request->text);
  if (!parsed) return Result::failure(path + ": " + parsed.error());
  cases::Case<T> v;
  for (int i = 0; i < 16; ++i) {
    const Expected<T> value = protocol::parse_number<T>(parsed->projection[i]);
    if (!value) return Result::failure(path + ": " + value.error());
    v.matrix(i / 4, i % 4) = *value;
  }
  for (int i = 0; i < 4; ++i) {
    const Expected<T> value = protocol::parse_number<T>(parsed->plane[i]);
    if (!value) return Result::failure(path + ": " + value.error());
    v.plane(i) = *value;
  }
  v.convention = parsed->convention.value_or(Convention::gl);
  if (const protocol::JsonValue* family = j->find("family");
      family && family->is(protocol::JsonValue::Kind::string)) {
    if (auto f = cases::parse_family(family->text)) v.family = *f;
  }
  return v;
}

void save_regression(const std::string& json_path, const std::string& folder, std::ostream& out,
                     std::ostream& err) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(folder, ec);
  const fs::path from(json_path);
  fs::path to = fs::path(folder) / from.filename();
  for (int n = 2; fs::exists(to, ec); ++n)
    to = fs::path(folder) / (from.stem().string() + "-" + std::to_string(n) + ".json");
  fs::copy_file(from, to, ec);
  if (ec) {
    err << "oblique verify: cannot save the regression to " << to.string() << ": " << ec.message()
        << "\n";
  } else {
    out << "  kept as a regression: " << to.string() << "\n";
  }
}

template <class T>
void FailureDatabase<T>::accuracy_again(const std::string& path, const cases::Case<T>& v) {
  const Expected<protocol::JsonValue> j = read_report(path);
  const auto& answer = session_.last_answer();
  if (!j || !report_is(*j, "accuracy") || !answer || answer->status != Status::ok) return;
  const oracle::Problem<T> problem(v.matrix, v.plane, v.convention);
  if (problem.exact_status() != Status::ok) return;
  const report::ProfiledAnswer now = report::profile_answer(problem, answer->projection);
  std::string recorded;
  if (const protocol::JsonValue* ulps = j->find("ulps"); ulps && ulps->is_array())
    for (const protocol::JsonValue& u : ulps->items)
      recorded += (recorded.empty() ? "" : ", ") + u.text;
  char line[256];
  std::snprintf(line, sizeof line,
                "  row 3 against the exact answer: %.1f, %.1f, %.1f, %.1f ulps (%.2f bits lost)",
                now.ulps[0], now.ulps[1], now.ulps[2], now.ulps[3],
                report::bits_lost(now.worst_ulps()));
  out_ << line << "; the profile recorded [" << recorded << "]\n";
}

template <class T>
Verdict FailureDatabase<T>::replay(const std::string& path, bool verbose) {
  const Expected<cases::Case<T>> v = read_report_case<T>(path);
  if (!v) {
    err_ << "oblique verify: --replay: " << v.error() << "\n";
    return Verdict::error;
  }
  Found<T> found;
  using Evaluation = typename Session<T>::Evaluation;
  switch (session_.evaluate(*v, found)) {
    case Evaluation::pass:
      if (verbose) {
        out_ << "oblique verify: " << path << ": holds (" << protocol::scalar_name<T>() << ", "
             << convention_name(v->convention) << ")\n";
        accuracy_again(path, *v);
      }
      return Verdict::holds;
    case Evaluation::finding: {
      const oracle::Finding& f = found.finding;
      out_ << "oblique verify: " << path << ": violated: " << check_name(f.check) << ": "
           << relation_text(f) << "\n"
           << sides_text(f, "  ");
      if (!found.answer_line.empty())
        out_ << "  answer: " << escape_bytes(found.answer_line.substr(0, 400)) << "\n";
      return Verdict::violated;
    }
    case Evaluation::protocol_error:
      session_.program().stop();
      return reporter_.issue(session_.issue());
    case Evaluation::out_of_time:
      err_ << "oblique verify: --replay: out of time before the answer\n";
      return Verdict::error;
  }
  return Verdict::error;
}

template <class T>
Verdict FailureDatabase<T>::replay_all(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::string> paths;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".json") paths.push_back(it->path().string());
  }
  if (ec && ec != std::errc::no_such_file_or_directory) {
    err_ << "oblique verify: --regressions " << folder << ": " << ec.message() << "\n";
    return Verdict::error;
  }
  std::sort(paths.begin(), paths.end());
  long replayed = 0, other_precision = 0;
  for (const std::string& path : paths) {
    const Expected<cases::Case<T>> v = read_report_case<T>(path);
    if (!v) {
      if (v.error().find(" case, not ") != std::string::npos) {
        ++other_precision;
        continue;
      }
      err_ << "oblique verify: --regressions: " << v.error() << "\n";
      return Verdict::error;
    }
    const Verdict result = replay(path, /*verbose=*/false);
    if (result != Verdict::holds) {
      session_.program().stop();
      if (result == Verdict::violated)
        out_ << "  (a kept regression fails again; the run is not started)\n";
      return result;
    }
    ++replayed;
  }
  session_.program().stop();
  out_ << "oblique verify: regressions: " << replayed << " kept cases hold"
       << (other_precision
               ? " (" + std::to_string(other_precision) + " of another precision not replayed)"
               : "")
       << "\n";
  return Verdict::holds;
}

template Expected<cases::Case<float>> read_report_case<float>(const std::string&);
template Expected<cases::Case<double>> read_report_case<double>(const std::string&);
template class FailureDatabase<float>;
template class FailureDatabase<double>;

}  // namespace oblique::verify
