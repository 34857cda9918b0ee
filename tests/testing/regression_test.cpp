// Replays every counterexample the project has kept (tests/regressions/*.json): the core
// must answer each with an acceptable status and every property, and the implementation that
// failed on it (a printed recipe or a mutant) must still fail the same way, so a finding in the
// README cannot silently stop being true.
#include <gtest/gtest.h>

#include <map>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "oblique/mistakes/implementations.h"
#include "oblique/oracle/judge.h"
#include "oblique/oracle/problem.h"

namespace oblique::oracle {

using mistakes::core_method;
using mistakes::known_implementations;
namespace {

std::vector<std::filesystem::path> regression_files() {
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(OBLIQUE_REGRESSION_DIR)) {
    if (entry.path().extension() == ".json") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// A kept number: a decimal, a hex float, "nan", "-nan", "inf" or "-inf" (protocol::parse_number
/// reads decimals as JSON number tokens, the rest as the protocol's strings).
template <class T>
T parse_value(const std::string& text) {
  Expected<T> value = protocol::parse_number<T>(text);
  if (!value) value = protocol::parse_number<T>("\"" + text);
  EXPECT_TRUE(value) << text << ": " << value.error();
  return value ? *value : T(0);
}

template <class T>
void replay(const nlohmann::json& j, const std::string& name) {
  Matrix4<T> m;
  Vector4<T> c;
  for (int i = 0; i < 16; ++i)
    m(i / 4, i % 4) = parse_value<T>(j.at("projection").at(i).get<std::string>());
  for (int i = 0; i < 4; ++i) c(i) = parse_value<T>(j.at("plane").at(i).get<std::string>());
  const Convention convention = parse_convention(j.at("convention").get<std::string>()).value();
  const Problem<T> problem(m, c, convention);
  for (Method method : all_methods) {
    const Implementation<T> core = core_method<T>(method);
    if (!core.accepts(convention, m)) continue;
    const Answer<T> outcome = core.run(m, c, convention);
    const Judgement judgement = judge(problem, outcome, core.checks(/*accuracy=*/true));
    EXPECT_TRUE(judgement.holds())
        << name << ": " << core.name << " violates " << check_name(judgement.violation()->check);
  }
  // Regressions kept before issue 26 name the planted mutants the catalogue's mistakes replaced.
  const std::map<std::string, std::string> renamed = {
      {"mutant_signs_from_c", "mistake_camera_space_signs"},
      {"mutant_zero_one_factor", "mistake_zero_one_formula_on_gl"},
      {"mutant_sign_by_division", "mistake_sign_by_division"},
      {"mutant_wrong_face", "mistake_wrong_face"},
      {"mutant_no_camera_check", "mistake_no_camera_guard"},
      {"mutant_ignores_m11_sign", "mistake_ignores_m11_sign"}};
  std::string recorded = j.at("implementation").get<std::string>();
  if (const auto it = renamed.find(recorded); it != renamed.end()) recorded = it->second;
  if (recorded.rfind("core_", 0) == 0) return;  // a finding about the checker: the core passes
  for (const Implementation<T>& impl : known_implementations<T>()) {
    if (impl.name != recorded) continue;
    const Answer<T> outcome = impl.run(m, c, convention);
    EXPECT_FALSE(judge(problem, outcome, impl.checks()).holds())
        << name << ": " << recorded << " no longer fails here";
    return;
  }
  ADD_FAILURE() << name << ": unknown implementation " << recorded;
}

TEST(Regressions, everyKeptCounterexampleStillHolds) {
  const auto files = regression_files();
  ASSERT_FALSE(files.empty()) << "no regression cases in " << OBLIQUE_REGRESSION_DIR;
  for (const auto& path : files) {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    const std::string precision = j.at("precision").get<std::string>();
    const std::string name = path.filename().string();
    if (precision == "float") {
      replay<float>(j, name);
    } else if (precision == "double") {
      replay<double>(j, name);
    } else {
      replay<long double>(j, name);
    }
  }
  std::cout << "replayed " << files.size() << " kept counterexamples" << std::endl;
}

}  // namespace
}  // namespace oblique::oracle
