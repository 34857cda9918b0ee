#include "accuracy.h"

#include <chrono>
#include <cmath>
#include <ostream>
#include <string>
#include <utility>

#include "oblique/client/program.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/json.h"
#include "oblique/protocol/protocol.h"
#include "reporter.h"

namespace oblique::verify {

template <class T>
AccuracyLook<T>::AccuracyLook(const VerifyOptions& options, std::string dir, std::ostream& out,
                              std::ostream& err)
    : options_(options), dir_(std::move(dir)), out_(out), err_(err) {
  mine_.name = protocol::command_name(options.command);
  mine_.scalar = std::string(protocol::scalar_name<T>());
  mine_.timing = report::Timing::round_trip;
}

template <class T>
void AccuracyLook<T>::passed(const cases::Case<T>& v, const std::string& request,
                             const std::string& answer) {
  if (v.defect) return;
  if (static_cast<long>(mine_.answers.size()) + mine_.refused >= kMaxProfiled) {
    ++skipped_;
    return;
  }
  const oracle::Problem<T> problem(v.matrix, v.plane, v.convention);
  if (problem.exact_status() != Status::ok) return;
  const Expected<Answer<T>> read = protocol::read_answer<T>(answer);
  if (!read) return;  // judged already: a protocol error never reaches here
  inputs_.push_back({v.matrix, v.plane, v.convention, std::string(cases::family_name(v.family)),
                     std::string(cases::place_name(v.place)), request});
  report::record_answer(mine_, problem, inputs_.back(), read->status, read->projection);
}

template <class T>
bool AccuracyLook<T>::write() {
  // The round trip: up to 4,096 of the profiled requests sent at once to a fresh process.
  const std::size_t timed = std::min<std::size_t>(inputs_.size(), 4096);
  if (timed > 0) {
    std::vector<std::string> requests;
    for (std::size_t i = 0; i < timed; ++i) requests.push_back(inputs_[i].request);
    client::Program program(
        options_.command,
        std::chrono::milliseconds(static_cast<long>(options_.request_timeout_seconds * 1000)),
        options_.matrix_order());
    mine_.ns = report::time_round_trip(program, requests).ns;
    program.stop();
    if (std::isnan(mine_.ns))
      err_ << "oblique verify: --accuracy: the round trip could not be timed (the program did "
              "not answer the requests again)\n";
  }
  std::vector<report::Profile> profiles{mine_};
  for (report::Profile& p : report::core_profiles(inputs_)) profiles.push_back(std::move(p));
  report::ProfileReportOptions o;
  o.dir = dir_;
  o.title = mine_.name + " (" + mine_.scalar + ")";
  o.replay = [this](const report::ProfiledAnswer&, const std::string& json) {
    return options_.self + " verify --replay " + shell_quote(json) + " " + impl_flags(options_);
  };
  const auto written = report::write_profile_report(profiles, o, err_);
  if (!written) {
    err_ << "oblique verify: --accuracy " << dir_ << ": the report could not be written\n";
    return false;
  }
  const report::ProfiledAnswer* worst = nullptr;
  for (const report::ProfiledAnswer& a : mine_.answers)
    if (!worst || a.worst_ulps() > worst->worst_ulps()) worst = &a;
  out_ << "accuracy: " << mine_.answers.size() << " answers profiled";
  if (skipped_ > 0) out_ << " (the first " << kMaxProfiled << "; " << skipped_ << " more judged)";
  if (worst) {
    char line[96];
    std::snprintf(line, sizeof line, ", worst %.2f bits lost",
                  report::bits_lost(worst->worst_ulps()));
    out_ << line;
  }
  out_ << ": " << (std::filesystem::path(dir_) / "accuracy.md").string() << "\n";
  return true;
}

template class AccuracyLook<float>;
template class AccuracyLook<double>;

}  // namespace oblique::verify
