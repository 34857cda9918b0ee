#include "oblique/report/counterexample_report.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oblique.h"
#include "oblique/protocol/protocol.h"
#include "oblique/report/html_page.h"
#include "oblique/report/report_files.h"
#include "oblique/report/views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#ifndef OBLIQUE_COMPILER
#define OBLIQUE_COMPILER "unknown compiler"
#endif
#ifndef OBLIQUE_CXX_FLAGS
#define OBLIQUE_CXX_FLAGS ""
#endif

namespace oblique::report {

using namespace oblique::oracle;  // NOLINT: the judge whose findings are reported

using namespace oblique::mistakes;  // NOLINT: the diagnosis a report shows

template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c,
                                   Convention convention) {
  using protocol::format_number;
  using protocol::Notation;
  Counterexample ce;
  ce.scalar = std::string(protocol::scalar_name<T>());
  ce.convention = std::string(convention_name(convention));
  for (int i = 0; i < 16; ++i) {
    ce.projection_decimal.push_back(format_number(m(i / 4, i % 4)));
    ce.projection_hex.push_back(format_number(m(i / 4, i % 4), Notation::hex));
  }
  for (int i = 0; i < 4; ++i) {
    ce.plane_decimal.push_back(format_number(c(i)));
    ce.plane_hex.push_back(format_number(c(i), Notation::hex));
  }
  ce.request = protocol::request_line(m, c, convention, Notation::hex);
  ce.request_decimal = protocol::request_line(m, c, convention, Notation::shortest);
  return ce;
}

template <class T>
void set_result(Counterexample& ce, const Matrix4<T>& result) {
  ce.result_decimal.clear();
  for (int i = 0; i < 16; ++i)
    ce.result_decimal.push_back(protocol::format_number(result(i / 4, i % 4)));
}

template <class T>
void set_views(Counterexample& ce, const Problem<T>& problem, const Matrix4<T>* answer) {
  CaseViews& v = ce.views;
  v = CaseViews{};
  if (!problem.finite()) return;  // nothing to draw: M or C has a NaN or an infinity
  v.set = true;
  v.convention = problem.convention();
  v.projection = problem.matrix().template cast<double>();
  v.plane = problem.plane().template cast<double>();
  auto to_double = [](const oracle::exact::Vec& p) {
    return Vector4<double>(p[0].get_d(), p[1].get_d(), p[2].get_d(), p[3].get_d());
  };
  if (problem.invertible()) v.far_corner = to_double(problem.far_corner());
  if (problem.exact_status() == Status::ok) {
    Matrix4<double> expected = v.projection;
    const oracle::exact::Vec row3 = problem.exact_row3();
    for (int i = 0; i < 4; ++i) expected(2, i) = row3[i].get_d();
    v.expected = expected;
  }
  if (answer && all_finite(*answer)) {
    v.answer = answer->template cast<double>();
    if (problem.exact_status() == Status::ok) {
      const Verdicts verdicts = problem.check(*answer);
      const Verdict& clipping = verdicts[Property::no_clipping];
      if (!clipping.holds && clipping.point) v.clipped = to_double(*clipping.point);
    }
  }
}

#define OBLIQUE_COUNTEREXAMPLE(T)                                                      \
  template Counterexample make_counterexample<T>(const Matrix4<T>&, const Vector4<T>&, \
                                                 Convention);                          \
  template void set_result<T>(Counterexample&, const Matrix4<T>&);                     \
  template void set_views<T>(Counterexample&, const Problem<T>&, const Matrix4<T>*);
OBLIQUE_COUNTEREXAMPLE(float)
OBLIQUE_COUNTEREXAMPLE(double)
OBLIQUE_COUNTEREXAMPLE(long double)
#undef OBLIQUE_COUNTEREXAMPLE

namespace {

/// finding_numbers() as a JSON object (a non-finite number as its text: JSON has none).
nlohmann::json finding_json_numbers(const Finding& f) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, x] : finding_numbers(f))
    out[name] = std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(protocol::format_number(x));
  return out;
}

std::string matrix_table(const std::vector<std::string>& values) {
  std::ostringstream out;
  out << "| | col 1 | col 2 | col 3 | col 4 |\n|---|---|---|---|---|\n";
  for (int i = 0; i < 4; ++i) {
    out << "| row " << i + 1 << " |";
    for (int j = 0; j < 4; ++j) out << " `" << values[static_cast<std::size_t>(4 * i + j)] << "` |";
    out << "\n";
  }
  return out.str();
}

std::string core_method_of(const std::string& implementation) {
  const std::string prefix = "core_";
  if (implementation.rfind(prefix, 0) != 0) return "";
  const std::string method = implementation.substr(prefix.size());
  return method;
}

/// A homogeneous point as a point of the picture; empty at infinity (w = 0) or non-finite.
std::optional<Eigen::Vector3d> affine(const Vector4<double>& p) {
  if (!(std::abs(p.w()) > 0)) return std::nullopt;
  const Eigen::Vector3d out = p.head<3>() / p.w();
  if (!out.allFinite()) return std::nullopt;
  return out;
}

std::string point_text(const Eigen::Vector3d& p) {
  return "(" + protocol::format_number(p.x()) + ", " + protocol::format_number(p.y()) + ", " +
         protocol::format_number(p.z()) + ")";
}

/// What the pictures mark: in words (the report), in the legend, and the point (when it has one
/// on the picture).
struct Mark {
  std::string what, legend;
  std::optional<Eigen::Vector3d> point;
  std::vector<Eigen::Vector3d> more;  ///< further points of the same mark (a consumer's)
  std::string title;                  ///< the pictures' title, when not the finding's check
};

Mark mark_of(const Counterexample& ce) {
  const CaseViews& v = ce.views;
  const Check check = ce.finding.check;
  if (v.clipped) {
    const std::optional<Eigen::Vector3d> p = affine(*v.clipped);
    if (p)
      return {"the clipped point " + point_text(*p) +
                  ": a vertex of M's view volume on C's side that the answer's far plane cuts away",
              "marked: clipped point",
              p,
              {},
              {}};
    return {"the clipped point is at infinity (direction " + point_text(v.clipped->head<3>()) +
                "): not drawn",
            "marked: nothing (the clipped point is at infinity)",
            std::nullopt,
            {},
            {}};
  }
  if ((check == Check::far_plane_through_corner || check == Check::infinite_edge_parallel) &&
      v.far_corner) {
    const std::optional<Eigen::Vector3d> q = affine(*v.far_corner);
    if (q)
      return {"the far corner Q " + point_text(*q) + ", which the answer's far plane misses",
              "marked: far corner Q",
              q,
              {},
              {}};
    return {"the far corner Q is at infinity (direction " + point_text(v.far_corner->head<3>()) +
                "): not drawn",
            "marked: nothing (Q is at infinity)",
            std::nullopt,
            {},
            {}};
  }
  const std::string why = !v.answer ? "no answer to draw"
                          : !v.expected
                              ? "the input has no answer, so nothing is judged clipped"
                              : "the answer clips no point of M's view volume on C's side";
  const std::string legend = !v.answer     ? "no answer"
                             : !v.expected ? "the input has no answer"
                                           : "the answer clips nothing";
  return {"nothing: " + why + " (the finding is " + std::string(check_name(check)) + ")",
          "marked: nothing (" + legend + ")",
          std::nullopt,
          {},
          {}};
}

/// C's crossing of the volume `edges` (each edge's point on C), in order around it.
std::vector<report::Segment> plane_cut(const std::vector<report::Segment>& edges,
                                       const Vector4<double>& c) {
  std::vector<Eigen::Vector3d> points;
  for (const report::Segment& e : edges) {
    const double da = c.head<3>().dot(e.a) + c.w(), db = c.head<3>().dot(e.b) + c.w();
    if (!(da * db <= 0) || da == db) continue;
    points.push_back(e.a + da / (da - db) * (e.b - e.a));
  }
  std::vector<report::Segment> out;
  if (points.size() < 2) return out;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  const Eigen::Vector3d n = c.head<3>().normalized();
  const Eigen::Vector3d u =
      (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
          .cross(n)
          .normalized();
  const Eigen::Vector3d w = n.cross(u);
  std::sort(points.begin(), points.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::atan2((a - centre).dot(w), (a - centre).dot(u)) <
           std::atan2((b - centre).dot(w), (b - centre).dot(u));
  });
  for (std::size_t i = 0; i < points.size(); ++i)
    out.push_back({points[i], points[(i + 1) % points.size()]});
  return out;
}

/// The case's top and side views: M's view volume, the expected and the answered oblique
/// volumes, C where it cuts M's volume, Q and the marked point.
report::Views case_views(const Counterexample& ce, const std::string& stem, const Mark& mark) {
  const CaseViews& v = ce.views;
  // How far an unbounded volume is drawn: three times the size of what is finite (the near face,
  // a finite far face, Q and the marked point).
  double extent = 0;
  bool unbounded = false;  // a corner at infinity: the volume is cut where `reach` ends
  const Matrix4<double> inverse = v.projection.inverse();
  const DepthRange range = clip_depth_range(v.convention);
  for (int x : {-1, 1}) {
    for (int y : {-1, 1}) {
      for (int z : {range.z_low, range.z_high}) {
        const std::optional<Eigen::Vector3d> p = affine(inverse * Vector4<double>(x, y, z, 1));
        if (p && p->norm() < 1e300) {
          extent = std::max(extent, p->norm());
        } else {
          unbounded = true;
        }
      }
    }
  }
  std::optional<Eigen::Vector3d> q;
  if (v.far_corner) q = affine(*v.far_corner);
  for (const auto& p : {q, mark.point}) {
    if (p) extent = std::max(extent, p->norm());
  }
  for (const Eigen::Vector3d& p : mark.more) extent = std::max(extent, p.norm());
  if (!(extent > 0) || !std::isfinite(extent)) extent = 1;
  const double reach = 3 * extent;
  const Matrix4<double> eye = Matrix4<double>::Identity();
  report::Views views;
  views.title = mark.title.empty()
                    ? std::string(check_name(ce.finding.check)) + " (" + ce.implementation + ")"
                    : mark.title;
  views.space = "eye";
  views.data = stem + ".views.dat";
  views.top = stem + ".top";
  views.side = stem + ".side";
  const std::vector<report::Segment> original =
      report::volume_edges(eye, v.projection, v.convention, reach);
  views.sets.push_back({unbounded ? "original view volume (M; unbounded: cut at 3x the rest)"
                                  : "original view volume (M)",
                        "lines lc rgb 'black' lw 2",
                        original,
                        {}});
  views.sets.push_back({"plane C (where it cuts M's volume)",
                        "lines lc rgb '#1f77b4' lw 2 dt 3",
                        plane_cut(original, v.plane),
                        {}});
  views.sets.push_back({v.expected
                            ? "oblique view volume, expected (exact M')"
                            : "oblique view volume, expected: none (the input has no answer)",
                        "lines lc rgb '#2ca02c' lw 2",
                        v.expected ? report::volume_edges(eye, *v.expected, v.convention, reach)
                                   : std::vector<report::Segment>{},
                        {}});
  views.sets.push_back({v.answer ? "oblique view volume, answered (the implementation's M')"
                                 : "oblique view volume, answered: none",
                        "lines lc rgb '#d62728' lw 1.5 dt 2",
                        v.answer ? report::volume_edges(eye, *v.answer, v.convention, reach)
                                 : std::vector<report::Segment>{},
                        {}});
  views.sets.push_back({q ? "far corner Q" : "far corner Q: none drawn (none, or at infinity)",
                        "points pt 6 ps 2 lw 2 lc rgb '#9467bd'",
                        {},
                        q ? std::vector<Eigen::Vector3d>{*q} : std::vector<Eigen::Vector3d>{}});
  std::vector<Eigen::Vector3d> marked = mark.more;
  if (mark.point) marked.insert(marked.begin(), *mark.point);
  views.sets.push_back({mark.legend,
                        marked.empty() ? "points ps 0" : "points pt 2 ps 3 lw 3 lc rgb '#e377c2'",
                        {},
                        marked});
  for (std::size_t i = 0; i < 4; ++i) {  // a volume (or cut) that has no edge to draw says so
    report::Dataset& d = views.sets[i];
    if (d.segments.empty() && d.title.find(": none") == std::string::npos)
      d.title += ": nothing to draw";
  }
  // One legend entry a line, its sample first: the entries are long.
  views.key = "outside right top vertical Left reverse samplen 1.5 spacing 0.9 font ',9'";
  // The box: the eye, M's volume, Q and the marked point, with a margin.
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  auto include = [&](const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const report::Segment& e : original) {
    include(e.a);
    include(e.b);
  }
  if (q) include(*q);
  for (const Eigen::Vector3d& p : marked) include(p);
  // (A volume that could not be drawn, a singular M, leaves the box empty: then a unit margin.)
  const double size = (hi - lo).maxCoeff();
  const double margin = size > 0 && std::isfinite(size) ? 0.1 * size : 1.0;
  views.lo = lo.array() - margin;
  views.hi = hi.array() + margin;
  return views;
}

}  // namespace

namespace {

/// The report's "diagnosis": the causes by name, the counts behind them and the evidence.
nlohmann::json diagnosis_object(const Diagnosis& d) {
  nlohmann::json j;
  j["causes"] = nlohmann::json::array();
  for (const auto& cause : d.causes) {
    nlohmann::json names = nlohmann::json::array();
    for (Mistake m : cause) names.push_back(std::string(mistake_entry(m).name));
    j["causes"].push_back(names);
  }
  if (d.numerical) {
    j["numerical"] = {{"route", std::string(numerical_route_entry(d.numerical->route).name)},
                      {"non_finite", d.numerical->non_finite},
                      {"relative_error", d.numerical->relative_error},
                      {"bits_lost", d.numerical->bits_lost},
                      {"precision", d.numerical->precision}};
  }
  if (d.transposed_layout) j["transposed_layout"] = true;
  j["line"] = likely_cause_line(d);
  j["seen"] = d.seen;
  j["wrong"] = d.wrong;
  j["probed"] = d.probed;
  j["decided"] = d.decided;
  j["wrong_where_it_differs"] = d.wrong_where_it_differs;
  j["right_where_it_agrees"] = d.right_where_it_agrees;
  nlohmann::json differences = nlohmann::json::array();
  for (const ChoiceDifference& c : d.differences) differences.push_back(choice_text(c));
  j["differences"] = differences;
  auto row = [](const std::optional<std::array<double, 4>>& r) {
    if (!r) return nlohmann::json(nullptr);
    nlohmann::json out = nlohmann::json::array();
    for (double v : *r) out.push_back(protocol::format_number(v));
    return out;
  };
  j["row"] = d.row + 1;
  j["answered"] = {{"status", status_code(d.answered)}, {"row", row(d.answered_row)}};
  j["mistaken"] = {{"status", status_code(d.mistaken)}, {"row", row(d.mistaken_row)}};
  j["right"] = {{"status", status_code(d.right)}, {"row", row(d.right_row)}};
  return j;
}

}  // namespace

std::string diagnosis_json(const Diagnosis& diagnosis) {
  return diagnosis_object(diagnosis).dump();
}

namespace {

/// Stages the case's pictures (top and side views, rendered by gnuplot in the staging folder when
/// it is there) in `files` under `stem`; returns the "## Pictures" section and sets `pictures`
/// (the JSON's field).
/// Which of a case's two views ("top", "side") gnuplot rendered from the staged `views`, and why
/// the others were not.
struct Rendered {
  std::vector<std::string> views;
  std::string why;
  bool has(const char* view) const {
    return std::find(views.begin(), views.end(), view) != views.end();
  }
  /// The Markdown of the pictures: each rendered view, or why not, and the files.
  std::string markdown(const std::string& stem) const {
    std::ostringstream md;
    for (const char* view : {"top", "side"}) {
      if (has(view)) md << "![" << view << " view](" << stem << "." << view << ".png)\n\n";
    }
    if (views.size() != 2) {
      md << (views.empty() ? "The pictures were" : "A picture was") << " not rendered: " << why
         << ".\n\n";
    }
    md << "Data `" << stem << ".views.dat`, scripts `" << stem << ".top.gp` and `" << stem
       << ".side.gp` (in this folder: `gnuplot " << stem << ".top.gp` renders the top view).\n\n";
    return md.str();
  }
};

Rendered render(report::ReportFiles& files, const report::Views& views, const std::string& stem) {
  report::stage_views(files, views);
  Rendered out;
  for (const char* view : {"top", "side"}) {
    std::ostringstream log;
    if (files.plot_staged(stem + "." + view + ".gp", stem + "." + view + ".png", log)) {
      out.views.push_back(view);
    } else if (out.why.empty()) {
      out.why = log.str();
    }
  }
  return out;
}

std::string stage_pictures(report::ReportFiles& files, const Counterexample& ce,
                           const std::string& stem, const Mark& mark, nlohmann::json& pictures,
                           report::Views* shown = nullptr) {
  std::ostringstream md;
  {
    const report::Views views = case_views(ce, stem, mark);
    if (shown) *shown = views;
    const Rendered rendered_views = render(files, views, stem);
    const bool rendered = rendered_views.views.size() == 2;
    auto has = [&](const char* view) { return rendered_views.has(view); };
    md << "## Pictures\n\nThe case in eye space (the space C is given in): a top view (x, z) and "
          "a side view (z, y) of M's view volume (black), C where it cuts it (blue, dotted), the "
          "expected oblique view volume (green), the implementation's (red, dashed), the far "
          "corner Q (circle) and the marked point (cross).\n\nMarked: "
       << mark.what << ".\n\n"
       << rendered_views.markdown(stem);
    pictures = nlohmann::json::object();
    pictures["rendered"] = rendered;
    pictures["error"] = rendered_views.why;
    for (const char* view : {"top", "side"}) {
      pictures[view] = has(view) ? nlohmann::json(stem + "." + view + ".png") : nullptr;
    }
    pictures["data"] = stem + ".views.dat";
    pictures["scripts"] = {stem + ".top.gp", stem + ".side.gp"};
    pictures["marked"] = mark.what;
    pictures["marked_point"] = nullptr;
    if (mark.point) {
      pictures["marked_point"] = {protocol::format_number(mark.point->x()),
                                  protocol::format_number(mark.point->y()),
                                  protocol::format_number(mark.point->z())};
    }
    pictures["clipped_point"] = nullptr;
    if (ce.views.clipped) {
      nlohmann::json p = nlohmann::json::array();
      for (int i = 0; i < 4; ++i) p.push_back(protocol::format_number((*ce.views.clipped)(i)));
      pictures["clipped_point"] = p;
    }
  }
  return md.str();
}

}  // namespace

std::string consumer_report_markdown(const std::string& consumer, const ConsumerFinding& finding,
                                     const std::string& inputs) {
  const std::string name(consumer_check_name(finding.check));
  return "# Counterexample: " + name + "\n\n`" + consumer + "` violates **" + name +
         "**.\n\n## What was found\n\n" + describe(finding) + "\n\n" +
         mistakes::consumer_cause_markdown(finding.likely_cause, finding.answers_show) +
         "## The inputs\n\n" + inputs +
         "\nNumbers print so that they read back to the same value; matrices are row by row, "
         "planes keep P . x >= 0. The properties and their bounds: docs/consumers.md.\n";
}

template <class T>
std::string stage_consumer_pictures(report::ReportFiles& files, const std::string& stem,
                                    const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                                    const ConsumerFinding& finding, const std::string& consumer) {
  Counterexample ce = make_counterexample(m, c, convention);
  ce.implementation = "the core's M', given to " + consumer;
  const Matrix4<T> oblique = apply<T>(m, c, convention).projection;
  set_result(ce, oblique);
  set_views(ce, Problem<T>(m, c, convention), &oblique);
  Mark mark;
  mark.title = std::string(consumer_check_name(finding.check)) + " (" + consumer + ")";
  mark.what = finding.points_what.empty() ? std::string("nothing") : finding.points_what;
  mark.legend = mark.what;
  mark.more = finding.points;
  nlohmann::json unused;
  return stage_pictures(files, ce, stem, mark, unused);
}

#define OBLIQUE_CONSUMER_PICTURES(T)                                                              \
  template std::string stage_consumer_pictures<T>(                                                \
      report::ReportFiles&, const std::string&, const Matrix4<T>&, const Vector4<T>&, Convention, \
      const ConsumerFinding&, const std::string&);
OBLIQUE_CONSUMER_PICTURES(float)
OBLIQUE_CONSUMER_PICTURES(double)
OBLIQUE_CONSUMER_PICTURES(long double)
#undef OBLIQUE_CONSUMER_PICTURES

std::string stage_drawn_pictures(report::ReportFiles& files, const std::string& stem,
                                 const ConsumerFinding& finding, const std::string& consumer) {
  if (finding.drawn.empty()) return "";
  static const char* const kColours[] = {"black",   "#2ca02c", "#d62728",
                                         "#1f77b4", "#9467bd", "#e377c2"};
  report::Views views;
  views.title = std::string(consumer_check_name(finding.check)) + " (" + consumer + ")";
  views.space = finding.drawn_space;
  views.data = stem + ".views.dat";
  views.top = stem + ".top";
  views.side = stem + ".side";
  views.key = "below left Left reverse maxcols 1";
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  auto include = [&](const Eigen::Vector3d& p) {
    if (!p.allFinite()) return;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  std::size_t k = 0;
  for (const ConsumerFinding::Drawn& d : finding.drawn) {
    const std::string colour = kColours[k++ % (sizeof kColours / sizeof *kColours)];
    report::Dataset lines{
        d.name, "lines lc rgb '" + colour + "' lw 2" + (k == 3 ? " dt 2" : ""), {}, {}};
    for (const auto& [a, b] : d.lines) {
      lines.segments.push_back({a, b});
      include(a);
      include(b);
    }
    for (const Eigen::Vector3d& p : d.points) include(p);
    if (!d.points.empty()) {
      views.sets.push_back({d.lines.empty() ? d.name : d.name + " (its point)",
                            "points pt 6 ps 2 lw 2 lc rgb '" + colour + "'",
                            {},
                            d.points});
    }
    if (!d.lines.empty()) views.sets.push_back(lines);
    if (d.lines.empty() && d.points.empty())
      views.sets.push_back({d.name + ": nothing to draw", "points ps 0", {}, {}});
  }
  if (!(lo.array() <= hi.array()).all()) lo = hi = Eigen::Vector3d::Zero();
  const double size = (hi - lo).maxCoeff();
  const double margin = size > 0 && std::isfinite(size) ? 0.1 * size : 1.0;
  views.lo = lo.array() - margin;
  views.hi = hi.array() + margin;
  const Rendered rendered = render(files, views, stem);
  return "## Pictures\n\nIn " + finding.drawn_space +
         ": a top view (x, z) and a side view (z, y) of what the finding is about, each in its "
         "colour as the legend names it.\n\n" +
         rendered.markdown(stem);
}

std::string write_report(const Counterexample& ce, const ReportContext& context) {
  std::string stem = context.stem.empty()
                         ? (context.report_key.empty() ? context.test_id : context.report_key) +
                               "." + ce.implementation
                         : context.stem;
  for (char& ch : stem) {
    if (ch == '/' || ch == ' ') ch = '_';
  }
  report::ReportFiles files(context.directory);
  if (context.keep_existing) stem = files.reserve_stem(stem, {".md", ".json", ".views.dat"});
  const std::string md_path = context.directory + "/" + stem + ".md";
  const std::string rc_params = "RC_PARAMS=\"seed=" + std::to_string(context.seed) +
                                " max_success=" + std::to_string(context.max_success) + "\"";
  const std::string impl_env =
      ce.implementation.rfind("core_", 0) == 0 ? "" : "OBLIQUE_IMPL=" + ce.implementation + " ";
  const std::string replay_suite = !context.replay_run.empty()
                                       ? context.replay_run
                                       : impl_env + rc_params + " " + context.binary +
                                             " --gtest_filter='" + context.test_id + "'";
  const std::string method = core_method_of(ce.implementation);
  const std::string replay_case = !context.replay_case.empty() ? context.replay_case
                                  : method.empty()             ? ""
                                                   : "echo '" + ce.request + "' | " + context.cli +
                                                         " apply --method " + method +
                                                         " --precision " + ce.scalar;

  std::ostringstream md;
  const Finding& f = ce.finding;
  md << "# Counterexample: " << check_name(f.check) << " (" << ce.implementation << ", "
     << ce.scalar << ")\n\n";
  md << "**Relation:** " << relation_text(f) << "\n\n";
  if (f.shows == Shows::statuses) {  // what the input allows and what came
    md << "| | status |\n|---|---|\n| expected | `" << bound_text(f) << "` |\n| got | `"
       << residual_text(f) << "` |\n";
  } else {
    md << "| side | value |\n|---|---|\n| residual | `" << residual_text(f) << "` |\n| bound | `"
       << bound_text(f) << "` |\n";
    if (f.ratio) md << "| residual / bound | `" << protocol::format_number(*f.ratio) << "` |\n";
  }
  md << "\nFamily `" << ce.family << "`, convention `" << ce.convention << "`, place `" << ce.place
     << "`.\n\n";
  if (ce.diagnosis) md << likely_cause_markdown(*ce.diagnosis);
  md << "## Input\n\nProjection M (shortest round-trip decimals):\n\n"
     << matrix_table(ce.projection_decimal) << "\nProjection M (hex, exact):\n\n"
     << matrix_table(ce.projection_hex) << "\nPlane C: `(" << ce.plane_decimal[0] << ", "
     << ce.plane_decimal[1] << ", " << ce.plane_decimal[2] << ", " << ce.plane_decimal[3]
     << ")` = `(" << ce.plane_hex[0] << ", " << ce.plane_hex[1] << ", " << ce.plane_hex[2] << ", "
     << ce.plane_hex[3] << ")`\n\n";
  if (!ce.result_decimal.empty())
    md << "## Result M'\n\n" << matrix_table(ce.result_decimal) << "\n";
  if (!ce.notes.empty()) {
    md << "## Notes\n\n| | |\n|---|---|\n";
    for (const auto& [key, value] : ce.notes) {
      std::string cell = value;
      for (char& ch : cell) {
        if (ch == '\n' || ch == '|') ch = ch == '|' ? '/' : ' ';
      }
      md << "| " << key << " | `" << cell << "` |\n";
    }
    md << "\n";
  }
  // The pictures: staged with the rest, rendered in the staging folder (gnuplot missing or
  // failing leaves the data and scripts, and says so).
  nlohmann::json pictures = nullptr;
  report::Views views;
  std::vector<report::StagedPicture> staged;
  report::RenderSummary render_summary;
  bool render_tried = false;
  if (ce.views.set) {
    md << "Interactive: `" << stem << ".html` (the case in 3D, this report beside it).\n\n";
    if (context.draw_case && ce.views.expected && ce.views.answer) {
      render_tried = true;
      md << context.draw_case(files, stem, ce.views, staged, render_summary);
    }
    md << stage_pictures(files, ce, stem, mark_of(ce), pictures, &views);
  }
  md << "## Replay\n\nThe whole run"
     << (context.seed ? ", shrinking included (seed " + std::to_string(context.seed) + ")" : "")
     << ":\n\n```sh\n"
     << replay_suite << "\n```\n\n";
  if (!replay_case.empty()) md << "This one case alone:\n\n```sh\n" << replay_case << "\n```\n\n";
  if (!context.contract.empty()) {
    md << "## Contract\n\nWhat the run held the implementation to, for a `--contract` file or a "
          "test (`oblique::read_contract(R\"(...)\").value()`):\n\n```json\n"
       << context.contract << "\n```\n\n";
  }
  // The build of the judge (oblique's libraries), not of the code judged.
  md << "Judged by oblique built with " << OBLIQUE_COMPILER << ", flags `" << OBLIQUE_CXX_FLAGS
     << "` (oblique's build, not the code under test's).\n";

  nlohmann::json j;
  j["property"] = std::string(check_name(f.check));
  j["relation"] = relation_text(f);
  j["residual"] = residual_text(f);
  j["bound"] = bound_text(f);
  j["ratio"] = f.ratio && std::isfinite(*f.ratio) ? nlohmann::json(*f.ratio) : nullptr;
  j["numbers"] = finding_json_numbers(f);
  j["diagnosis"] = ce.diagnosis ? diagnosis_object(*ce.diagnosis) : nlohmann::json(nullptr);
  j["implementation"] = ce.implementation;
  j["precision"] = ce.scalar;
  j["family"] = ce.family;
  j["convention"] = ce.convention;
  j["place"] = ce.place;
  j["projection"] = ce.projection_hex;
  j["plane"] = ce.plane_hex;
  j["projection_decimal"] = ce.projection_decimal;
  j["plane_decimal"] = ce.plane_decimal;
  j["result"] = ce.result_decimal;
  j["status_expected"] = f.shows == Shows::statuses ? bound_text(f) : "";
  j["status_answered"] = f.shows == Shows::statuses ? residual_text(f) : "";
  j["seed"] = context.seed;
  j["replay"] = replay_suite;
  j["replay_case"] = replay_case;
  if (!context.contract.empty())
    j["contract"] = nlohmann::json::parse(context.contract, nullptr, /*allow_exceptions=*/false);
  j["request"] = ce.request;
  j["request_decimal"] = ce.request_decimal;
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& [key, value] : ce.notes) notes[key] = value;
  j["notes"] = notes;
  j["compiler"] = OBLIQUE_COMPILER;
  j["flags"] = OBLIQUE_CXX_FLAGS;
  j["pictures"] = pictures;
  if (ce.views.set) {
    j["html"] = stem + ".html";
    nlohmann::json renders = nlohmann::json::array();
    for (const report::StagedPicture& p : staged) renders.push_back(p.file);
    j["renders"] = renders;
  }
  j["render"] = nullptr;
  if (render_tried) {
    j["render"] = {{"drawn", render_summary.drawn},
                   {"differing_pixels", render_summary.differing_pixels},
                   {"marks", render_summary.marks},
                   {"marks_with_difference", render_summary.marks_with_difference},
                   {"why", render_summary.why}};
  }
  // Text from other programs may be any bytes: invalid UTF-8 becomes U+FFFD, never an abort.
  files.open(stem + ".json") << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                             << "\n";
  files.open(stem + ".md") << md.str();
  if (ce.views.set) files.open(stem + ".html") << report::views_html(views, md.str(), staged);
  std::ostringstream log;
  if (!files.commit(log)) {
    std::string why = log.str();
    while (!why.empty() && why.back() == '\n') why.pop_back();
    throw std::runtime_error(why);
  }
  // A picture of this name not rendered now is an earlier case's (the report it went with is
  // replaced): it would show the wrong case beside this report.
  for (const char* view : {"top", "side"}) {
    if (!pictures.is_object() || pictures[view].is_null()) {
      std::error_code ignored;
      std::filesystem::remove(context.directory + "/" + stem + "." + view + ".png", ignored);
    }
  }
  for (const char* render : {".render.png", ".depth.png"}) {
    if (std::none_of(staged.begin(), staged.end(),
                     [&](const report::StagedPicture& p) { return p.file == stem + render; })) {
      std::error_code ignored;
      std::filesystem::remove(context.directory + "/" + stem + render, ignored);
    }
  }
  return md_path;
}

}  // namespace oblique::report
