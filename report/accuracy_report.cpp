#include "oblique/report/accuracy_report.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <random>
#include <sstream>

#include "oblique/client/program.h"
#include "oblique/oblique.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/projection.h"
#include "oblique/protocol/names.h"
#include "oblique/protocol/numbers.h"
#include "oblique/protocol/protocol.h"
#include "oblique/report/accuracy_profile.h"
#include "oblique/report/report_files.h"
#include "oblique/report/views.h"

namespace oblique::report {
namespace {

using Matrix = Matrix4<double>;
using Plane = Vector4<double>;
using Vec3 = Eigen::Vector3d;

struct Input {
  Matrix matrix;
  Plane plane;
  Convention convention;
};

/// A regime: its stiffness parameter's values, and a maker of one case at a given value.
struct Regime {
  std::string name;
  cases::Family family;   ///< of the projections it builds
  std::string parameter;  ///< empty when the regime has no stiffness sweep
  std::vector<double> values;
  std::function<std::optional<Input>(std::mt19937_64&, double, Convention)> make;
};

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A unit normal leaning toward -z (the view direction), so planes in front of the camera keep
/// the far part of the view volume.
Vec3 forward_normal(std::mt19937_64& rng) {
  const Vec3 n(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1) - 2.0);
  return n.normalized();
}

struct Frustum {
  double l, r, b, t, n, f;
};

Frustum random_frustum(std::mt19937_64& rng, double n, double f) {
  const double top = n * std::tan(uniform(rng, 0.3, 1.2) / 2);
  const double right = top * uniform(rng, 0.75, 2.0);
  return {-right, right, -top, top, n, f};
}

Matrix perspective_of(const Frustum& v, Convention c) {
  return frustum<double>(v.l, v.r, v.b, v.t, v.n, v.f, c);
}

/// A plane through a random point inside the frustum's depth range [n, depth_limit], facing
/// forward; empty when the eye is not behind it.
std::optional<Plane> typical_plane(std::mt19937_64& rng, const Frustum& v, double depth_limit) {
  const double z = -uniform(rng, v.n, std::min(v.f, depth_limit));
  const double s = -z / v.n;
  const Vec3 point(uniform(rng, v.l, v.r) * s, uniform(rng, v.b, v.t) * s, z);
  const Plane c = plane_from_normal_and_point<double>(forward_normal(rng), point);
  if (!(c.w() < 0)) return std::nullopt;
  return c;
}

std::vector<double> powers_of_ten(int from, int to) {
  std::vector<double> out;
  for (int k = from; k <= to; ++k) out.push_back(std::pow(10.0, k));
  return out;
}

std::vector<Regime> regimes() {
  std::vector<Regime> out;
  out.push_back({"typical",
                 cases::Family::perspective,
                 "",
                 {1.0},
                 [](std::mt19937_64& rng, double, Convention c) {
                   const Frustum v =
                       random_frustum(rng, uniform(rng, 0.1, 1), uniform(rng, 50, 1000));
                   auto plane = typical_plane(rng, v, v.f);
                   if (!plane) return std::optional<Input>();
                   return std::optional<Input>(Input{perspective_of(v, c), *plane, c});
                 }});
  out.push_back({"tiny_near", cases::Family::perspective, "1/n", powers_of_ten(1, 6),
                 [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v = random_frustum(rng, 1 / k, 100);
                   auto plane = typical_plane(rng, v, v.f);
                   if (!plane) return std::optional<Input>();
                   return std::optional<Input>(Input{perspective_of(v, c), *plane, c});
                 }});
  out.push_back({"far_near_ratio", cases::Family::perspective, "f/n", powers_of_ten(1, 12),
                 [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v = random_frustum(rng, 1, k);
                   auto plane = typical_plane(rng, v, std::min(v.f, 1000.0));
                   if (!plane) return std::optional<Input>();
                   return std::optional<Input>(Input{perspective_of(v, c), *plane, c});
                 }});
  out.push_back({"infinite",
                 cases::Family::infinite,
                 "",
                 {1.0},
                 [](std::mt19937_64& rng, double, Convention c) {
                   const Frustum v = random_frustum(rng, uniform(rng, 0.1, 1), 1000);
                   auto plane = typical_plane(rng, v, 1000);
                   if (!plane) return std::optional<Input>();
                   return std::optional<Input>(
                       Input{infinite_frustum<double>(v.l, v.r, v.b, v.t, v.n, c), *plane, c});
                 }});
  out.push_back(
      {"orthographic",
       cases::Family::orthographic,
       "",
       {1.0},
       [](std::mt19937_64& rng, double, Convention c) {
         const double w = uniform(rng, 1, 50), h = uniform(rng, 1, 50);
         const double n = uniform(rng, 0.1, 10), f = n + uniform(rng, 10, 1000);
         const Vec3 point(uniform(rng, -w, w), uniform(rng, -h, h), -uniform(rng, n, f));
         const Plane plane = plane_from_normal_and_point<double>(forward_normal(rng), point);
         if (!(plane.w() < 0)) return std::optional<Input>();
         return std::optional<Input>(Input{orthographic<double>(-w, w, -h, h, n, f, c), plane, c});
       }});
  out.push_back({"near_eye", cases::Family::perspective, "1/|C_w|", powers_of_ten(1, 12),
                 [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v =
                       random_frustum(rng, uniform(rng, 0.1, 1), uniform(rng, 50, 1000));
                   const Vec3 n = forward_normal(rng);
                   return std::optional<Input>(
                       Input{perspective_of(v, c), Plane(n.x(), n.y(), n.z(), -1 / k), c});
                 }});
  out.push_back({"near_far_corner", cases::Family::perspective, "|C||Q|/(C.Q)",
                 powers_of_ten(1, 12), [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v =
                       random_frustum(rng, uniform(rng, 0.1, 1), uniform(rng, 50, 1000));
                   const Vec3 n = forward_normal(rng);
                   const double s = v.f / v.n;
                   Vec3 far_corner(0, 0, 0);
                   double best = -1;
                   for (double x : {v.l * s, v.r * s}) {
                     for (double y : {v.b * s, v.t * s}) {
                       const Vec3 p(x, y, -v.f);
                       if (n.dot(p) > best) best = n.dot(p), far_corner = p;
                     }
                   }
                   const double delta = far_corner.norm() / k;  // C . Q = delta, |N| = 1
                   if (!(best > delta)) return std::optional<Input>();
                   return std::optional<Input>(
                       Input{perspective_of(v, c), Plane(n.x(), n.y(), n.z(), delta - best), c});
                 }});
  out.push_back({"near_standard", cases::Family::perspective, "1/perturbation",
                 powers_of_ten(1, 12), [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v =
                       random_frustum(rng, uniform(rng, 0.1, 1), uniform(rng, 50, 1000));
                   auto jitter = [&] { return uniform(rng, -1, 1) / k; };
                   const Plane plane(jitter(), jitter(), -1 + jitter(), -v.n * (1 + jitter()));
                   return std::optional<Input>(Input{perspective_of(v, c), plane, c});
                 }});
  out.push_back({"scaled",
                 cases::Family::general,
                 "scale",
                 {1e-30, 1e-20, 1e-10, 1e10, 1e20, 1e30},
                 [](std::mt19937_64& rng, double k, Convention c) {
                   const Frustum v =
                       random_frustum(rng, uniform(rng, 0.1, 1), uniform(rng, 50, 1000));
                   auto plane = typical_plane(rng, v, v.f);
                   if (!plane) return std::optional<Input>();
                   const double matrix_scale = std::pow(k, 1.0 / 3.0);
                   return std::optional<Input>(
                       Input{Matrix(perspective_of(v, c) * matrix_scale), Plane(*plane * k), c});
                 }});
  return out;
}

constexpr Method kMethods[] = {Method::closed_form, Method::general, Method::accurate};

struct Errors {
  std::vector<double> ulps;
  double max_bound_ratio = 0;
  int answered = 0, refused = 0, violating = 0;
};

/// One answer (status ok) to the case of `problem`, counted in the regime's and its step's
/// errors: its worst entry in ulps of the row (accuracy_profile.h) and its error over the
/// checker's bound.
template <class T>
void record(const oracle::Problem<T>& problem, const Matrix4<T>& answer, Errors& all,
            Errors& step) {
  ++all.answered;
  ++step.answered;
  const auto closeness = problem.compare_row3(answer);
  const double ratio = closeness.judged ? closeness.ratio : 0.0;
  const double u = profile_answer(problem, answer).worst_ulps();
  for (Errors* e : {&all, &step}) {
    e->max_bound_ratio = std::max(e->max_bound_ratio, ratio);
    e->ulps.push_back(u);
  }
}

struct Stats {
  double max = 0, p999 = 0, mean = 0;
};

Stats stats_of(std::vector<double> values) {
  Stats s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.max = values.back();
  const std::size_t index =
      static_cast<std::size_t>(std::ceil(0.999 * static_cast<double>(values.size()))) - 1;
  s.p999 = values[std::min(index, values.size() - 1)];
  double sum = 0;
  for (double v : values) sum += std::isfinite(v) ? v : 0;
  s.mean = sum / static_cast<double>(values.size());
  return s;
}

/// The rows of one method (or implementation) on one scalar type in `regime`: the whole
/// regime, and each stiffness step.
void add_rows(const Regime& regime, const std::string& scalar, const std::string& method,
              bool round_trip, double ns, const Errors& all, const std::vector<Errors>& by_step,
              AccuracyReport& report) {
  AccuracyRow row;
  row.regime = regime.name;
  row.scalar = scalar;
  row.method = method;
  row.round_trip = round_trip;
  row.answered = all.answered;
  row.refused = all.refused;
  row.violating = all.violating;
  const Stats s = stats_of(all.ulps);
  row.max_ulps = s.max;
  row.p999_ulps = s.p999;
  row.mean_ulps = s.mean;
  row.ns_per_call = ns;
  row.max_bound_ratio = all.max_bound_ratio;
  report.rows.push_back(row);
  if (regime.parameter.empty()) return;
  for (std::size_t k = 0; k < regime.values.size(); ++k) {
    if (by_step[k].ulps.empty()) continue;
    StiffnessPoint p;
    p.regime = regime.name;
    p.parameter = regime.parameter;
    p.scalar = scalar;
    p.method = method;
    p.value = regime.values[k];
    p.max_ulps = stats_of(by_step[k].ulps).max;
    p.max_bound_ratio = by_step[k].max_bound_ratio;
    report.stiffness.push_back(p);
  }
}

template <class T>
struct Case {
  Matrix4<T> matrix;
  Vector4<T> plane;
  Convention convention;
  std::size_t step;
};

template <class T>
void measure_scalar(const Regime& regime, const std::vector<Input>& inputs,
                    const std::vector<std::size_t>& steps, const AccuracyOptions& options,
                    AccuracyReport& report) {
  std::vector<Case<T>> cases;
  std::vector<oracle::Problem<T>> problems;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Case<T> c{inputs[i].matrix.template cast<T>(), inputs[i].plane.template cast<T>(),
              inputs[i].convention, steps[i]};
    if (!all_finite(c.matrix) || !all_finite(c.plane)) continue;
    problems.emplace_back(c.matrix, c.plane, c.convention);
    cases.push_back(c);
  }
  for (Method method : kMethods) {
    Errors all;
    std::vector<Errors> by_step(regime.values.size());
    std::vector<const Case<T>*> timed;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case<T>& c = cases[i];
      const oracle::Problem<T>& problem = problems[i];
      if (method == Method::closed_form && !has_perspective_shape(c.matrix)) continue;
      if (problem.exact_status() != Status::ok) continue;
      timed.push_back(&c);
      const ObliqueResult<T> r = apply<T>(c.matrix, c.plane, c.convention, method);
      Errors& step = by_step[c.step];
      if (!r.ok()) {
        ++all.refused;
        ++step.refused;
        continue;
      }
      record(problem, r.projection, all, step);
    }
    if (timed.empty()) continue;
    // Time per call: every answered case in turn, several passes; a checksum keeps the calls.
    double checksum = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int pass = 0; pass < options.timing_repeats; ++pass) {
      for (const Case<T>* c : timed)
        checksum += static_cast<double>(
            apply<T>(c->matrix, c->plane, c->convention, method).projection(2, 2));
    }
    const double elapsed =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    if (checksum == 0.123456789) std::abort();  // never: only keeps the calls alive
    add_rows(
        regime, std::string(protocol::scalar_name<T>()), std::string(method_name(method)), false,
        elapsed / (static_cast<double>(options.timing_repeats) * static_cast<double>(timed.size())),
        all, by_step, report);
  }
}

/// The same cases sent to an implementation over the pipe, in T: each answer's error, the
/// round trip per request (every case of the regime sent at once, timed to the last answer).
/// Empty, or what went wrong.
template <class T>
std::string measure_external(const Regime& regime, const std::vector<Input>& inputs,
                             const std::vector<std::size_t>& steps,
                             const ExternalImplementation& impl, client::Program& program,
                             cases::StatusContract statuses, AccuracyReport& report) {
  std::vector<Case<T>> cases;
  std::vector<oracle::Problem<T>> problems;
  std::vector<std::string> requests;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Case<T> c{inputs[i].matrix.template cast<T>(), inputs[i].plane.template cast<T>(),
              inputs[i].convention, steps[i]};
    if (!all_finite(c.matrix) || !all_finite(c.plane)) continue;
    oracle::Problem<T> problem(c.matrix, c.plane, c.convention);
    if (problem.exact_status() != Status::ok) continue;
    requests.push_back(protocol::request_line(c.matrix, c.plane, c.convention));
    problems.push_back(std::move(problem));
    cases.push_back(c);
  }
  if (cases.empty()) return "";
  // The count check (the client's, before and after each regime's requests): one answer line a
  // request.
  const RoundTrip trip = time_round_trip(program, requests);
  if (trip.failure) {
    using Cause = client::Failure::Cause;
    const client::Failure& f = *trip.failure;
    if (f.cause == Cause::left_over || f.cause == Cause::beyond)
      return impl.command + ": wrote lines beyond one answer per request (" +
             (f.cause == Cause::left_over ? "before" : "after") + " regime " + regime.name +
             "): " + f.lines.front();
    if (f.cause == Cause::overlong)
      return impl.command + ": an answer line longer than 1 MiB in regime " + regime.name +
             " (not read further)";
    return impl.command + ": answered " + std::to_string(trip.lines.size()) + " of the " +
           std::to_string(cases.size()) + " requests of regime " + regime.name + " (" +
           (f.cause == Cause::timed_out ? "timed out"
            : f.ended.empty()           ? f.what
                                        : f.ended) +
           ")";
  }
  const std::vector<std::string>& lines = trip.lines;
  Errors all;
  std::vector<Errors> by_step(regime.values.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Expected<Answer<T>> answer = protocol::read_answer<T>(lines[i]);
    if (!answer)
      return impl.command + ": answer " + std::to_string(i + 1) + " of regime " + regime.name +
             " is not an answer (" + answer.error() + ")";
    Errors& step = by_step[cases[i].step];
    // Only answers that pass the properties are profiled (a refusal is judged by the contract's
    // statuses: any refusal by default).
    cases::Checks checks;
    checks.statuses = statuses;
    const Answer<T> outcome{answer->status, answer->projection};
    if (oracle::judge(problems[i], outcome, checks).violation()) {
      ++all.violating;
      continue;
    }
    if (answer->status != Status::ok) {
      ++all.refused;
      ++step.refused;
      continue;
    }
    record(problems[i], answer->projection, all, step);
  }
  add_rows(regime, std::string(protocol::scalar_name<T>()), impl.name, true, trip.ns, all, by_step,
           report);
  return "";
}

std::string number(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

}  // namespace

AccuracyReport measure_accuracy(const AccuracyOptions& options, std::ostream& progress) {
  AccuracyReport report;
  std::mt19937_64 rng(options.seed);
  const auto all = regimes();
  // One process for each implementation, asked regime after regime.
  const auto timeout =
      std::chrono::milliseconds(static_cast<long>(options.request_timeout_seconds * 1000));
  std::vector<std::unique_ptr<client::Program>> programs;
  for (const ExternalImplementation& impl : options.implementations)
    programs.push_back(std::make_unique<client::Program>(impl.command, timeout));
  const Contract& contract = options.contract;
  const std::vector<Convention> conventions =
      contract.conventions.empty()
          ? std::vector<Convention>(std::begin(all_conventions), std::end(all_conventions))
          : contract.conventions;
  const cases::StatusContract statuses =
      contract.statuses.value_or(cases::StatusContract::any_refusal);
  for (std::size_t r = 0; r < all.size(); ++r) {
    const Regime& regime = all[r];
    const bool claimed =
        contract.families.empty() || std::find(contract.families.begin(), contract.families.end(),
                                               regime.family) != contract.families.end();
    if (options.progress)
      progress << "report accuracy: regime " << (r + 1) << "/" << all.size() << " " << regime.name
               << (claimed
                       ? std::string()
                       : " left out (its family " + std::string(cases::family_name(regime.family)) +
                             " is not in the contract)")
               << "\n"
               << std::flush;
    if (!claimed) continue;
    report.regimes.push_back(regime.name);
    std::vector<Input> inputs;
    std::vector<std::size_t> steps;
    for (std::size_t k = 0; k < regime.values.size(); ++k) {
      int made = 0;
      for (int attempt = 0; made < options.cases_per_step && attempt < 20 * options.cases_per_step;
           ++attempt) {
        const Convention c = conventions[static_cast<std::size_t>(attempt) % conventions.size()];
        if (auto input = regime.make(rng, regime.values[k], c)) {
          inputs.push_back(*input);
          steps.push_back(k);
          ++made;
        }
      }
    }
    measure_scalar<float>(regime, inputs, steps, options, report);
    measure_scalar<double>(regime, inputs, steps, options, report);
    measure_scalar<long double>(regime, inputs, steps, options, report);
    for (std::size_t i = 0; i < options.implementations.size(); ++i) {
      const ExternalImplementation& impl = options.implementations[i];
      report.error = impl.float32 ? measure_external<float>(regime, inputs, steps, impl,
                                                            *programs[i], statuses, report)
                                  : measure_external<double>(regime, inputs, steps, impl,
                                                             *programs[i], statuses, report);
      if (!report.error.empty()) return report;
    }
  }
  for (const cases::Family f : contract.families) {
    if (std::none_of(all.begin(), all.end(), [f](const Regime& r) { return r.family == f; }))
      report.unmeasured_families.emplace_back(cases::family_name(f));
  }
  if (options.progress && !report.unmeasured_families.empty())
    progress << "report accuracy: not measured (no regime builds them): "
             << protocol::name_list(report.unmeasured_families) << "\n";
  if (report.regimes.empty()) {
    std::vector<std::string> families;
    for (const Regime& regime : all) {
      const std::string name(cases::family_name(regime.family));
      if (std::find(families.begin(), families.end(), name) == families.end())
        families.push_back(name);
    }
    report.error =
        "no regime builds projections of a family the contract claims (the regimes' "
        "families: " +
        protocol::name_list(families) + "): nothing to measure";
    return report;
  }
  // The count check of the last regime: once their input is closed, the implementations have
  // nothing more to say (at most a second each to say it).
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const std::vector<std::string> extra = programs[i]->finish();
    if (!extra.empty()) {
      report.error = options.implementations[i].command +
                     ": wrote lines beyond one answer per request: " + extra.front();
      return report;
    }
  }
  return report;
}

std::map<std::pair<std::string, std::string>, OverallPoint> overall_points(
    const AccuracyReport& report) {
  std::map<std::pair<std::string, std::string>, OverallPoint> points;
  std::map<std::pair<std::string, std::string>, int> regimes;
  for (const AccuracyRow& row : report.rows) {
    if (row.answered == 0) continue;
    const auto key = std::make_pair(row.method, row.scalar);
    OverallPoint& p = points[key];
    p.ns_per_call += row.ns_per_call;  // a sum until divided below
    p.round_trip = row.round_trip;
    p.max_ulps = std::max(p.max_ulps, row.max_ulps);
    p.p999_ulps = std::max(p.p999_ulps, row.p999_ulps);
    p.max_bound_ratio = std::max(p.max_bound_ratio, row.max_bound_ratio);
    ++regimes[key];
  }
  for (auto& [key, p] : points) p.ns_per_call /= regimes[key];
  std::vector<std::pair<double, double>> at;
  for (const auto& [key, p] : points) at.emplace_back(p.ns_per_call, p.max_ulps);
  const std::vector<bool> front = non_dominated(at);
  std::size_t i = 0;
  for (auto& [key, p] : points) p.on_front = front[i++];
  return points;
}

std::vector<std::string> unprofiled_implementations(const AccuracyReport& report) {
  std::map<std::string, std::array<long, 3>> by_method;  // answered, refused, violating
  std::vector<std::string> order;
  for (const AccuracyRow& r : report.rows) {
    if (!r.round_trip) continue;
    if (!by_method.count(r.method)) order.push_back(r.method);
    auto& n = by_method[r.method];
    n[0] += r.answered;
    n[1] += r.refused;
    n[2] += r.violating;
  }
  std::vector<std::string> out;
  for (const std::string& method : order) {
    const auto& n = by_method[method];
    if (n[0] > 0) continue;
    out.push_back(method + ": no answer profiled (" + std::to_string(n[2]) +
                  " violating the properties, " + std::to_string(n[1]) +
                  " refused): nothing of it was measured");
  }
  return out;
}

std::optional<std::vector<std::filesystem::path>> write_accuracy_report(
    const AccuracyReport& report, const AccuracyOptions& options, std::ostream& log) {
  ReportFiles files(options.out_dir);

  std::ostream& csv = files.open("accuracy.csv");
  csv << "regime,scalar,method,answered,refused,max_ulps,p999_ulps,mean_ulps,max_bits,p999_bits,"
         "mean_bits,ns_per_call,max_error_over_bound,timing,violating\n";
  csv.precision(17);
  for (const AccuracyRow& r : report.rows) {
    csv << r.regime << ',' << r.scalar << ',' << r.method << ',' << r.answered << ',' << r.refused
        << ',' << r.max_ulps << ',' << r.p999_ulps << ',' << r.mean_ulps << ','
        << bits_lost(r.max_ulps) << ',' << bits_lost(r.p999_ulps) << ',' << bits_lost(r.mean_ulps)
        << ',' << r.ns_per_call << ',' << r.max_bound_ratio << ','
        << (r.round_trip ? "round_trip" : "in_process") << ',' << r.violating << '\n';
  }

  std::ostream& stiff = files.open("stiffness.csv");
  stiff << "regime,parameter,value,scalar,method,max_ulps,max_bits,max_error_over_bound\n";
  stiff.precision(17);
  for (const StiffnessPoint& p : report.stiffness) {
    stiff << p.regime << ',' << p.parameter << ',' << p.value << ',' << p.scalar << ',' << p.method
          << ',' << p.max_ulps << ',' << bits_lost(p.max_ulps) << ',' << p.max_bound_ratio << '\n';
  }

  const auto overall = overall_points(report);

  std::ostream& md = files.open("accuracy.md");
  md << "Each answer's error is its worst entry of row 3 against the exact answer, in ulps of the "
        "row (of its largest entry); bits lost = log2(ulps + 1). The core's methods are timed "
        "in this process (ns per call); an implementation given with --impl over the pipe (ns "
        "per request, round trip: JSON both ways and the program's own work).\n\n";
  if (contract_json(options.contract) != contract_json(Contract{}))
    md << "Measured under the contract `" << contract_json(options.contract) << "`: the regimes "
       << protocol::name_list(report.regimes)
       << ", an implementation's refusals judged by its statuses."
       << (report.unmeasured_families.empty()
               ? std::string()
               : " Not measured: the families " + protocol::name_list(report.unmeasured_families) +
                     " of the contract (no regime builds them).")
       << "\n\n";
  md << "| method | scalar | max error (ulp) | max error (bits) | worst 99.9th pct (ulp) | "
        "ns per answer (mean over regimes) | max error / checker bound | on the front |\n"
        "|---|---|---:|---:|---:|---:|---:|:---:|\n";
  for (const auto& [key, o] : overall) {
    md << "| " << key.first << " | " << key.second << " | " << number(o.max_ulps) << " | "
       << number(bits_lost(o.max_ulps)) << " | " << number(o.p999_ulps) << " | "
       << number(o.ns_per_call) << (o.round_trip ? " (round trip)" : "") << " | "
       << number(o.max_bound_ratio) << " | " << (o.on_front ? "yes" : "") << " |\n";
  }
  std::vector<std::string> methods{"closed_form", "general", "accurate"};
  for (const ExternalImplementation& impl : options.implementations) methods.push_back(impl.name);
  md << "\nPer regime (max / 99.9th percentile / mean error in ulps, ns per answer):\n\n"
        "| regime | scalar";
  for (const std::string& m : methods) md << " | " << m;
  md << " |\n|---|---";
  for (std::size_t i = 0; i < methods.size(); ++i) md << "|---";
  md << "|\n";
  std::map<std::pair<std::string, std::string>, std::map<std::string, const AccuracyRow*>> cells;
  std::vector<std::pair<std::string, std::string>> order;
  for (const AccuracyRow& r : report.rows) {
    const auto key = std::make_pair(r.regime, r.scalar);
    if (cells.find(key) == cells.end()) order.push_back(key);
    cells[key][r.method] = &r;
  }
  for (const auto& key : order) {
    md << "| " << key.first << " | " << key.second;
    for (const std::string& m : methods) {
      const auto it = cells[key].find(m);
      if (it == cells[key].end() || it->second->answered == 0) {
        md << " | n/a";
        if (it != cells[key].end() && it->second->violating > 0)
          md << " (none profiled: " << it->second->violating << " violating the properties)";
        continue;
      }
      const AccuracyRow& r = *it->second;
      md << " | " << number(r.max_ulps) << " / " << number(r.p999_ulps) << " / "
         << number(r.mean_ulps) << ", " << number(r.ns_per_call) << " ns";
      if (r.refused > 0) md << " (" << r.refused << " refused)";
      if (r.violating > 0) md << " (" << r.violating << " violating the properties, not profiled)";
    }
    md << " |\n";
  }

  // Error against time: one point per (method, scalar), in the method's colour (the profiles'
  // colours: an implementation first, then the core's three) with the scalar's point type.
  auto method_colour = [&methods](const std::string& method) {
    const auto at = static_cast<std::size_t>(std::find(methods.begin(), methods.end(), method) -
                                             methods.begin());
    return at < 3 ? at + 1 : at == 3 ? 0 : at + 1;
  };
  std::vector<TimePoint> chart;
  for (const auto& [key, o] : overall) {
    const int point_type = key.second == "float" ? 9 : key.second == "double" ? 7 : 5;
    chart.push_back({key.first + " (" + key.second + ")" + (o.round_trip ? ", round trip" : ""),
                     o.ns_per_call, bits_lost(o.max_ulps), bits_lost(o.p999_ulps),
                     method_colour(key.first), point_type});
  }
  stage_time_chart(files, "accuracy", "oblique: error against run time (worst over every regime)",
                   "ns per answer, mean over regimes (log scale): a call in process, or a request "
                   "over the pipe (round trip)",
                   chart);

  // Stiffness: one panel per swept regime, error in bits against the parameter, double only.
  std::vector<std::string> swept;
  for (const StiffnessPoint& p : report.stiffness) {
    if (std::find(swept.begin(), swept.end(), p.regime) == swept.end()) swept.push_back(p.regime);
  }
  // A block is written only where it has points (gnuplot counts no empty one), so each
  // panel names the blocks it has.
  std::ostream& sdat = files.open("stiffness.dat");
  std::vector<std::string> panels;
  int blocks = 0;
  for (const std::string& regime : swept) {
    std::string plot;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      // The core's methods in double; an implementation in the type it answers in.
      const std::string scalar =
          m < 3 ? "double" : (options.implementations[m - 3].float32 ? "float" : "double");
      std::ostringstream block;
      block.precision(17);
      for (const StiffnessPoint& p : report.stiffness) {
        if (p.regime == regime && p.method == methods[m] && p.scalar == scalar)
          block << p.value << ' ' << bits_lost(p.max_ulps) << '\n';
      }
      if (block.str().empty()) continue;
      sdat << "# " << regime << ' ' << methods[m] << " (" << scalar << ")\n"
           << block.str() << "\n\n";
      plot += std::string(plot.empty() ? "" : ", ") + "'stiffness.dat'" + " index " +
              std::to_string(blocks++) + " using 1:2 with linespoints pt 7 lw 2 lc rgb '" +
              chart_colour(method_colour(methods[m])) + "' title " + gnuplot_string(methods[m]);
    }
    panels.push_back(plot);
  }
  std::ostream& sgp = files.open("stiffness.gp");
  sgp << "set terminal pngcairo size 1200," << 340 * ((swept.size() + 1) / 2)
      << " noenhanced\nset output "
      << "'stiffness.png'"
      << "\nset multiplot layout " << (swept.size() + 1) / 2
      << ",2 title 'oblique: worst error against the stiffness of each regime (the core in "
         "double)'\n"
         "set logscale x\nset ylabel 'max error, bits lost'\nset yrange [-1:*]\nset grid\n"
         "set key top left\n";
  for (std::size_t k = 0; k < swept.size(); ++k) {
    std::string parameter;
    for (const StiffnessPoint& p : report.stiffness)
      if (p.regime == swept[k]) parameter = p.parameter;
    sgp << "set title " << gnuplot_string(swept[k]) << "\nset xlabel " << gnuplot_string(parameter)
        << "\nplot " << panels[k] << "\n";
  }
  sgp << "unset multiplot\n";

  // Drawn before the commit, so the pictures come with the rest or not at all.
  std::ostringstream plot_log;
  // Why gnuplot did not draw it (a folder that cannot be made is said once, by the commit).
  if (!files.plot_staged("stiffness.gp", "stiffness.png", plot_log) &&
      plot_log.str().rfind("report: ", 0) != 0)
    log << "report: " << plot_log.str() << "\n";
  if (!files.commit(log)) return std::nullopt;
  return files.written();
}

}  // namespace oblique::report
