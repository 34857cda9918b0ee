#include "oblique/report/accuracy_profile.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <sstream>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/projection.h"
#include "oblique/protocol/json.h"
#include "oblique/protocol/numbers.h"
#include "oblique/report/report_files.h"
#include "oblique/report/views.h"

namespace oblique::report {

double ProfiledAnswer::worst_ulps() const {
  return *std::max_element(std::begin(ulps), std::end(ulps));
}

double bits_lost(double ulps) {
  return std::log2(ulps + 1);
}

template <class T>
ProfiledAnswer profile_answer(const oracle::Problem<T>& problem, const Matrix4<T>& answer) {
  ProfiledAnswer out;
  out.convention = problem.convention();
  out.kappa = oracle::approx(problem.kappa());
  const oracle::exact::Vec row = problem.exact_row3();
  // The row's ulp: that of its largest entry, correctly rounded (the subnormal quantum at 0).
  oracle::exact::Rational largest = 0;
  for (const oracle::exact::Rational& x : row) largest = std::max(largest, oracle::exact::abs(x));
  const T top = oracle::exact::round_to<T>(largest);
  constexpr int p = std::numeric_limits<T>::digits;
  const long lowest = std::numeric_limits<T>::min_exponent - p;
  const long quantum =
      top == T(0) ? lowest : std::max(static_cast<long>(std::ilogb(top)) - p + 1, lowest);
  for (int j = 0; j < 4; ++j) {
    const T rounded = oracle::exact::round_to<T>(row[j]);
    if (!std::isfinite(answer(2, j)) || !std::isfinite(rounded)) {
      out.ulps[j] = std::numeric_limits<double>::infinity();
      continue;
    }
    const oracle::exact::Rational gap = oracle::exact::abs(oracle::exact::Rational(
        oracle::exact::to_rational(answer(2, j)) - oracle::exact::to_rational(rounded)));
    out.ulps[j] = oracle::exact::Rational(gap / oracle::exact::power_of_two(quantum)).get_d();
  }
  return out;
}

template ProfiledAnswer profile_answer<float>(const oracle::Problem<float>&, const Matrix4<float>&);
template ProfiledAnswer profile_answer<double>(const oracle::Problem<double>&,
                                               const Matrix4<double>&);
template ProfiledAnswer profile_answer<long double>(const oracle::Problem<long double>&,
                                                    const Matrix4<long double>&);

template <class T>
void record_answer(Profile& profile, const oracle::Problem<T>& problem,
                   const ProfileInput<T>& input, Status status, const Matrix4<T>& projection) {
  if (status != Status::ok) {
    ++profile.refused;
    return;
  }
  ProfiledAnswer a = profile_answer(problem, projection);
  a.family = input.family;
  a.place = input.place;
  a.request = input.request;
  profile.answers.push_back(std::move(a));
}

template void record_answer<float>(Profile&, const oracle::Problem<float>&,
                                   const ProfileInput<float>&, Status, const Matrix4<float>&);
template void record_answer<double>(Profile&, const oracle::Problem<double>&,
                                    const ProfileInput<double>&, Status, const Matrix4<double>&);
template void record_answer<long double>(Profile&, const oracle::Problem<long double>&,
                                         const ProfileInput<long double>&, Status,
                                         const Matrix4<long double>&);

RoundTrip time_round_trip(client::Program& program, const std::vector<std::string>& requests) {
  RoundTrip out;
  if (requests.empty()) return out;
  if (!program.running()) {
    client::Reply warm = program.ask(requests.front());
    if (warm.failure) {
      out.failure = std::move(warm.failure);
      return out;
    }
  }
  const auto start = client::Clock::now();
  client::Reply reply = program.ask(requests);
  out.lines = std::move(reply.lines);
  out.failure = std::move(reply.failure);
  if (!out.failure)
    out.ns = std::chrono::duration<double, std::nano>(client::Clock::now() - start).count() /
             static_cast<double>(requests.size());
  return out;
}

std::vector<bool> non_dominated(const std::vector<std::pair<double, double>>& points) {
  std::vector<bool> out(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [ns, bits] = points[i];
    if (std::isnan(ns) || std::isnan(bits)) continue;
    out[i] = std::none_of(points.begin(), points.end(), [&](const auto& q) {
      return q.first <= ns && q.second <= bits && (q.first < ns || q.second < bits);
    });
  }
  return out;
}

const char* chart_colour(std::size_t index) {
  static const char* colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f"};
  return colours[index % (sizeof colours / sizeof *colours)];
}

bool stage_time_chart(ReportFiles& files, const std::string& stem, const std::string& title,
                      const std::string& xlabel, const std::vector<TimePoint>& points) {
  // A point without a time or an error is not drawn; every block written holds a point, so
  // the blocks gnuplot counts are the ones named below.
  std::vector<const TimePoint*> drawn;
  for (const TimePoint& p : points)
    if (!std::isnan(p.ns) && !std::isnan(p.worst_bits)) drawn.push_back(&p);
  std::ostream& dat = files.open(stem + "_points.dat");
  std::vector<std::pair<double, double>> at;
  for (const TimePoint* p : drawn) {
    dat << "# " << p->label << "\n"
        << p->ns << ' ' << p->worst_bits << ' ' << p->p999_bits << "\n\n\n";
    at.emplace_back(p->ns, p->worst_bits);
  }
  const std::vector<bool> on_front = non_dominated(at);
  std::vector<std::pair<double, double>> front;
  for (std::size_t i = 0; i < at.size(); ++i)
    if (on_front[i]) front.push_back(at[i]);
  std::sort(front.begin(), front.end());
  std::ostream& front_file = files.open(stem + "_front.dat");
  front_file << "# the non-dominated points, by time\n";
  for (const auto& [ns, bits] : front) front_file << ns << ' ' << bits << '\n';
  std::ostream& gp = files.open(stem + ".gp");
  gp << "set terminal pngcairo size 1000,760 noenhanced\nset output '" << stem
     << ".png'\nset title " << gnuplot_string(title) << "\nset xlabel " << gnuplot_string(xlabel)
     << "\nset logscale x\nset ylabel 'bits lost: worst answer (filled), 99.9th percentile "
        "(open)'\nset yrange [-1:*]\nset grid\n"
        "set key outside below\nplot '"
     << stem << "_front.dat' using 1:2 with steps lw 2 lc rgb '#aaaaaa' title "
     << "'non-dominated front'";
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const TimePoint& p = *drawn[i];
    gp << ", '" << stem << "_points.dat' index " << i << " using 1:2 with points pt "
       << p.point_type << " ps 2 lc rgb '" << chart_colour(p.colour) << "' title "
       << gnuplot_string(p.label);
    if (!std::isnan(p.p999_bits))
      gp << ", '' index " << i << " using 1:3 with points pt " << p.point_type - 1
         << " ps 2 lc rgb '" << chart_colour(p.colour) << "' notitle";
  }
  gp << "\n";
  std::ostringstream plot_log;
  return files.plot_staged(stem + ".gp", stem + ".png", plot_log);
}

double ns_per_call(std::size_t count, const std::function<void(std::size_t)>& call) {
  if (count == 0) return std::numeric_limits<double>::quiet_NaN();
  using Clock = std::chrono::steady_clock;
  std::vector<double> measured;
  for (int repeat = 0; repeat < 5; ++repeat) {
    long calls = 0;
    const auto start = Clock::now();
    double seconds = 0;
    while (seconds < 0.1) {
      for (std::size_t i = 0; i < count; ++i) call(i);
      calls += static_cast<long>(count);
      seconds = std::chrono::duration<double>(Clock::now() - start).count();
    }
    measured.push_back(seconds * 1e9 / static_cast<double>(calls));
  }
  std::sort(measured.begin(), measured.end());
  return measured[measured.size() / 2];
}

template <class T>
std::vector<Profile> core_profiles(const std::vector<ProfileInput<T>>& inputs) {
  constexpr Method methods[] = {Method::closed_form, Method::general, Method::accurate};
  std::vector<Profile> out(3);
  std::vector<std::vector<const ProfileInput<T>*>> asked(3);
  for (std::size_t m = 0; m < 3; ++m) {
    out[m].name = "core " + std::string(method_name(methods[m]));
    out[m].scalar = std::string(protocol::scalar_name<T>());
    out[m].core = true;
    out[m].timing = Timing::in_process;
  }
  // One exact problem a case, for the three methods.
  for (const ProfileInput<T>& in : inputs) {
    const oracle::Problem<T> problem(in.matrix, in.plane, in.convention);
    if (problem.exact_status() != Status::ok) continue;
    for (std::size_t m = 0; m < 3; ++m) {
      if (methods[m] == Method::closed_form && !has_perspective_shape(in.matrix)) continue;
      asked[m].push_back(&in);
      const ObliqueResult<T> r = apply<T>(in.matrix, in.plane, in.convention, methods[m]);
      record_answer(out[m], problem, in, r.status, r.projection);
    }
  }
  for (std::size_t m = 0; m < 3; ++m) {
    // A checksum keeps the calls from being optimised away.
    T checksum = 0;
    out[m].ns = ns_per_call(asked[m].size(), [&](std::size_t i) {
      const ProfileInput<T>& in = *asked[m][i];
      checksum += apply<T>(in.matrix, in.plane, in.convention, methods[m]).projection(2, 2);
    });
    if (checksum == T(0.123456789)) out[m].name += " ";  // never; keeps the checksum alive
  }
  return out;
}

template std::vector<Profile> core_profiles<float>(const std::vector<ProfileInput<float>>&);
template std::vector<Profile> core_profiles<double>(const std::vector<ProfileInput<double>>&);
template std::vector<Profile> core_profiles<long double>(
    const std::vector<ProfileInput<long double>>&);

namespace {

struct Summary {
  long answers = 0;
  double worst = 0, p999 = 0, mean = 0;  ///< bits lost, over the answers' worst entries
};

Summary summary_of(const std::vector<const ProfiledAnswer*>& answers) {
  Summary s;
  s.answers = static_cast<long>(answers.size());
  if (answers.empty()) return s;
  std::vector<double> bits;
  for (const ProfiledAnswer* a : answers) bits.push_back(bits_lost(a->worst_ulps()));
  std::sort(bits.begin(), bits.end());
  s.worst = bits.back();
  s.p999 =
      bits[std::min(bits.size() - 1, static_cast<std::size_t>(std::ceil(0.999 * bits.size())) - 1)];
  double sum = 0;
  for (double b : bits) sum += std::isfinite(b) ? b : 0;
  s.mean = sum / static_cast<double>(bits.size());
  return s;
}

std::string fixed(double x, int digits = 2) {
  if (std::isnan(x)) return "n/a";
  if (std::isinf(x)) return "inf";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

std::string time_text(const Profile& p) {
  if (p.timing == Timing::none || std::isnan(p.ns)) return "not measured";
  char text[96];
  if (p.ns >= 1e4)
    std::snprintf(text, sizeof text, "%.1f us", p.ns / 1e3);
  else
    std::snprintf(text, sizeof text, "%.1f ns", p.ns);
  return std::string(text) +
         (p.timing == Timing::round_trip ? " a request, round trip over the pipe" : " a call");
}

/// kappa's decade: k with 10^k <= kappa < 10^(k + 1), 0 below 10.
int kappa_decade(double kappa) {
  return kappa >= 10 ? static_cast<int>(std::floor(std::log10(kappa))) : 0;
}

/// kappa's decade as a group name that sorts as the decades do: "kappa < 1e01",
/// "1e01 <= kappa < 1e02", ...
std::string kappa_group(double kappa) {
  const int k = kappa_decade(kappa);
  char name[48];
  if (k == 0)
    std::snprintf(name, sizeof name, "kappa < 1e01");
  else
    std::snprintf(name, sizeof name, "1e%02d <= kappa < 1e%02d", k, k + 1);
  return name;
}

/// Answers of `p` grouped by `key`.
std::map<std::string, std::vector<const ProfiledAnswer*>> grouped(
    const Profile& p, const std::function<std::string(const ProfiledAnswer&)>& key) {
  std::map<std::string, std::vector<const ProfiledAnswer*>> out;
  for (const ProfiledAnswer& a : p.answers) out[key(a)].push_back(&a);
  return out;
}

std::vector<const ProfiledAnswer*> all_of(const Profile& p) {
  std::vector<const ProfiledAnswer*> out;
  for (const ProfiledAnswer& a : p.answers) out.push_back(&a);
  return out;
}

/// A profile's name in the charts' keys.
std::string chart_label(const Profile& p) {
  std::string label = p.name + " (" + p.scalar + ")";
  if (p.timing == Timing::round_trip) label += ", round trip over the pipe";
  return label;
}

/// A table of `groups` (rows) by profile (columns): worst bits lost and the answers counted.
void group_table(std::ostream& md, const std::vector<Profile>& profiles, const std::string& title,
                 const std::function<std::string(const ProfiledAnswer&)>& key) {
  std::vector<std::map<std::string, std::vector<const ProfiledAnswer*>>> by;
  std::vector<std::string> rows;
  for (const Profile& p : profiles) {
    by.push_back(grouped(p, key));
    for (const auto& [name, answers] : by.back())
      if (std::find(rows.begin(), rows.end(), name) == rows.end()) rows.push_back(name);
  }
  // Names sort as they read, except that "kappa < 1e01" comes before the decades above it.
  std::sort(rows.begin(), rows.end(), [](const std::string& a, const std::string& b) {
    const bool a_low = a.rfind("kappa <", 0) == 0, b_low = b.rfind("kappa <", 0) == 0;
    return a_low != b_low ? a_low : a < b;
  });
  md << "\n### By " << title << "\n\nWorst bits lost (answers):\n\n| " << title;
  for (const Profile& p : profiles) md << " | " << p.name;
  md << " |\n|---";
  for (std::size_t i = 0; i < profiles.size(); ++i) md << "|---:";
  md << "|\n";
  for (const std::string& row : rows) {
    md << "| " << row;
    for (const auto& groups : by) {
      const auto it = groups.find(row);
      if (it == groups.end()) {
        md << " | -";
        continue;
      }
      const Summary s = summary_of(it->second);
      md << " | " << fixed(s.worst) << " (" << s.answers << ")";
    }
    md << " |\n";
  }
}

std::string json_list(const double (&values)[4]) {
  std::string out = "[";
  for (int i = 0; i < 4; ++i)
    out += (i ? ", " : "") +
           (std::isfinite(values[i]) ? protocol::json_number(values[i]) : std::string("null"));
  return out + "]";
}

}  // namespace

std::optional<std::vector<std::filesystem::path>> write_profile_report(
    const std::vector<Profile>& profiles, const ProfileReportOptions& options, std::ostream& log) {
  if (profiles.empty()) {
    log << "no profile to write\n";
    return std::nullopt;
  }
  ReportFiles files(options.dir);
  files.supersede("worst-", ".json");  // a run with fewer worst answers leaves none of before
  const Profile& mine = profiles.front();

  // accuracy.csv: one row per profile and group (all, family, place, kappa decade).
  std::ostream& csv = files.open("accuracy.csv");
  csv << "profile,scalar,timing,ns_per_answer,group,value,answers,refused,worst_bits,"
         "p999_bits,mean_bits\n";
  csv.precision(17);
  for (const Profile& p : profiles) {
    const char* timing = p.timing == Timing::round_trip   ? "round_trip"
                         : p.timing == Timing::in_process ? "in_process"
                                                          : "none";
    auto row = [&](const std::string& group, const std::string& value,
                   const std::vector<const ProfiledAnswer*>& answers) {
      const Summary s = summary_of(answers);
      csv << p.name << ',' << p.scalar << ',' << timing << ',' << p.ns << ',' << group << ','
          << value << ',' << s.answers << ',' << (group == "all" ? p.refused : 0) << ',' << s.worst
          << ',' << s.p999 << ',' << s.mean << '\n';
    };
    row("all", "", all_of(p));
    for (const auto& [f, a] : grouped(p, [](const ProfiledAnswer& x) { return x.family; }))
      row("family", f, a);
    for (const auto& [f, a] : grouped(p, [](const ProfiledAnswer& x) { return x.place; }))
      row("place", f, a);
    for (const auto& [f, a] :
         grouped(p, [](const ProfiledAnswer& x) { return kappa_group(x.kappa); }))
      row("kappa", f, a);
  }

  // The worst answers of the implementation, each a case `oblique verify --replay` reads.
  std::vector<const ProfiledAnswer*> worst = all_of(mine);
  std::stable_sort(worst.begin(), worst.end(),
                   [](const ProfiledAnswer* a, const ProfiledAnswer* b) {
                     return a->worst_ulps() > b->worst_ulps();
                   });
  if (static_cast<int>(worst.size()) > options.worst) worst.resize(options.worst);

  std::ostream& md = files.open("accuracy.md");
  md << "# Accuracy profile: " << options.title << "\n\n"
     << "Each answer that passed the properties, row 3 entry by entry against the exact answer "
        "(GMP): bits lost = log2(ulps + 1), 0 for the correctly rounded answer; an answer's "
        "error is its worst entry. The core's methods were asked the same cases in the same "
        "run, in this process.\n\n"
     << "| | scalar | answers | worst bits | 99.9th pct | mean | time |\n"
        "|---|---|---:|---:|---:|---:|---|\n";
  for (const Profile& p : profiles) {
    const Summary s = summary_of(all_of(p));
    md << "| " << p.name << " | " << p.scalar << " | " << s.answers;
    if (p.refused > 0) md << " (+" << p.refused << " refused)";
    md << " | " << fixed(s.worst) << " | " << fixed(s.p999) << " | " << fixed(s.mean, 3) << " | "
       << time_text(p) << " |\n";
  }
  md << "\n![error against time](accuracy.png)\n\n![error against stiffness](stiffness.png)\n";
  group_table(md, profiles, "family", [](const ProfiledAnswer& a) { return a.family; });
  group_table(md, profiles, "place", [](const ProfiledAnswer& a) { return a.place; });
  group_table(md, profiles, "kappa", [](const ProfiledAnswer& a) { return kappa_group(a.kappa); });

  md << "\n## The worst answers of " << mine.name << "\n\n";
  if (worst.empty()) md << "No answer was profiled.\n";
  for (std::size_t k = 0; k < worst.size(); ++k) {
    const ProfiledAnswer& a = *worst[k];
    const std::string json = "worst-" + std::to_string(k + 1) + ".json";
    files.open(json) << "{\"type\": \"accuracy\", \"precision\": "
                     << protocol::json_string(mine.scalar)
                     << ", \"family\": " << protocol::json_string(a.family)
                     << ", \"place\": " << protocol::json_string(a.place)
                     << ", \"kappa\": " << protocol::json_number(a.kappa)
                     << ", \"ulps\": " << json_list(a.ulps)
                     << ", \"request\": " << protocol::json_string(a.request) << "}\n";
    md << k + 1 << ". " << fixed(bits_lost(a.worst_ulps()))
       << " bits lost (ulps per entry: " << fixed(a.ulps[0], 1) << ", " << fixed(a.ulps[1], 1)
       << ", " << fixed(a.ulps[2], 1) << ", " << fixed(a.ulps[3], 1) << "), family `" << a.family
       << "`, place `" << a.place << "`, " << convention_name(a.convention) << ", kappa "
       << protocol::json_number(a.kappa) << " ([" << json << "](" << json << "))\n\n   ```sh\n   "
       << (options.replay ? options.replay(a, (options.dir / json).string())
                          : "# the request: " + a.request)
       << "\n   ```\n";
  }

  // Error against time: one point per profile (worst and 99.9th percentile), a colour each.
  std::vector<TimePoint> points;
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    const Summary s = summary_of(all_of(profiles[i]));
    const bool drawn = s.answers > 0 && !std::isnan(profiles[i].ns);
    points.push_back({chart_label(profiles[i]), drawn ? profiles[i].ns : NAN, drawn ? s.worst : NAN,
                      s.p999, i, 7});
  }
  stage_time_chart(files, "accuracy", options.title + ": error against time",
                   "time per answer, ns (log scale)", points);

  // Error against stiffness: the worst bits lost in each decade of kappa, a line per profile.
  // A block is written only for a profile with points: gnuplot counts no empty block, and the
  // lines name the blocks written.
  std::ostream& stiff = files.open("stiffness.dat");
  std::string lines;
  int blocks = 0;
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    std::map<int, double> worst_in;
    for (const ProfiledAnswer& a : profiles[i].answers) {
      double& w = worst_in[kappa_decade(a.kappa)];
      w = std::max(w, std::min(bits_lost(a.worst_ulps()), 1e9));
    }
    if (worst_in.empty()) continue;
    stiff << "# " << profiles[i].name << "\n";
    for (const auto& [decade, bits] : worst_in)
      stiff << std::pow(10.0, decade) << ' ' << bits << '\n';
    stiff << "\n\n";
    lines += std::string(lines.empty() ? "" : ", ") + "'stiffness.dat' index " +
             std::to_string(blocks++) + " using 1:2 with linespoints pt 7 lw 2 lc rgb '" +
             chart_colour(i) + "' title " + gnuplot_string(chart_label(profiles[i]));
  }
  std::ostream& sgp = files.open("stiffness.gp");
  sgp << "set terminal pngcairo size 900,700 noenhanced\nset output 'stiffness.png'\n"
         "set title "
      << gnuplot_string(options.title + ": error against the stiffness of the case")
      << "\nset xlabel 'kappa, the condition number of C . Q (decades)'\nset logscale x\n"
         "set ylabel 'bits lost, worst answer in the decade'\nset yrange [-0.5:*]\n"
         "set key outside below\nset grid\n";
  if (!lines.empty()) sgp << "plot " << lines << "\n";

  std::ostringstream plot_log;
  files.plot_staged("stiffness.gp", "stiffness.png", plot_log);
  if (!files.commit(log)) return std::nullopt;
  return files.written();
}

}  // namespace oblique::report
