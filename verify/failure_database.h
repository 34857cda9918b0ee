// oblique verify's failure database: the cases of earlier reports, replayed one (--replay) or a
// folder of them (--regressions) before a run, and new findings kept there (--save-regressions).
// Internal to oblique::verify.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "cases.h"
#include "oblique/expected.h"
#include "oblique/protocol/numbers.h"
#include "reporter.h"
#include "session.h"

namespace oblique::verify {

/// A report's JSON, or why it cannot be read.
Expected<protocol::JsonValue> read_report(const std::string& path);

/// Whether a report's JSON is of `type` (its "type": "consumers", "raster", "accuracy"; a
/// property finding's has none).
bool report_is(const protocol::JsonValue& report, std::string_view type);

/// The precision a report names ("precision"), if any; an error when it is not a report.
Expected<std::optional<protocol::Precision>> report_precision(const std::string& path);

/// `field`'s numbers in T, `n` of them, from a report (hex strings or numbers).
template <class T>
bool report_numbers(const protocol::JsonValue& report, const char* field, std::size_t n,
                    std::vector<T>& out, std::string& error) {
  const protocol::JsonValue* v = report.find(field);
  if (!v || !v->is_array() || v->size() != n) {
    error = std::string("\"") + field + "\" must hold " + std::to_string(n) + " numbers";
    return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::optional<std::string> token = protocol::number_token((*v)[i]);
    const Expected<T> x =
        token ? protocol::parse_number<T>(*token) : Expected<T>::failure("not a number");
    if (!x) {
      error = std::string("\"") + field + "\"[" + std::to_string(i) + "]: " + x.error();
      return false;
    }
    out.push_back(*x);
  }
  return true;
}

/// The case of a report (its JSON sidecar): the request, and the family named there.
template <class T>
Expected<cases::Case<T>> read_report_case(const std::string& path);

/// Copies a report's JSON into `folder` (created if missing), never over a file already there.
void save_regression(const std::string& json_path, const std::string& folder, std::ostream& out,
                     std::ostream& err);

template <class T>
class FailureDatabase {
 public:
  FailureDatabase(Session<T>& session, Reporter<T>& reporter, std::ostream& out, std::ostream& err)
      : session_(session), reporter_(reporter), out_(out), err_(err) {}

  /// Sends one report's case and judges the answer: holds, violated, or error (cannot).
  Verdict replay(const std::string& report_json, bool verbose);
  /// Every report (.json) in `folder`, in name order; the first that fails again ends it (its
  /// verdict); reports of another precision are counted and skipped.
  Verdict replay_all(const std::string& folder);

 private:
  /// For an accuracy profile's case (verify --accuracy's worst-K.json) that holds: its row 3's
  /// error measured again on the answer just given, beside the one the profile recorded.
  void accuracy_again(const std::string& path, const cases::Case<T>& v);

  Session<T>& session_;
  Reporter<T>& reporter_;
  std::ostream& out_;
  std::ostream& err_;
};

}  // namespace oblique::verify
