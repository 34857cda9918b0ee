// The counterexample reports' pictures (issue 19): a report of `oblique verify` on an
// implementation that clips, and a report of the property suite, carry a top and a side view of
// the case whose marked point is a point of the original view volume that the answer's volume
// leaves out (checked on the numbers, not on the files' existence); without gnuplot on PATH the
// report is still written, with the data and scripts, and says the pictures were not rendered.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/testing/harness.h"

namespace oblique {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

double number(const Json& value) {
  const std::string text = value.get<std::string>();
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << "not a number: " << text;
  return x;
}

Matrix4<double> matrix_of(const Json& entries) {
  EXPECT_EQ(entries.size(), 16u);
  Matrix4<double> m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = number(entries.at(static_cast<std::size_t>(i)));
  return m;
}

Vector4<double> vector_of(const Json& entries) {
  EXPECT_EQ(entries.size(), 4u);
  Vector4<double> v;
  for (int i = 0; i < 4; ++i) v(i) = number(entries.at(static_cast<std::size_t>(i)));
  return v;
}

Convention convention_of(const std::string& name) {
  for (Convention c : all_conventions) {
    if (convention_name(c) == name) return c;
  }
  ADD_FAILURE() << "unknown convention " << name;
  return Convention::gl;
}

/// The datasets of a views .dat file: "# 'title'" and the rows under it.
struct Dataset {
  std::string title;
  std::vector<Eigen::Vector3d> rows;
};

std::vector<Dataset> read_views(const fs::path& path) {
  std::vector<Dataset> out;
  std::istringstream in(read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# '", 0) == 0) {
      out.push_back({line.substr(3, line.size() - 4), {}});
      continue;
    }
    if (line.empty() || out.empty()) continue;
    std::istringstream row(line);
    std::string x, y, z;
    row >> x >> y >> z;
    out.back().rows.emplace_back(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                                 std::strtod(z.c_str(), nullptr));
  }
  return out;
}

const Dataset* dataset(const std::vector<Dataset>& sets, const std::string& title) {
  for (const Dataset& d : sets) {
    if (d.title == title) return &d;
  }
  return nullptr;
}

/// p (eye space) lies in M's view volume on C's positive side, and outside the volume of the
/// answer M' (rows 1, 2, 4 are M's, so outside means beyond the depth range of M').
void expect_clipped(const Matrix4<double>& m, const Vector4<double>& c,
                    const Matrix4<double>& answer, Convention convention,
                    const Eigen::Vector3d& p) {
  const Vector4<double> h(p.x(), p.y(), p.z(), 1);
  const DepthRange range = clip_depth_range(convention);
  const Vector4<double> before = m * h;
  const double slack = 1e-9 * (m.cwiseAbs() * h.cwiseAbs()).maxCoeff();
  EXPECT_GT(before.w(), 0) << "behind the eye: " << p.transpose();
  EXPECT_LE(std::abs(before.x()), before.w() + slack) << p.transpose();
  EXPECT_LE(std::abs(before.y()), before.w() + slack) << p.transpose();
  EXPECT_GE(before.z(), range.z_low * before.w() - slack) << p.transpose();
  EXPECT_LE(before.z(), range.z_high * before.w() + slack) << p.transpose();
  EXPECT_GE(c.dot(h), -1e-9 * c.cwiseAbs().dot(h.cwiseAbs())) << "on C's cut-away side";
  const Vector4<double> after = answer * h;
  const double answer_slack = 1e-6 * (answer.cwiseAbs() * h.cwiseAbs()).maxCoeff();
  EXPECT_TRUE(after.z() < range.z_low * after.w() - answer_slack ||
              after.z() > range.z_high * after.w() + answer_slack)
      << "the answer keeps " << p.transpose() << ": clip z " << after.z() << ", w " << after.w();
}

/// Checks a report's pictures: the marked clipped point is in the data, is the JSON's, and is a
/// point of M's volume the answer clips. Returns the report's JSON.
Json expect_marked_clipped_point(const fs::path& json_path) {
  const Json j = Json::parse(read_text(json_path));
  const Json& pictures = j.at("pictures");
  EXPECT_TRUE(pictures.is_object()) << j.dump(2);
  const fs::path dir = json_path.parent_path();
  const std::vector<Dataset> sets = read_views(dir / pictures.at("data").get<std::string>());
  const Dataset* original = dataset(sets, "original view volume (M)");
  if (!original)
    original = dataset(sets, "original view volume (M; unbounded: cut at 3x the rest)");
  const Dataset* marked = dataset(sets, "marked: clipped point");
  EXPECT_NE(original, nullptr);
  if (original) {
    EXPECT_GE(original->rows.size(), 24u);  // 12 edges
  }
  EXPECT_NE(marked, nullptr) << "no clipped point in the pictures' data; marked: "
                             << pictures.at("marked");
  if (!marked) return j;
  EXPECT_EQ(marked->rows.size(), 1u);
  if (marked->rows.size() != 1) return j;
  const Eigen::Vector3d p = marked->rows[0];
  // The data's point is the JSON's (both printed round-trip), and the homogeneous clipped point's.
  const Json& point = pictures.at("marked_point");
  EXPECT_EQ(p.x(), number(point.at(0)));
  EXPECT_EQ(p.y(), number(point.at(1)));
  EXPECT_EQ(p.z(), number(point.at(2)));
  const Vector4<double> clipped = vector_of(pictures.at("clipped_point"));
  EXPECT_NEAR(p.x(), clipped.x() / clipped.w(), 1e-12 * (1 + std::abs(p.x())));
  EXPECT_NEAR(p.z(), clipped.z() / clipped.w(), 1e-12 * (1 + std::abs(p.z())));
  expect_clipped(matrix_of(j.at("projection_decimal")), vector_of(j.at("plane_decimal")),
                 matrix_of(j.at("result")), convention_of(j.at("convention")), p);
  // The scripts draw that data file and write the pictures the report names.
  for (const char* view : {"top", "side"}) {
    const std::string stem = json_path.stem().string();
    const std::string script = read_text(dir / (stem + "." + view + ".gp"));
    EXPECT_NE(script.find("'" + stem + ".views.dat'"), std::string::npos) << script;
    EXPECT_NE(script.find("set output '" + stem + "." + view + ".png'"), std::string::npos);
  }
  return j;
}

bool gnuplot_installed() {
  return std::system("command -v gnuplot > /dev/null 2>&1") == 0;
}

int exit_status(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<fs::path> reports_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".json") out.push_back(entry.path());
  }
  return out;
}

std::string verify_command(const fs::path& dir) {
  return std::string(OBLIQUE_CLI) + " verify --impl " + OBLIQUE_EXAMPLE_THAT_CLIPS +
         " --seed 1 --time-limit 20 --quiet --report-dir " + dir.string() + " > " +
         (dir.string() + ".out") + " 2>&1";
}

TEST(VerifyReportViews, marksAPointOfTheOriginalVolumeThatTheAnswerClips) {
  const fs::path dir = ::testing::TempDir() + "oblique_verify_views";
  fs::remove_all(dir);
  ASSERT_EQ(exit_status(verify_command(dir)), 1) << read_text(dir.string() + ".out");
  const std::vector<fs::path> reports = reports_in(dir);
  ASSERT_EQ(reports.size(), 1u);
  const Json j = expect_marked_clipped_point(reports[0]);
  const std::string stem = reports[0].stem().string();
  const std::string markdown = read_text(dir / (stem + ".md"));
  EXPECT_NE(markdown.find("## Pictures"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("Marked: the clipped point"), std::string::npos) << markdown;
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed: the PNGs are not checked";
  EXPECT_TRUE(j.at("pictures").at("rendered").get<bool>()) << j.at("pictures").dump();
  for (const char* view : {"top", "side"}) {
    const fs::path png = dir / (stem + "." + view + ".png");
    EXPECT_TRUE(fs::exists(png) && fs::file_size(png) > 0) << png;
    EXPECT_NE(markdown.find("](" + stem + "." + view + ".png)"), std::string::npos) << markdown;
  }
  // A second run never replaces the first report or its pictures: it gets the stem "-2".
  const std::string first_data = read_text(dir / (stem + ".views.dat"));
  ASSERT_EQ(exit_status(verify_command(dir)), 1) << read_text(dir.string() + ".out");
  EXPECT_EQ(reports_in(dir).size(), 2u);
  EXPECT_EQ(read_text(dir / (stem + ".views.dat")), first_data);
  EXPECT_TRUE(fs::exists(dir / (stem + "-2.top.png")));
  EXPECT_TRUE(fs::exists(dir / (stem + "-2.views.dat")));
}

TEST(VerifyReportViews, withoutGnuplotTheReportIsWrittenAndSaysThePicturesAreNot) {
  const fs::path dir = ::testing::TempDir() + "oblique_verify_views_no_gnuplot";
  const fs::path empty = ::testing::TempDir() + "oblique_empty_path";
  fs::remove_all(dir);
  fs::remove_all(empty);
  fs::create_directories(empty);
  ASSERT_EQ(exit_status("PATH=" + empty.string() + " " + verify_command(dir)), 1)
      << read_text(dir.string() + ".out");
  const std::vector<fs::path> reports = reports_in(dir);
  ASSERT_EQ(reports.size(), 1u);
  const Json j = expect_marked_clipped_point(reports[0]);
  const std::string stem = reports[0].stem().string();
  const Json& pictures = j.at("pictures");
  EXPECT_FALSE(pictures.at("rendered").get<bool>());
  EXPECT_NE(pictures.at("error").get<std::string>().find("gnuplot not found"), std::string::npos)
      << pictures.dump();
  EXPECT_TRUE(pictures.at("top").is_null());
  const std::string markdown = read_text(dir / (stem + ".md"));
  EXPECT_NE(markdown.find("The pictures were not rendered: gnuplot not found"), std::string::npos)
      << markdown;
  // Every picture it links is there (gnuplot's are not linked; the renders need no gnuplot).
  for (std::size_t at = markdown.find("]("); at != std::string::npos;
       at = markdown.find("](", at + 2)) {
    const std::size_t end = markdown.find(')', at);
    const std::string linked = markdown.substr(at + 2, end - at - 2);
    if (linked.size() > 4 && linked.compare(linked.size() - 4, 4, ".png") == 0) {
      EXPECT_TRUE(fs::exists(dir / linked)) << "links a picture that is not there: " << linked;
    }
  }
  EXPECT_EQ(markdown.find(".top.png)"), std::string::npos);
  for (const std::string& name : {stem + ".views.dat", stem + ".top.gp", stem + ".side.gp"})
    EXPECT_TRUE(fs::exists(dir / name) && fs::file_size(dir / name) > 0) << name;
  for (const std::string& name : {stem + ".top.png", stem + ".side.png"})
    EXPECT_FALSE(fs::exists(dir / name)) << name;
  // Nothing staged is left behind.
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().rfind(".oblique-staging", 0), std::string::npos);
}

// The property suite's report: what testing::fail_with records for a wrong answer (the exact
// third row scaled by 5/4, so the far plane passes in front of Q), written by write_report().
TEST(SuiteReportViews, marksThePointTheWrongAnswerClips) {
  cases::Case<double> c;
  c.family = cases::Family::off_axis;
  c.convention = Convention::zero_one;
  c.matrix = frustum<double>(-1, 2, -0.5, 1, 0.5, 50, c.convention);
  c.plane = Vector4<double>(0.2, 0.1, -1, -5);  // through (0, 0, -5), leaning: C_w < 0
  const oracle::Problem<double> problem(c.matrix, c.plane, c.convention);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  Answer<double> wrong;
  wrong.projection = c.matrix;
  const oracle::exact::Vec row3 = problem.exact_row3();
  for (int i = 0; i < 4; ++i) wrong.projection(2, i) = 1.25 * row3[i].get_d();
  const oracle::Judgement judgement = oracle::judge(problem, wrong);
  ASSERT_NE(judgement.violation(), nullptr) << "the wrong answer passes: the test shows nothing";
  oracle::Implementation<double> impl;
  impl.name = "scaled_third_row";
  testing::tally() = testing::Tally{};
  EXPECT_ANY_THROW(testing::fail_with(c, impl, *judgement.violation(), &wrong));
  ASSERT_TRUE(testing::tally().failure.has_value());
  report::ReportContext context;
  context.directory = ::testing::TempDir() + "oblique_suite_views";
  context.test_id = "SuiteReportViews.marksThePointTheWrongAnswerClips";
  fs::remove_all(context.directory);
  const std::string md = report::write_report(*testing::tally().failure, context);
  const fs::path json = fs::path(md).replace_extension(".json");
  const Json j = expect_marked_clipped_point(json);
  EXPECT_EQ(j.at("property"), std::string(check_name(judgement.violation()->check)));
  EXPECT_NE(read_text(md).find("## Pictures"), std::string::npos);
}

// The same report for an answer that clips nothing marks nothing, and says so.
TEST(SuiteReportViews, marksNothingWhenTheAnswerClipsNothing) {
  cases::Case<double> c;
  c.convention = Convention::gl;
  c.matrix = frustum<double>(-1, 1, -1, 1, 1, 100, c.convention);
  c.plane = Vector4<double>(0, 0.3, -1, -4);
  const oracle::Problem<double> problem(c.matrix, c.plane, c.convention);
  ASSERT_EQ(problem.exact_status(), Status::ok);
  Answer<double> wrong;  // row 1 changed: side_rows_unchanged, nothing clipped
  wrong.projection = c.matrix;
  const oracle::exact::Vec row3 = problem.exact_row3();
  for (int i = 0; i < 4; ++i) wrong.projection(2, i) = row3[i].get_d();
  wrong.projection(0, 0) *= 2;
  const oracle::Judgement judgement = oracle::judge(problem, wrong);
  ASSERT_NE(judgement.violation(), nullptr);
  report::Counterexample ce = report::make_counterexample(c.matrix, c.plane, c.convention);
  ce.finding = *judgement.violation();
  ce.implementation = "widened";
  report::set_result(ce, wrong.projection);
  report::set_views(ce, problem, &wrong.projection);
  EXPECT_FALSE(ce.views.clipped.has_value());
  report::ReportContext context;
  context.directory = ::testing::TempDir() + "oblique_suite_views_nothing";
  context.test_id = "SuiteReportViews.marksNothing";
  fs::remove_all(context.directory);
  const std::string md = report::write_report(ce, context);
  const Json j = Json::parse(read_text(fs::path(md).replace_extension(".json")));
  EXPECT_TRUE(j.at("pictures").at("marked_point").is_null());
  EXPECT_NE(j.at("pictures").at("marked").get<std::string>().find("nothing"), std::string::npos);
  const std::vector<Dataset> sets =
      read_views(fs::path(context.directory) / j.at("pictures").at("data").get<std::string>());
  EXPECT_EQ(dataset(sets, "marked: clipped point"), nullptr);
  EXPECT_NE(dataset(sets, "marked: nothing (the answer clips nothing)"), nullptr);
  EXPECT_NE(read_text(md).find("Marked: nothing"), std::string::npos);
}

// The suite replaces a report of the same test and implementation: when the new one's pictures
// cannot be rendered (no gnuplot on PATH), the replaced report's pictures go too (they show
// another case), and the new report says why it has none.
TEST(SuiteReportViews, aReplacedReportTakesItsPicturesAlong) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot is not installed";
  cases::Case<double> c;
  c.matrix = frustum<double>(-1, 1, -1, 1, 1, 100, c.convention);
  c.plane = Vector4<double>(0, 0.3, -1, -4);
  const oracle::Problem<double> problem(c.matrix, c.plane, c.convention);
  report::Counterexample ce = report::make_counterexample(c.matrix, c.plane, c.convention);
  ce.finding.check = oracle::Check::status;
  ce.finding.shows = oracle::Shows::statuses;
  ce.implementation = "refuses";
  report::set_views(ce, problem, static_cast<const Matrix4<double>*>(nullptr));
  report::ReportContext context;
  context.directory = ::testing::TempDir() + "oblique_suite_views_replaced";
  context.test_id = "SuiteReportViews.replaced";
  fs::remove_all(context.directory);
  const fs::path md = report::write_report(ce, context);
  const fs::path top = fs::path(context.directory) / (md.stem().string() + ".top.png");
  ASSERT_TRUE(fs::exists(top));
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  const std::string empty = ::testing::TempDir() + "oblique_empty_path";
  fs::create_directories(empty);
  setenv("PATH", empty.c_str(), 1);
  std::string again;
  try {
    again = report::write_report(ce, context);
  } catch (...) {
  }
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(again, md.string());
  EXPECT_FALSE(fs::exists(top)) << "the replaced report's picture is left beside the new one";
  EXPECT_NE(read_text(md).find("The pictures were not rendered: gnuplot not found"),
            std::string::npos)
      << read_text(md);
}

}  // namespace
}  // namespace oblique
