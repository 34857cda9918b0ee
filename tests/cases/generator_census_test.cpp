// The generators' census (issue 44): every sign an engine's matrix takes, in each shape family,
// is drawn and reaches the judgement in every default run (100 cases, sizes 0 .. 99), whatever
// the seed, under the engine contract's families and under every family.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <initializer_list>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "oblique/cases/contract.h"
#include "oblique/cases/generators.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"
#include "oblique/projection.h"
#include "oblique/references/frustum_planes.h"

namespace oblique {
namespace {

using cases::Family;

std::string sign(double x) {
  return x < 0 ? "<0" : (x > 0 ? ">0" : "=0");
}

/// The sign features a case of `c`'s family shows (row-major M(i, j) printed 1-based): the
/// joint (M13, M23) signs of an off-axis frustum; for the others each entry's sign alone.
template <class T>
std::vector<std::string> features(const cases::Case<T>& c) {
  const auto& m = c.matrix;
  const std::string family(cases::family_name(c.family));
  switch (c.family) {
    case Family::off_axis:
      return {family + " M13" + sign(double(m(0, 2))) + " M23" + sign(double(m(1, 2)))};
    case Family::jittered:
    case Family::y_flipped:
    case Family::x_flipped:
    case Family::xy_flipped:
      return {family + " M13" + sign(double(m(0, 2))), family + " M23" + sign(double(m(1, 2)))};
    case Family::left_handed:
    case Family::left_handed_x_flipped:
      return {family + " M13" + sign(double(m(0, 2))), family + " M23" + sign(double(m(1, 2))),
              family + " M43" + sign(double(m(3, 2))), family + " M11" + sign(double(m(0, 0))),
              family + (far_plane(m, c.convention).template head<3>().isZero(0) ? " infinite"
                                                                                : " finite")};
    case Family::stereo_shift:
      return {family + " M13" + sign(double(m(0, 2))), family + " M14" + sign(double(m(0, 3))),
              family + " M24" + sign(double(m(1, 3)))};
    case Family::orthographic:
      return {family + " M14" + sign(double(m(0, 3))), family + " M24" + sign(double(m(1, 3))),
              family + (m(0, 3) == T(0) && m(1, 3) == T(0) ? " centred" : " off-centre")};
    default: return {};
  }
}

/// The features each default run must show for `families`.
std::set<std::string> required(const std::vector<Family>& families) {
  std::set<std::string> out;
  for (Family f : families) {
    const std::string name(cases::family_name(f));
    // Each of `entries` seen negative and positive.
    auto either_sign = [&](std::initializer_list<const char*> entries) {
      for (const char* entry : entries)
        for (const char* s : {"<0", ">0"}) out.insert(name + " " + entry + s);
    };
    switch (f) {
      case Family::off_axis:
        for (const char* x : {"<0", ">0"})
          for (const char* y : {"<0", ">0"}) out.insert(name + " M13" + x + " M23" + y);
        break;
      case Family::jittered:
      case Family::y_flipped:
      case Family::x_flipped:
      case Family::xy_flipped: either_sign({"M13", "M23"}); break;
      case Family::left_handed:
      case Family::left_handed_x_flipped:
        either_sign({"M13", "M23"});
        out.insert(name + " M43>0");
        out.insert(name + (f == Family::left_handed ? " M11>0" : " M11<0"));
        out.insert(name + " finite");
        out.insert(name + " infinite");
        break;
      case Family::stereo_shift: either_sign({"M13", "M14", "M24"}); break;
      case Family::orthographic:
        either_sign({"M14", "M24"});
        out.insert(name + " centred");
        out.insert(name + " off-centre");
        break;
      default: break;
    }
  }
  return out;
}

/// For `runs` seeds: the default run's cases of the contract, and the features of those whose
/// answer would be judged (oracle::not_judged() leaves nothing out for the contract's
/// statuses); each run must show every required feature.
template <class T>
void every_run_shows_every_pattern(Contract contract, int runs) {
  contract = resolved(contract, {Convention::gl}, cases::StatusContract::exact, false);
  contract.conventions = cases::every_convention();
  const std::set<std::string> needed = required(contract.families);
  ASSERT_FALSE(needed.empty());
  const auto gen = cases::valid_case_for<T>(contract);
  for (int run = 0; run < runs; ++run) {
    rc::Random random(20261205u + static_cast<std::uint64_t>(run));
    std::map<std::string, int> judged;
    for (int size = 0; size < 100; ++size) {
      const cases::Case<T> c = gen(random.split(), size).value();
      const oracle::FilteredProblem<T> problem(c.matrix, c.plane, c.convention);
      if (!oracle::not_judged(problem, *contract.statuses, contract.refusals).empty()) continue;
      for (const std::string& f : features(c)) ++judged[f];
    }
    for (const std::string& f : needed)
      EXPECT_GT(judged[f], 0) << "run " << run << " (" << contract_json(contract)
                              << "): no case of " << f << " was judged";
  }
}

TEST(GeneratorCensus, everySignPatternOfTheEngineFamiliesIsJudgedInEveryRun) {
  every_run_shows_every_pattern<double>(engine_contract(), 30);
  every_run_shows_every_pattern<float>(engine_contract(), 30);
}

TEST(GeneratorCensus, everySignPatternOfEveryFamilyIsJudgedInEveryRun) {
  Contract every;
  every.statuses = cases::StatusContract::exact;
  every_run_shows_every_pattern<double>(every, 30);
  every_run_shows_every_pattern<float>(every, 30);
}

// The census itself: a family's features are what its matrices show (a generator drawing one
// lean only would fail above).
TEST(GeneratorCensus, theFeaturesReadTheMatrix) {
  cases::Case<double> c;
  c.family = Family::off_axis;
  c.matrix = frustum<double>(-3, 1, -1, 2, 1, 10, Convention::gl);  // leans left and up
  EXPECT_EQ(features(c), std::vector<std::string>{"off_axis M13<0 M23>0"});
  c.family = Family::orthographic;
  c.matrix = orthographic<double>(-1, 1, -1, 1, 1, 10, Convention::gl);
  EXPECT_EQ(features(c), (std::vector<std::string>{"orthographic M14=0", "orthographic M24=0",
                                                   "orthographic centred"}));
}

}  // namespace
}  // namespace oblique
