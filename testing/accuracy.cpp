// profile_accuracy(): an implementation's accuracy profile in this process, beside the core's
// methods on the same cases (oblique::accuracy_profile), for float, double and long double.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/protocol.h"
#include "oblique/report/accuracy_profile.h"
#include "oblique/testing/harness.h"

namespace oblique::testing {

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
void profile_accuracy(const Implementation<T>& impl, const Contract& given,
                      const AccuracySettings& settings) {
  const Contract contract = resolved(given, impl.conventions, impl.status_contract(), false);
  if (!serves_conventions(impl, contract)) return;
  const rc::Gen<cases::Case<T>> generator = cases::valid_case_for<T>(contract);
  rc::Random random(settings.seed);
  report::Profile mine;
  mine.name = impl.name;
  mine.scalar = std::string(protocol::scalar_name<T>());
  mine.timing = report::Timing::in_process;
  std::vector<report::ProfileInput<T>> inputs;
  long violating = 0;
  std::string first_violation;
  Checks checks = impl.checks(contract.row3_accuracy.value_or(false));
  checks.properties = contract.properties;
  for (int i = 0; i < settings.cases; ++i) {
    const cases::Case<T> c = generator(random.split(), i % 101).value();
    if (!impl.accepts(c.convention, c.matrix)) continue;
    const Problem<T> problem(c.matrix, c.plane, c.convention);
    if (problem.exact_status() != Status::ok) continue;
    inputs.push_back({c.matrix, c.plane, c.convention, std::string(cases::family_name(c.family)),
                      std::string(cases::place_name(c.place)),
                      protocol::request_line(c.matrix, c.plane, c.convention)});
    const Answer<T> outcome = impl.run(c.matrix, c.plane, c.convention);
    if (const oracle::Finding* v = judge(problem, outcome, checks).violation()) {
      if (++violating == 1)
        first_violation = std::string(check_name(v->check)) + " on " + inputs.back().request;
      continue;
    }
    report::record_answer(mine, problem, inputs.back(), outcome.status, outcome.projection);
  }
  // The function's own time per call, on the cases it was asked.
  T checksum = 0;
  mine.ns = report::ns_per_call(inputs.size(), [&](std::size_t i) {
    checksum += impl.run(inputs[i].matrix, inputs[i].plane, inputs[i].convention).projection(2, 2);
  });
  if (checksum == T(0.123456789)) mine.name += " ";  // never; keeps the checksum alive
  std::vector<report::Profile> profiles{mine};
  for (report::Profile& p : report::core_profiles(inputs)) profiles.push_back(std::move(p));

  const std::string violations =
      violating == 0 ? std::string()
                     : impl.name + ": " + std::to_string(violating) +
                           " answers violate the properties and are not profiled (the property "
                           "tests report them); the first: " +
                           first_violation;
  if (mine.answers.empty()) {
    ADD_FAILURE() << "oblique::testing: no answer of " << impl.name << " was profiled ("
                  << settings.cases << " cases asked, " << inputs.size()
                  << " with an answer it is for, " << mine.refused << " refused)"
                  << (violations.empty() ? "" : "; " + violations);
    return;
  }
  report::ProfileReportOptions o;
  const report::ReportContext context = report_context("");
  o.dir = settings.directory.empty()
              ? std::filesystem::path(context.directory) / (context.report_key + ".accuracy")
              : std::filesystem::path(settings.directory);
  o.title = impl.name + " (" + mine.scalar + ")";
  std::ostringstream log;
  const auto written = report::write_profile_report(profiles, o, log);
  if (!written) {
    ADD_FAILURE() << "oblique::testing: the accuracy report could not be written to "
                  << o.dir.string() << ": " << log.str();
    return;
  }
  double worst = 0;
  for (const report::ProfiledAnswer& a : mine.answers) worst = std::max(worst, a.worst_ulps());
  char line[160];
  std::snprintf(line, sizeof line,
                "accuracy: %zu answers profiled, worst %.2f bits lost, %.1f ns a call: ",
                mine.answers.size(), report::bits_lost(worst), mine.ns);
  std::cout << line << (o.dir / "accuracy.md").string() << std::endl;
  if (!violations.empty()) ADD_FAILURE() << violations;
}

template void profile_accuracy<float>(const Implementation<float>&, const Contract&,
                                      const AccuracySettings&);
template void profile_accuracy<double>(const Implementation<double>&, const Contract&,
                                       const AccuracySettings&);
template void profile_accuracy<long double>(const Implementation<long double>&, const Contract&,
                                            const AccuracySettings&);

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing
