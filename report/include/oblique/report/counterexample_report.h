// Counterexample reports: a Markdown page a person can read and a JSON sidecar a tool (and the
// regression replay) can read, each naming the one command that replays the case.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/oracle/consumers.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"
#include "oblique/projection.h"
#include "oblique/report/picture.h"

namespace oblique::report {

class ReportFiles;
using oracle::ConsumerFinding;
using oracle::Finding;
using oracle::Problem;

/// The case in eye space (the space C is given in), for the report's top view (x, z) and side
/// view (z, y): set by set_views(), drawn by write_report().
struct CaseViews {
  bool set = false;
  Convention convention = Convention::gl;
  Matrix4<double> projection = Matrix4<double>::Identity();  ///< M
  Vector4<double> plane = Vector4<double>::Zero();           ///< C
  std::optional<Matrix4<double>> expected;    ///< the exact M', rounded (an input with an answer)
  std::optional<Matrix4<double>> answer;      ///< the implementation's M' (finite answers only)
  std::optional<Vector4<double>> far_corner;  ///< Q, homogeneous (w = 0: a direction)
  /// A vertex of M's view volume on C's positive side that the answer's far plane cuts away
  /// (no_clipping's worst vertex, whatever the finding's kind), homogeneous.
  std::optional<Vector4<double>> clipped;
};

struct Counterexample {
  Finding finding;             ///< what the answer violates (its kind names the property)
  std::string implementation;  ///< e.g. core_general, listing_5_1
  std::string scalar;          ///< float, double, long_double (protocol::scalar_name)
  std::string family, convention, place;
  std::vector<std::string> projection_decimal, projection_hex;  ///< 16, row-major
  std::vector<std::string> plane_decimal, plane_hex;            ///< 4
  std::string request, request_decimal;     ///< the `oblique apply` request: hex strings, numbers
  std::vector<std::string> result_decimal;  ///< 16, or empty if refused
  /// Further facts for the reader (the exact answer, what an external program printed...),
  /// shown as a table in the Markdown and as an object in the JSON.
  std::vector<std::pair<std::string, std::string>> notes;
  CaseViews views;  ///< the pictures' case (none unless set_views() was called)
  /// Which known mistake explains the answer (diagnose()), for the "Likely cause" section.
  std::optional<mistakes::Diagnosis> diagnosis;
};

/// The input's part of a counterexample: the numbers (shortest decimal and exact hex), the
/// request lines (protocol::request_line), the scalar and the convention.
template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);

/// Fills result_decimal from an answered M'.
template <class T>
void set_result(Counterexample& ce, const Matrix4<T>& result);

/// Fills ce.views from the exact Problem of the case and the implementation's answer M' (null
/// when it gave none): the expected M', the far corner Q and, when the answer clips the
/// original view volume on C's side, the vertex it clips.
template <class T>
void set_views(Counterexample& ce, const Problem<T>& problem, const Matrix4<T>* answer);

/// A diagnosis as the report's JSON has it ("diagnosis"): its causes by name, the counts and the
/// evidence, as JSON text (for other writers: `oblique check --impl --json`).
std::string diagnosis_json(const mistakes::Diagnosis& diagnosis);

/// Where the report goes and how it is replayed.
struct ReportContext {
  std::string directory;  ///< reports folder
  std::string test_id;    ///< "Suite.Name"
  /// What the property suite's reports are named by: "executable.Suite.Name" (two test
  /// executables with the same test names keep their reports apart); empty: test_id.
  std::string report_key;
  std::uint64_t seed = 0;  ///< RapidCheck's seed for this run
  int max_success = 100;   ///< RapidCheck's max_success for this run
  std::string binary;      ///< the test executable
  std::string cli;         ///< the oblique executable
  // Set by tools other than the property suite (oblique verify):
  std::string stem;         ///< the report's file name without extension (default: test id.impl)
  std::string replay_run;   ///< the command that repeats the whole run, instead of the suite's
  std::string replay_case;  ///< the command that replays this one case, instead of `oblique apply`
  /// The contract the run judged by (oblique::contract_json()), printed for pasting.
  std::string contract;
  /// Never replace an earlier report: a taken stem gets "-2", "-3", ... (oblique verify).
  bool keep_existing = false;
  /// Draws what an engine would draw through the correct M' and the answer (a case with both),
  /// staging its pictures in the report's files under STEM and adding them to `staged`; returns
  /// the Markdown section. Set by the ways in that link the rasterizer
  /// (raster::stage_case_renders(), oblique/raster/case_scene.h); empty: no such section.
  std::function<std::string(ReportFiles& files, const std::string& stem, const CaseViews& views,
                            std::vector<StagedPicture>& staged, RenderSummary& summary)>
      draw_case;
};

/// Writes NAME.md and NAME.json into the reports folder and, when ce.views is set, the case's
/// top and side views: NAME.views.dat, NAME.top.gp, NAME.side.gp and (with gnuplot)
/// NAME.top.png, NAME.side.png; the Markdown links the pictures, or says why they were not
/// rendered; NAME.html, the case in 3D with the report beside it (oblique/report/html_page.h);
/// and, with context.draw_case, what an engine would draw (NAME.render.png, NAME.depth.png). Every
/// file is staged and moved into place only when all were written in full (report::ReportFiles), so
/// a failed write leaves an earlier report as it was. Returns the Markdown path; throws
/// std::runtime_error when it cannot write the report.
std::string write_report(const Counterexample& ce, const ReportContext& context);

/// A consumer finding's report as every tool writes it (oblique::testing, `oblique verify`), up
/// to its pictures and replay: the title, what was found and the inputs (`inputs`, a Markdown
/// list).
std::string consumer_report_markdown(const std::string& consumer, const ConsumerFinding& finding,
                                     const std::string& inputs);

/// The pictures of a consumer finding about an oblique matrix's case (m, c, convention: M's
/// volume, C and the core's M', the answer the consumer was given), as write_report() draws a
/// case, with the finding's points marked; staged (and rendered, with gnuplot) in `files` under
/// `stem`. Returns the report's "## Pictures" section.
/// The pictures of a consumer finding about a pass camera or its plane (finding.drawn, in its
/// space: the cameras, the planes, the points); "" when it has nothing drawn.
std::string stage_drawn_pictures(ReportFiles& files, const std::string& stem,
                                 const ConsumerFinding& finding, const std::string& consumer);

template <class T>
std::string stage_consumer_pictures(ReportFiles& files, const std::string& stem,
                                    const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                                    const ConsumerFinding& finding, const std::string& consumer);

}  // namespace oblique::report
