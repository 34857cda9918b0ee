// The reports' measurements against what can be derived by hand: Figure 5's surface from a
// closed form of Eq. 19 for this frustum, the identity of the conventions' reachable depth, the
// depth bits of planes parallel to the near plane, the oracle's rounding, the error-against-time
// front.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "oblique/oracle/exact.h"
#include "oblique/report/accuracy_report.h"
#include "oblique/report/depth_report.h"
#include "oblique/report/report_files.h"

namespace oblique::report {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(DepthReport, figure5MatchesEq19InClosedFormForThisFrustum) {
  // 90 degree square frustum, n = 1, f = 100: the far corner on C's side is Q = (1, y, -1, 1/f)
  // (Q_z = -1 scaling), so C . Q = sin t + cos t - d / f and Eq. 19 along -z is
  // z_max = 2 cos t / (sin t + cos t - d / f) - 1.
  DepthOptions options;
  const DepthReport report = measure_depth(options);
  ASSERT_FALSE(report.figure5.empty());
  int checked = 0;
  for (const Figure5Point& p : report.figure5) {
    const double t = p.angle_degrees * kPi / 180;
    const double dot = std::sin(t) + std::cos(t) - p.distance / options.far_distance;
    if (!(dot > 1e-9)) continue;
    ASSERT_TRUE(p.answered) << p.angle_degrees << " " << p.distance;
    const double expected = 2 * std::cos(t) / dot - 1;
    EXPECT_NEAR(p.z_max_eq19, expected, 1e-12 * std::max(1.0, std::abs(expected)))
        << p.angle_degrees << " degrees, d = " << p.distance;
    EXPECT_NEAR(p.z_max_matrix, expected, 1e-12 * std::max(1.0, std::abs(expected)));
    const double fraction = std::min(1.0, (expected + 1) / 2);
    for (double r : p.reachable) EXPECT_NEAR(r, fraction, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(report.eq19_vs_matrix_max_gap, 1e-12);
  EXPECT_LT(report.convention_max_gap, 1e-12);
}

TEST(DepthReport, planesParallelToTheNearPlaneLoseNoFixedPointDepthAndTiltedOnesDo) {
  const DepthReport report = measure_depth(DepthOptions{});
  int parallel = 0, tilted = 0;
  for (const DepthBitsRow& r : report.bits) {
    EXPECT_DOUBLE_EQ(r.fixed24_bits_original, 24.0);
    if (r.direction != "axis") continue;
    const double lost = r.fixed24_bits_original - r.fixed24_bits_oblique;
    if (r.angle_degrees == 0) {
      // C parallel to the near plane: F is the original far plane, the axis spans the range.
      EXPECT_NEAR(lost, 0.0, 1e-6) << r.convention << " d = " << r.distance;
      ++parallel;
    } else {
      EXPECT_GT(lost, 0.01) << r.angle_degrees << " " << r.convention;
      ++tilted;
    }
  }
  EXPECT_GT(parallel, 0);
  EXPECT_GT(tilted, 0);
}

TEST(AccuracyReport, oracleRoundsToNearestEven) {
  // 1 + 2^-53 is halfway between 1 and 1 + 2^-52: ties go to the even significand, 1.
  const oracle::exact::Rational tie = oracle::exact::Rational(1) + oracle::exact::power_of_two(-53);
  EXPECT_EQ(oracle::exact::round_to<double>(tie), 1.0);
  EXPECT_EQ(oracle::exact::round_to<double>(tie + oracle::exact::power_of_two(-100)),
            1.0 + std::ldexp(1.0, -52));
  EXPECT_EQ(oracle::exact::round_to<double>(oracle::exact::Rational(1, 3)), 1.0 / 3.0);
  EXPECT_EQ(oracle::exact::round_to<float>(oracle::exact::Rational(1, 3)), 1.0f / 3.0f);
  // Subnormals and overflow.
  EXPECT_EQ(oracle::exact::round_to<double>(oracle::exact::power_of_two(-1074) * 3 / 4),
            std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(oracle::exact::round_to<double>(oracle::exact::power_of_two(-1076)), 0.0);
  EXPECT_TRUE(std::isinf(oracle::exact::round_to<float>(oracle::exact::power_of_two(128))));
  EXPECT_EQ(oracle::exact::round_to<long double>(oracle::exact::Rational(1) +
                                                 oracle::exact::power_of_two(-63)),
            1.0L + std::ldexp(1.0L, -63));
  EXPECT_EQ(oracle::exact::ulp_distance(1.0 + std::ldexp(1.0, -51), oracle::exact::Rational(1)),
            2.0);
}

TEST(AccuracyReport, frontKeepsOnlyNonDominatedPairs) {
  AccuracyReport report;
  auto row = [](const char* method, double ulps, double ns) {
    AccuracyRow r;
    r.regime = "typical";
    r.scalar = "double";
    r.method = method;
    r.answered = 1;
    r.max_ulps = ulps;
    r.ns_per_call = ns;
    return r;
  };
  report.rows = {row("fast", 100, 10), row("slow_and_bad", 200, 50), row("exact", 0, 40)};
  const auto points = overall_points(report);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_TRUE((points.at({"fast", "double"}).on_front));
  EXPECT_TRUE((points.at({"exact", "double"}).on_front));
  EXPECT_FALSE((points.at({"slow_and_bad", "double"}).on_front));
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A report either replaces its files whole or leaves the folder as it was: a folder that cannot
// be made (under a regular file) writes nothing and says so; a complete run replaces the earlier
// files and leaves no staging folder behind.
TEST(ReportFiles, aRunThatCannotWriteLeavesTheFolderAsItWas) {
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / "oblique_report_files_test";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  std::ofstream(root / "plain_file") << "not a folder";
  DepthOptions options;
  options.out_dir = root / "plain_file" / "report";
  const DepthReport report = measure_depth(options);
  std::ostringstream log;
  EXPECT_FALSE(write_depth_report(report, options, log));
  EXPECT_NE(log.str().find("nothing written"), std::string::npos) << log.str();
  EXPECT_EQ(read_file(root / "plain_file"), "not a folder");

  options.out_dir = root / "report";
  std::filesystem::create_directories(options.out_dir);
  std::ofstream(options.out_dir / "depth.md") << "an earlier report";
  std::ofstream(options.out_dir / "kept.txt") << "the user's";
  const auto written = write_depth_report(report, options, log);
  ASSERT_TRUE(written) << log.str();
  EXPECT_NE(read_file(options.out_dir / "depth.md"), "an earlier report");
  EXPECT_EQ(read_file(options.out_dir / "kept.txt"), "the user's");
  for (const auto& entry : std::filesystem::directory_iterator(options.out_dir))
    EXPECT_EQ(entry.path().filename().string().rfind(".oblique-staging", 0), std::string::npos)
        << entry.path();
}

// Pictures rendered in the staging folder (the counterexample reports' views) come with the
// commit or not at all: none is in the folder before commit(); one that gnuplot fails on is never
// moved in, and the failure says what gnuplot said; a folder that cannot be made renders nothing.
TEST(ReportFiles, picturesRenderedBeforeTheCommitComeWithItOrNotAtAll) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "gnuplot is not installed (bash scripts/setup.sh installs it)";
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / "oblique_report_files_plot_test";
  std::filesystem::remove_all(root);
  {
    ReportFiles files(root);
    files.open("line.dat") << "0 0\n1 1\n";
    files.open("good.gp") << "set terminal pngcairo\nset output 'good.png'\n"
                             "plot 'line.dat' with lines\n";
    files.open("bad.gp") << "set terminal pngcairo\nset output 'bad.png'\n"
                            "plot no_such_function(x)\n";
    std::ostringstream good_log, bad_log, commit_log;
    EXPECT_TRUE(files.plot_staged("good.gp", "good.png", good_log)) << good_log.str();
    EXPECT_FALSE(std::filesystem::exists(root / "good.png")) << "in place before the commit";
    EXPECT_FALSE(files.plot_staged("bad.gp", "bad.png", bad_log));
    EXPECT_NE(bad_log.str().find("gnuplot failed on bad.gp"), std::string::npos) << bad_log.str();
    EXPECT_NE(bad_log.str().find("no_such_function"), std::string::npos) << bad_log.str();
    ASSERT_TRUE(files.commit(commit_log)) << commit_log.str();
  }
  EXPECT_GT(std::filesystem::file_size(root / "good.png"), 0u);
  EXPECT_TRUE(std::filesystem::exists(root / "bad.gp"));
  EXPECT_FALSE(std::filesystem::exists(root / "bad.png"));
  for (const auto& entry : std::filesystem::directory_iterator(root))
    EXPECT_EQ(entry.path().filename().string().rfind(".oblique-staging", 0), std::string::npos)
        << entry.path();

  std::ofstream(root / "plain_file") << "not a folder";
  ReportFiles nowhere(root / "plain_file" / "report");
  nowhere.open("good.gp") << "plot x\n";
  std::ostringstream log;
  EXPECT_FALSE(nowhere.plot_staged("good.gp", "good.png", log));
  EXPECT_NE(log.str().find("cannot create"), std::string::npos) << log.str();
  EXPECT_FALSE(nowhere.commit(log));
}

TEST(ReportFiles, aHungGnuplotIsStoppedAndThePictureIsNotWritten) {
  // A gnuplot that never ends, first on PATH; the limit set to 1 s.
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / "oblique_report_files_hung_gnuplot_test";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root / "bin");
  std::ofstream(root / "bin" / "gnuplot") << "#!/bin/sh\nexec sleep 1000\n";
  std::filesystem::permissions(root / "bin" / "gnuplot", std::filesystem::perms::owner_all);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", ((root / "bin").string() + ":" + old_path).c_str(), 1);
  ::setenv("OBLIQUE_GNUPLOT_SECONDS", "1", 1);
  std::ostringstream log, commit_log;
  bool rendered = true;
  {
    ReportFiles files(root / "report");
    files.open("line.dat") << "0 0\n1 1\n";
    files.open("view.gp") << "plot 'line.dat'\n";
    rendered = files.plot_staged("view.gp", "view.png", log);
    EXPECT_TRUE(files.commit(commit_log)) << commit_log.str();
  }
  ::setenv("PATH", old_path.c_str(), 1);
  ::unsetenv("OBLIQUE_GNUPLOT_SECONDS");
  EXPECT_FALSE(rendered);
  EXPECT_NE(log.str().find("did not finish within 1 s"), std::string::npos) << log.str();
  EXPECT_TRUE(std::filesystem::exists(root / "report" / "view.gp"));
  EXPECT_FALSE(std::filesystem::exists(root / "report" / "view.png"));
}

// Two reports picking a name in one folder at the same time never share one: the name is held
// (an empty file, create-exclusive) from the moment it is picked; a report that is not committed
// gives it back, and one committed replaces it.
TEST(ReportFiles, aReservedNameIsNeverPickedTwice) {
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / "oblique_report_files_reserve_test";
  std::filesystem::remove_all(root);
  std::ostringstream log;
  {
    ReportFiles first(root), second(root), third(root);
    const std::string a = first.reserve_stem("verify-status", {".md", ".json"});
    const std::string b = second.reserve_stem("verify-status", {".md", ".json"});
    EXPECT_EQ(a, "verify-status");
    EXPECT_EQ(b, "verify-status-2");
    EXPECT_TRUE(std::filesystem::exists(root / "verify-status.md"));
    std::ofstream(root / "verify-status-3.json") << "an earlier report's data";
    EXPECT_EQ(third.reserve_stem("verify-status", {".md", ".json"}), "verify-status-4");
    first.open(a + ".md") << "the first report";
    ASSERT_TRUE(first.commit(log)) << log.str();
    // second and third are not committed: their names are given back.
  }
  EXPECT_EQ(read_file(root / "verify-status.md"), "the first report");
  EXPECT_FALSE(std::filesystem::exists(root / "verify-status-2.md"));
  EXPECT_FALSE(std::filesystem::exists(root / "verify-status-4.md"));
  EXPECT_EQ(read_file(root / "verify-status-3.json"), "an earlier report's data");
}

// A report that owns files by pattern moves an earlier run's leftovers to earlier/ at commit: a
// 3-answer profile does not stand beside worst-4..10.json of the run before.
TEST(ReportFiles, filesOfAnEarlierRunThisOneDidNotWriteAreMovedAside) {
  const std::filesystem::path root =
      std::filesystem::path(::testing::TempDir()) / "oblique_report_files_supersede_test";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  for (int k = 1; k <= 5; ++k)
    std::ofstream(root / ("worst-" + std::to_string(k) + ".json")) << "earlier " << k;
  std::ofstream(root / "notes.txt") << "the user's";
  std::ostringstream log;
  {
    ReportFiles files(root);
    files.supersede("worst-", ".json");
    for (int k = 1; k <= 3; ++k) files.open("worst-" + std::to_string(k) + ".json") << "new " << k;
    ASSERT_TRUE(files.commit(log)) << log.str();
  }
  EXPECT_EQ(read_file(root / "worst-3.json"), "new 3");
  EXPECT_FALSE(std::filesystem::exists(root / "worst-4.json"));
  EXPECT_FALSE(std::filesystem::exists(root / "worst-5.json"));
  EXPECT_EQ(read_file(root / "notes.txt"), "the user's");
  int moved = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root / "earlier")) {
    const std::string name = entry.path().filename().string();
    if (name == "worst-4.json" || name == "worst-5.json") ++moved;
  }
  EXPECT_EQ(moved, 2);
  EXPECT_NE(log.str().find("2 file(s) of an earlier run moved"), std::string::npos) << log.str();
}

// An implementation none of whose answers could be profiled is named, so the report fails.
TEST(AccuracyReport, anImplementationWithNothingProfiledIsNamed) {
  AccuracyReport report;
  AccuracyRow core;
  core.method = "closed_form";
  core.answered = 10;
  AccuracyRow liar;
  liar.method = "liar";
  liar.round_trip = true;
  liar.violating = 7;
  AccuracyRow partly = liar;
  partly.method = "partly";
  partly.answered = 1;
  report.rows = {core, liar, liar, partly};
  const std::vector<std::string> lines = unprofiled_implementations(report);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("liar: no answer profiled (14 violating"), std::string::npos) << lines[0];
}

}  // namespace
}  // namespace oblique::report
