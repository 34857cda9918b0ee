// oblique::accuracy_profile: an answer's error in ulps of its row against the exact answer, the
// core's methods measured beside it, and the report written all or nothing.
#include "oblique/report/accuracy_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/projection.h"

namespace oblique {
namespace {

struct Case {
  Matrix4<double> m;
  Vector4<double> c;
  Convention convention;
};

Case tilted(Convention convention) {
  return {perspective<double>(0.9, 1.3, 0.1, 100.0, convention),
          Vector4<double>(0.2, -0.9, -0.3, -1.5), convention};
}

TEST(AccuracyProfile, theCoresAccurateAnswerIsWithinAnUlpOfItsRow) {
  for (const Convention convention : all_conventions) {
    const Case k = tilted(convention);
    const oracle::Problem<double> problem(k.m, k.c, convention);
    const auto answer = apply<double>(k.m, k.c, convention, Method::accurate);
    ASSERT_TRUE(answer.ok());
    const report::ProfiledAnswer a = report::profile_answer(problem, answer.projection);
    EXPECT_LE(a.worst_ulps(), 1.0) << convention_name(convention);
    EXPECT_GT(a.kappa, 0.0);
  }
}

TEST(AccuracyProfile, ulpsAreThoseOfTheRowsLargestEntry) {
  const Case k = tilted(Convention::gl);
  const oracle::Problem<double> problem(k.m, k.c, k.convention);
  auto answer = apply<double>(k.m, k.c, k.convention, Method::accurate).projection;
  // Correctly rounded first (the accurate method is within an ulp; make it exact).
  const oracle::exact::Vec row = problem.exact_row3();
  for (int j = 0; j < 4; ++j) answer(2, j) = oracle::exact::round_to<double>(row[j]);
  int largest = 0;
  for (int j = 1; j < 4; ++j)
    if (std::abs(answer(2, j)) > std::abs(answer(2, largest))) largest = j;
  const double ulp =
      std::nextafter(std::abs(answer(2, largest)), INFINITY) - std::abs(answer(2, largest));
  Matrix4<double> moved = answer;
  moved(2, largest) += 3 * std::copysign(ulp, answer(2, largest));
  // The smallest entry moved by the largest entry's ulp: one ulp of the row, many of its own.
  int smallest = largest == 0 ? 1 : 0;
  for (int j = 0; j < 4; ++j)
    if (std::abs(answer(2, j)) < std::abs(answer(2, smallest))) smallest = j;
  moved(2, smallest) += ulp;
  const report::ProfiledAnswer a = report::profile_answer(problem, moved);
  EXPECT_EQ(a.ulps[largest], 3.0);
  EXPECT_EQ(a.ulps[smallest], 1.0);
  EXPECT_DOUBLE_EQ(report::bits_lost(a.worst_ulps()), 2.0);
  moved(2, smallest) = NAN;
  EXPECT_TRUE(std::isinf(report::profile_answer(problem, moved).ulps[smallest]));
}

TEST(AccuracyProfile, theCoresMethodsAreMeasuredOnTheSameCases) {
  std::vector<report::ProfileInput<double>> inputs;
  for (const Convention convention : all_conventions) {
    const Case k = tilted(convention);
    inputs.push_back({k.m, k.c, convention, "perspective", "typical", "{}"});
    // An orthographic case: the closed form does not take it.
    inputs.push_back({orthographic<double>(-2, 2, -1, 1, 0.5, 50, convention),
                      Vector4<double>(0.1, 0.2, -0.9, -3), convention, "orthographic", "typical",
                      "{}"});
  }
  const std::vector<report::Profile> core = report::core_profiles(inputs);
  ASSERT_EQ(core.size(), 3u);
  EXPECT_EQ(core[0].name, "core closed_form");
  EXPECT_EQ(core[0].answers.size(), 3u);
  EXPECT_EQ(core[1].answers.size(), 6u);
  EXPECT_EQ(core[2].answers.size(), 6u);
  for (const report::Profile& p : core) {
    EXPECT_GT(p.ns, 0.0) << p.name;
    EXPECT_EQ(p.timing, report::Timing::in_process);
  }
  for (const report::ProfiledAnswer& a : core[2].answers) EXPECT_LE(a.worst_ulps(), 1.0);
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AccuracyProfile, theReportHasEveryProfileTheWorstAnswersAndKappaInOrder) {
  namespace fs = std::filesystem;
  report::Profile mine;
  mine.name = "mine";
  mine.scalar = "double";
  mine.timing = report::Timing::round_trip;
  mine.ns = 12000;
  for (int k = 0; k < 12; ++k) {
    report::ProfiledAnswer a;
    a.family = k % 2 ? "perspective" : "off_axis";
    a.place = "typical";
    a.kappa = std::pow(10.0, k);  // kappa 1 (below 1e01) and the decades 1e01 to 1e11
    a.ulps[1] = k;
    a.request = "{\"k\": " + std::to_string(k) + "}";
    mine.answers.push_back(a);
  }
  report::Profile core = mine;
  core.name = "core accurate";
  core.core = true;
  core.timing = report::Timing::in_process;
  core.ns = 100;
  report::ProfileReportOptions o;
  o.dir = fs::path(::testing::TempDir()) / "oblique_accuracy_profile_report";
  fs::remove_all(o.dir);
  o.title = "mine (double)";
  o.worst = 3;
  o.replay = [](const report::ProfiledAnswer&, const std::string& json) {
    return "replay " + json;
  };
  std::ostringstream log;
  const auto written = report::write_profile_report({mine, core}, o, log);
  ASSERT_TRUE(written) << log.str();
  const std::string md = read(o.dir / "accuracy.md");
  EXPECT_NE(md.find("| mine | double | 12 |"), std::string::npos) << md;
  EXPECT_NE(md.find("12.0 us a request, round trip over the pipe"), std::string::npos) << md;
  EXPECT_NE(md.find("| core accurate | double | 12 |"), std::string::npos) << md;
  // The worst first: 11 ulps (3.58 bits), with its replay.
  EXPECT_NE(md.find("1. 3.58 bits lost"), std::string::npos) << md;
  EXPECT_NE(md.find("replay " + (o.dir / "worst-1.json").string()), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(o.dir / "worst-3.json"));
  EXPECT_FALSE(fs::exists(o.dir / "worst-4.json"));
  EXPECT_NE(read(o.dir / "worst-1.json").find("{\\\"k\\\": 11}"), std::string::npos);
  // kappa's decades in order: below 1e01 first, then 1e01, 1e02, ..., 1e10 after 1e09.
  const std::size_t low = md.find("| kappa < 1e01 |"), d2 = md.find("| 1e02 <= kappa < 1e03 |"),
                    d10 = md.find("| 1e10 <= kappa < 1e11 |");
  ASSERT_NE(low, std::string::npos) << md;
  EXPECT_LT(low, d2);
  EXPECT_LT(d2, d10);
}

// gnuplot counts no empty block: a profile without answers writes none, and the charts name
// the blocks that were written (before, the next profile's line drew the wrong block).
TEST(AccuracyProfile, aProfileWithoutAnswersShiftsNoOtherLine) {
  namespace fs = std::filesystem;
  report::Profile mine, none, other;
  mine.name = "mine";
  none.name = "none";
  other.name = "other";
  for (report::Profile* p : {&mine, &none, &other}) {
    p->scalar = "double";
    p->timing = report::Timing::in_process;
    p->ns = 10;
  }
  none.ns = NAN;
  report::ProfiledAnswer a;
  a.family = "perspective";
  a.place = "typical";
  a.kappa = 100;
  mine.answers.push_back(a);
  a.ulps[0] = 7;
  other.answers.push_back(a);
  other.ns = 20;
  report::ProfileReportOptions o;
  o.dir = fs::path(::testing::TempDir()) / "oblique_accuracy_profile_empty_block";
  fs::remove_all(o.dir);
  o.title = "mine";
  std::ostringstream log;
  ASSERT_TRUE(report::write_profile_report({mine, none, other}, o, log)) << log.str();
  const std::string stiffness = read(o.dir / "stiffness.gp");
  EXPECT_NE(stiffness.find("index 1 using 1:2 with linespoints pt 7 lw 2 lc rgb '" +
                           std::string(report::chart_colour(2)) + "' title 'other (double)'"),
            std::string::npos)
      << stiffness;
  EXPECT_EQ(stiffness.find("index 2"), std::string::npos) << stiffness;
  EXPECT_EQ(stiffness.find("none"), std::string::npos) << stiffness;
  const std::string chart = read(o.dir / "accuracy.gp");
  EXPECT_NE(chart.find("index 1 using 1:2 with points pt 7 ps 2 lc rgb '" +
                       std::string(report::chart_colour(2)) + "' title 'other (double)'"),
            std::string::npos)
      << chart;
  EXPECT_EQ(chart.find("'none (double)'"), std::string::npos) << chart;
}

TEST(AccuracyProfile, aFolderThatCannotBeWrittenIsSaidAndNothingIsLeft) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(::testing::TempDir()) / "oblique_accuracy_profile_a_file";
  std::ofstream(file) << "not a folder\n";
  report::Profile mine;
  mine.name = "mine";
  mine.scalar = "double";
  report::ProfileReportOptions o;
  o.dir = file / "report";
  std::ostringstream log;
  EXPECT_FALSE(report::write_profile_report({mine}, o, log));
  EXPECT_FALSE(log.str().empty());
  EXPECT_EQ(read(file), "not a folder\n");
}

}  // namespace
}  // namespace oblique
