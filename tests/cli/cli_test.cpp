// End to end: `oblique apply` answers generated requests of every family and convention,
// stiff ones included, with the exact status, rows 1, 2, 4 bit-exact and row 3 within the
// conditioning bound of the exact answer. Also its exit statuses.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "oblique/cases/contract.h"
#include "oblique/cases/generators.h"
#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/protocol/protocol.h"
#include "printers.h"

namespace oblique {
namespace {

struct Case {
  std::string family;
  Convention convention;
  Matrix4<double> m;
  Vector4<double> c;
};

/// Requests the unit tests never saw: random parameters, stiff ranges, random planes through a
/// random point of the view volume.
std::vector<Case> generated_cases(unsigned seed, int count) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(random)); };
  std::vector<Case> out;
  const char* families[] = {"perspective", "off_axis",   "infinite",   "orthographic",
                            "y_flipped",   "jittered",   "rotated",    "general",
                            "x_flipped",   "xy_flipped", "left_handed"};
  constexpr int kFamilies = sizeof families / sizeof families[0];
  for (int i = 0; i < count; ++i) {
    Case k;
    k.family = families[i % kFamilies];
    k.convention = all_conventions[(i / kFamilies) % 3];
    const double n = log_uniform(1e-6, 10), f = n * log_uniform(1.5, 1e12);
    const double top = n * log_uniform(0.05, 3), right = top * log_uniform(0.5, 3);
    const double shift = unit(random) - 0.5;
    if (k.family == "perspective" || k.family == "y_flipped" || k.family == "jittered" ||
        k.family == "rotated" || k.family == "general" || k.family == "x_flipped" ||
        k.family == "xy_flipped" || k.family == "left_handed") {
      k.m = frustum<double>(-right, right, -top, top, n, f, k.convention);
    } else if (k.family == "off_axis") {
      k.m = frustum<double>(-right + shift * right, right + shift * right, -top, top * 0.5, n, f,
                            k.convention);
    } else if (k.family == "infinite") {
      k.m = infinite_frustum<double>(-right, right, -top, top, n, k.convention);
    } else {
      k.m = orthographic<double>(-right, right, -top, top, n, f, k.convention);
    }
    if (k.family == "y_flipped" || k.family == "xy_flipped") k.m.row(1) *= -1;
    if (k.family == "x_flipped" || k.family == "xy_flipped") k.m.row(0) *= -1;
    if (k.family == "left_handed") k.m.col(2) *= -1;  // camera z negated: M43 = +1
    if (k.family == "jittered") k.m.row(0) += (shift / 960) * k.m.row(3);
    if (k.family == "rotated" || k.family == "general") {
      Matrix4<double> r = Matrix4<double>::Identity();
      r.topLeftCorner<3, 3>() =
          Eigen::Quaterniond::UnitRandom().toRotationMatrix();  // uses std::rand: seed below
      if (k.family == "general") {
        r.topLeftCorner<3, 3>() *=
            Eigen::Vector3d(1 + unit(random), 1 + unit(random), 1).asDiagonal();
        r(0, 1) += unit(random) - 0.5;
      }
      k.m = k.m * r;
    }
    // A point inside the view volume, a random normal through it, the camera behind it.
    const DepthRange range = clip_depth_range(k.convention);
    const Vector4<double> clip(2 * unit(random) - 1, 2 * unit(random) - 1,
                               range.z_low + (range.z_high - range.z_low) * unit(random), 1);
    Vector4<double> p = k.m.partialPivLu().solve(clip);
    p /= p.w();
    const Eigen::Vector3d normal = Eigen::Vector3d::Random().normalized();
    k.c << normal, -normal.dot(p.head<3>());
    if (k.c.w() > 0) k.c = -k.c;
    out.push_back(k);
  }
  return out;
}

std::string request_line(const Case& k) {
  return protocol::request_line(k.m, k.c, k.convention);
}

int run_cli(const std::string& arguments, const std::string& input,
            std::vector<std::string>* lines) {
  // One file pair per test: CTest runs tests in parallel.
  const std::string stem = ::testing::TempDir() + "oblique_cli_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string in_path = stem + ".in.jsonl", out_path = stem + ".out.jsonl";
  std::ofstream(in_path) << input;
  const std::string command = std::string(OBLIQUE_CLI) + " " + arguments + " < " + in_path + " > " +
                              out_path + " 2>/dev/null";
  const int raw = std::system(command.c_str());
  std::ifstream out(out_path);
  for (std::string line; std::getline(out, line);) lines->push_back(line);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

/// The matrix of an ok answer.
template <class Answer>
Matrix4<double> answered_matrix(const Answer& answer) {
  Matrix4<double> result;
  for (int j = 0; j < 16; ++j)
    result(j / 4, j % 4) = protocol::parse_number<double>((*answer.projection)[j]).value();
  return result;
}

/// `oblique ARGUMENTS` on one request per case; its answer lines.
std::vector<std::string> answer_lines(const std::vector<Case>& cases,
                                      const std::string& arguments) {
  std::string input;
  for (const Case& k : cases) input += request_line(k) + "\n";
  std::vector<std::string> lines;
  run_cli(arguments, input, &lines);
  return lines;
}

TEST(Cli, answersGeneratedCasesOfEveryFamilyAndConvention) {
  std::srand(7);
  const std::vector<Case> cases = generated_cases(424242, 480);
  const std::vector<std::string> lines = answer_lines(cases, "apply");
  ASSERT_EQ(lines.size(), cases.size());
  int ok = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& k = cases[i];
    const oracle::Problem<double> problem(k.m, k.c, k.convention);
    const auto answer = protocol::parse_answer(lines[i]);
    const std::string what =
        k.family + " " + std::string(convention_name(k.convention)) + ": " + lines[i];
    ASSERT_TRUE(answer) << answer.error() << "\n" << what;
    ASSERT_EQ(answer->status, status_code(problem.exact_status())) << what;
    if (problem.exact_status() != Status::ok) continue;
    ++ok;
    const Matrix4<double> result = answered_matrix(*answer);
    const auto verdicts = problem.check(result);
    for (const auto& v : verdicts.items) {
      EXPECT_TRUE(!v.applies || v.holds)
          << what << "\n"
          << cases::property_name(v.property()) << " " << oracle::residual_text(v) << " vs "
          << oracle::bound_text(v);
    }
    const auto closeness = problem.compare_row3(result);
    EXPECT_TRUE(closeness.within) << what << "\nrow 3 at " << closeness.ratio << " of its bound";
  }
  EXPECT_GT(ok, 300) << "too few generated cases were valid to mean anything";
}

TEST(Cli, accurateMethodAnswersTheCorrectlyRoundedMatrix) {
  const std::vector<Case> cases = generated_cases(171717, 240);
  const std::vector<std::string> lines = answer_lines(cases, "apply --method accurate");
  ASSERT_EQ(lines.size(), cases.size());
  int ok = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& k = cases[i];
    const oracle::Problem<double> problem(k.m, k.c, k.convention);
    const auto answer = protocol::parse_answer(lines[i]);
    ASSERT_TRUE(answer) << answer.error();
    if (problem.exact_status() != Status::ok || answer->status != "ok") continue;
    ++ok;
    const Matrix4<double> result = answered_matrix(*answer);
    // Printed so that it reads back exactly, so the ulp distance is the core's.
    EXPECT_LE(problem.ulps_from_exact(result), oracle::tolerance::kAccurateUlps)
        << k.family << " " << convention_name(k.convention) << ": " << lines[i];
  }
  EXPECT_GT(ok, 150) << "too few generated cases were valid to mean anything";
}

TEST(Cli, exitStatusSaysWhetherEveryLineWasOk) {
  const std::string good =
      "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1,-1]}\n";
  const std::string bad = "{\"projection\": [1]}\n";
  std::vector<std::string> lines;
  EXPECT_EQ(run_cli("apply", good + good, &lines), 0);
  EXPECT_EQ(lines.size(), 2u);
  lines.clear();
  EXPECT_EQ(run_cli("apply --precision float", good + bad + "\n" + good, &lines), 1);
  ASSERT_EQ(lines.size(), 4u);  // one answer per line, the empty one included
  EXPECT_NE(lines[1].find("invalid_input"), std::string::npos);
  EXPECT_NE(lines[2].find("invalid_input"), std::string::npos);
  EXPECT_EQ(run_cli("apply --method fast", good, &lines), 2);
  EXPECT_EQ(run_cli("", good, &lines), 2);
  EXPECT_EQ(run_cli("apply extra-argument", good, &lines), 2);
}

const std::string kGood =
    "{\"projection\": [1,0,0,0,0,1,0,0,0,0,-3,-4,0,0,-1,0], \"plane\": [0,0,-1,-1]}";

/// Runs a shell command; its exit status, and its standard output in `out`.
int shell(const std::string& command, std::string* out) {
  // One file per test: CTest runs tests in parallel (a shared name mixed two tests' outputs).
  const std::string out_path = ::testing::TempDir() + "oblique_cli_shell_" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                               ".txt";
  const int raw = std::system((command + " > " + out_path).c_str());
  std::ifstream file(out_path);
  std::ostringstream text;
  text << file.rdbuf();
  *out = text.str();
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// The help names every family and every place of the generators' tables (stereo_shift was
// once missing from a hand-written list).
TEST(Cli, verifyHelpListsEveryFamilyAndPlace) {
  std::string help;
  ASSERT_EQ(shell(std::string(OBLIQUE_CLI) + " verify --help", &help), 0);
  const auto names_after = [&](const std::string& option) {
    const auto at = help.find(option);
    EXPECT_NE(at, std::string::npos) << option << "\n" << help;
    return at == std::string::npos ? std::string() : help.substr(at, help.find("\n  -", at) - at);
  };
  const std::string families = names_after("--families"), places = names_after("--places");
  const auto listed = [](const std::string& text, std::string_view name) {
    for (auto at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
      const auto is_name = [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
      };
      const bool starts = at == 0 || !is_name(text[at - 1]);
      const bool ends = at + name.size() == text.size() || !is_name(text[at + name.size()]);
      if (starts && ends) return true;
    }
    return false;
  };
  for (auto f : cases::all_families)
    EXPECT_TRUE(listed(families, cases::family_name(f))) << cases::family_name(f) << "\n"
                                                         << families;
  for (auto p : cases::all_places)
    EXPECT_TRUE(listed(places, cases::place_name(p))) << cases::place_name(p) << "\n" << places;
}

// The help of every contract flag lists the names its JSON field takes (the contract's tables).
TEST(Cli, verifyHelpListsEveryNameOfTheContract) {
  std::string help;
  ASSERT_EQ(shell(std::string(OBLIQUE_CLI) + " verify --help", &help), 0);
  for (const auto& names : {names_in(convention_names), names_in(cases::family_names),
                            names_in(cases::place_names), names_in(cases::defect_names),
                            property_names(), refusal_names(), names_in(status_contract_names)}) {
    for (const std::string& name : names)
      EXPECT_NE(help.find(name), std::string::npos) << name << "\n" << help;
  }
}

TEST(Cli, versionNamesTheReleaseAndTheCommit) {
  std::string out;
  ASSERT_EQ(shell(std::string(OBLIQUE_CLI) + " --version", &out), 0);
  EXPECT_EQ(out.rfind("oblique 0.", 0), 0u) << out;
  EXPECT_NE(out.find("(commit "), std::string::npos) << out;
  EXPECT_EQ(out.find("subcommand"), std::string::npos) << out;
}

TEST(Cli, aMistypedSubcommandFlagOrNameGetsTheClosest) {
  const struct {
    std::string arguments, says;
  } cases[] = {
      {"verfy", "unknown subcommand \"verfy\" (did you mean verify?"},
      {"chekc scene.json", "did you mean check?"},
      {"report acuracy", "unknown subcommand \"acuracy\" (did you mean accuracy?"},
      {"verify --impl cat --cses 3", "unknown flag \"--cses\" (did you mean --cases?"},
      {"apply --methd auto", "unknown flag \"--methd\" (did you mean --method?"},
      {"apply --method acurate", "unknown method \"acurate\" (did you mean accurate?"},
      {"apply --convention opengl", "unknown convention \"opengl\" (known: gl, zero_one"},
      {"verify --impl cat --families perspectve",
       "unknown family \"perspectve\" (did you mean perspective?"},
      {"verify --impl cat --statuses answer_only",
       "unknown status contract or refusal \"answer_only\" (did you mean answers_only?"},
      {"verify --impl cat --exclude infinte", "did you mean infinite?"},
      {"verify --impl cat --preset engin",
       "--preset: unknown preset \"engin\" (did you mean engine?"},
      // Files that never end are refused, not read whole.
      {"verify --impl cat --contract /dev/zero", "/dev/zero: larger than"},
      {"verify --impl cat --replay /dev/zero", "/dev/zero: larger than"},
  };
  for (const auto& c : cases) {
    std::string err;
    // Standard error into the captured output: the group's redirection is set up first.
    EXPECT_EQ(
        shell("{ " + std::string(OBLIQUE_CLI) + " " + c.arguments + " < /dev/null 2>&1; }", &err),
        2)
        << c.arguments;
    EXPECT_NE(err.find(c.says), std::string::npos) << c.arguments << " said:\n" << err;
  }
}

/// A fresh folder TempDir()/NAME with the first `count` inputs of the fuzz corpus (in name order)
/// under inputs/.
std::filesystem::path fuzz_inputs(const std::string& name, std::size_t count) {
  namespace fs = std::filesystem;
  const fs::path work = fs::path(::testing::TempDir()) / name;
  fs::remove_all(work);
  fs::create_directories(work / "inputs");
  std::vector<fs::path> corpus;
  for (const auto& entry : fs::directory_iterator(OBLIQUE_FUZZ_CORPUS)) corpus.push_back(entry);
  std::sort(corpus.begin(), corpus.end());
  for (std::size_t i = 0; i < count && i < corpus.size(); ++i)
    fs::copy_file(corpus[i], work / "inputs" / corpus[i].filename());
  return work;
}

/// `oblique fuzz-report` over `work`/inputs through the project's fuzz target running OBLIQUE_IMPL
/// `impl`, reports in `work`/reports: its exit status, its output in `out`.
int fuzz_report_of(const std::string& impl, const std::filesystem::path& work, std::string& out) {
  const std::string target = "env OBLIQUE_IMPL=" + impl + " " + OBLIQUE_FUZZ_REPLAY;
  return shell(std::string(OBLIQUE_CLI) + " fuzz-report --report-dir " +
                   (work / "reports").string() + " --target '" + target + "' " +
                   (work / "inputs").string(),
               &out);
}

// Many failing inputs of a fuzz target, one report per distinct finding: the printed Listing 5.1
// through the project's own target on 40 corpus inputs. Each report's one-case command fails
// again, each property's report has its Likely cause; the index lists every finding.
TEST(Cli, fuzzReportGivesOneReportPerDistinctFinding) {
  namespace fs = std::filesystem;
  const fs::path work = fuzz_inputs("oblique_fuzz_report", 40);
  std::string out;
  ASSERT_EQ(fuzz_report_of("listing_5_1", work, out), 1) << out;
  EXPECT_NE(out.find("oblique fuzz-report: 40 inputs, "), std::string::npos) << out;
  std::vector<std::string> reports;
  for (std::size_t at = out.find(", report "); at != std::string::npos;
       at = out.find(", report ", at + 1))
    reports.push_back(out.substr(at + 9, out.find('\n', at) - at - 9));
  ASSERT_GE(reports.size(), 2u) << out;
  std::set<std::string> distinct(reports.begin(), reports.end());
  EXPECT_EQ(distinct.size(), reports.size()) << out;
  for (const std::string& report : reports) {
    std::ifstream file(report);
    std::ostringstream text;
    text << file.rdbuf();
    const std::string md = text.str();
    // A property's report names the likely cause (from its one case: the target is not asked).
    if (md.rfind("# Counterexample:", 0) == 0) {
      EXPECT_NE(md.find("## Likely cause\n"), std::string::npos) << report << "\n" << md;
    }
    const auto alone = md.find("This one case alone:\n\n```sh\n");
    ASSERT_NE(alone, std::string::npos) << report << "\n" << md;
    const auto start = alone + std::string("This one case alone:\n\n```sh\n").size();
    const std::string replay = md.substr(start, md.find('\n', start) - start);
    std::string ignored;
    EXPECT_NE(shell(replay + " 2>/dev/null", &ignored), 0) << replay;
  }
  EXPECT_TRUE(fs::exists(work / "reports" / "fuzz-index.md"));
}

// One bug, one report: a catalogued mistake through the project's own target on 300 corpus inputs
// breaks several properties on several families and conventions; the inputs whose answers the
// diagnosis names as that mistake are one finding, with what they found listed in its report.
TEST(Cli, fuzzReportGivesOneReportPerLikelyCause) {
  namespace fs = std::filesystem;
  const fs::path work = fuzz_inputs("oblique_fuzz_report_per_cause", 300);
  std::string out;
  ASSERT_EQ(fuzz_report_of("mistake_wrong_face", work, out), 1) << out;
  // Exactly one finding names wrong_face, and it holds inputs of more than one kind.
  int named = 0;
  std::string report;
  for (std::size_t at = out.find("  likely cause "); at != std::string::npos;
       at = out.find("  likely cause ", at + 1)) {
    const std::string line = out.substr(at, out.find('\n', at) - at);
    const std::string cause = line.substr(
        15, line.find(" x mistake_wrong_face") - std::min<std::size_t>(15, line.size()));
    if (cause.find("wrong_face") == std::string::npos) continue;
    ++named;
    report = line.substr(line.find(", report ") + 9);
  }
  ASSERT_EQ(named, 1) << out;
  std::ifstream file(report);
  std::ostringstream text;
  text << file.rdbuf();
  const std::string md = text.str();
  EXPECT_NE(md.find("what they found (property x family x convention)"), std::string::npos)
      << report << "\n"
      << md;
  EXPECT_NE(md.find("`wrong_face`"), std::string::npos) << md;
}

// Other findings group by what ended the run: a sanitizer's error (by kind and function), a
// signal; an input that runs through is counted, not reported.
TEST(Cli, fuzzReportGroupsSanitizerErrorsAndCrashes) {
  namespace fs = std::filesystem;
  const fs::path work = fs::path(::testing::TempDir()) / "oblique_fuzz_report_crashes";
  fs::remove_all(work);
  fs::create_directories(work / "inputs");
  std::ofstream(work / "target.sh")
      << "case $(cat \"$1\") in\n"
      << "  asan*) echo '==7==ERROR: AddressSanitizer: heap-buffer-overflow on address 0x60'\n"
      << "         echo '    #0 0x4f5 in make_oblique engine.cpp:12'; exit 1;;\n"
      << "  segv) kill -SEGV $$;;\n"
      << "  *) exit 0;;\n"
      << "esac\n";
  for (const auto& [name, text] : {std::pair{"a", "asan one"}, std::pair{"b", "asan two"},
                                   std::pair{"c", "segv"}, std::pair{"d", "fine"}})
    std::ofstream(work / "inputs" / name) << text;
  std::string out;
  ASSERT_EQ(shell(std::string(OBLIQUE_CLI) + " fuzz-report --report-dir " +
                      (work / "reports").string() + " --target 'sh " +
                      (work / "target.sh").string() + "' " + (work / "inputs").string(),
                  &out),
            1)
      << out;
  EXPECT_NE(out.find("4 inputs, 2 distinct findings, 1 run without a finding now"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("AddressSanitizer heap-buffer-overflow in make_oblique: 2 inputs"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("crash: signal 11: 1 inputs"), std::string::npos) << out;
}

TEST(Cli, applyOnAFullDiskExitsTwoAndSaysSo) {
  const std::string in_path = ::testing::TempDir() + "oblique_cli_full_in.jsonl";
  std::ofstream(in_path) << kGood << "\n" << kGood << "\n";
  std::string err;
  // Standard error to the file shell() reads, standard output to the full device.
  const int status =
      shell("{ " + std::string(OBLIQUE_CLI) + " apply < " + in_path + " 2>&1 > /dev/full; }", &err);
  EXPECT_EQ(status, 2);
  EXPECT_NE(err.find("cannot write the answers"), std::string::npos) << err;
}

TEST(Cli, applySkipsALineLongerThanOneMebibyte) {
  std::vector<std::string> lines;
  const std::string input =
      kGood + "\n{\"projection\": [" + std::string(1 << 21, '1') + "]}\n" + kGood + "\n";
  EXPECT_EQ(run_cli("apply", input, &lines), 1);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(protocol::parse_answer(lines[0])->status, "ok");
  EXPECT_NE(lines[1].find("line longer than 1048576 bytes"), std::string::npos) << lines[1];
  EXPECT_EQ(protocol::parse_answer(lines[2])->status, "ok");
}

TEST(Cli, applyAnswersARequestFollowedByAPartialLineAtOnce) {
  // The writer sends one request and the start of the next, then waits: the answer must come
  // before the second line completes (here: before the writer's 4 s pause ends; 3 s allowed).
  std::string out;
  const std::string writer = "(printf '%s\\n{\"projection\"' '" + kGood + "'; sleep 4)";
  shell(writer + " | timeout 3 " + OBLIQUE_CLI + " apply | head -n 1", &out);
  EXPECT_EQ(out.rfind("{\"status\": \"ok\"", 0), 0u) << "no answer within 3 s: " << out;
}

}  // namespace
}  // namespace oblique
