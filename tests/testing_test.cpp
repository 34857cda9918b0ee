// oblique::testing on a user's function: the default contract is the function's own.
#include "oblique/testing.h"

#include <gtest/gtest-spi.h>

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "oblique/oblique.h"
#include "oblique/properties/generators.h"
#include "oblique/properties/mistakes.h"
#include "oblique/properties/seeded_recipes.h"

namespace oblique {
namespace {

/// A GL-only engine function, pointer-style (column-major, in place): it takes no convention.
Status make_oblique_gl(double m[16], const double plane[4]) {
  const ObliqueResult<double> r =
      apply<double>(adapting::load(m, Layout::column_major),
                    Vector4<double>(plane[0], plane[1], plane[2], plane[3]), Convention::gl);
  if (r.ok()) adapting::store(r.projection, Layout::column_major, m);
  return r.status;
}

const auto gl_only =
    adapt<double>("make_oblique_gl", Layout::column_major, Convention::gl, make_oblique_gl);

// The done-when of issue 25: the default contract checks it in the convention it serves.
OBLIQUE_PROPERTY_TEST(Testing, aGlOnlyFunctionPassesTheDefaultContract, gl_only, Contract{})

TEST(Testing, aContractNamingAConventionTheFunctionDoesNotServeFails) {
  Contract zero_one;
  zero_one.conventions = {Convention::zero_one};
  EXPECT_NONFATAL_FAILURE(testing::check_properties(gl_only, zero_one),
                          "the contract names convention zero_one, which make_oblique_gl");
}

TEST(Testing, theGlFunctionJudgedInAnotherConventionFails) {
  // What the default contract spares it: the same function, claimed for every convention (a
  // matrix-shaped wrapper that ignores the convention), is caught.
  const auto claims_all =
      adapt<double>("ignores_the_convention", Layout::row_major,
                    [](const Matrix4<double>& m, const Vector4<double>& c, Convention) {
                      return apply<double>(m, c, Convention::gl);
                    });
  Contract zero_one;
  zero_one.conventions = {Convention::zero_one};
  // Its near plane is M4 + M3' = lambda C in GL; in [0, 1] depth the near plane is M3' alone.
  // (Both conventions' far plane is M4 - M3', so far_plane_through_corner may well hold.)
  zero_one.properties = {properties::Property::near_is_clip_plane};
  zero_one.statuses = properties::StatusContract::answers_only;  // one run, so one failure
  EXPECT_NONFATAL_FAILURE(testing::check_properties(claims_all, zero_one),
                          "violates near_is_clip_plane");
}

// A pass is one line per property, and a report an earlier run left for a property that passes
// now is moved to earlier/ (kept, not deleted); other reports stay where they are.
TEST(Testing, aPassIsOneLineAndEarlierReportsAreMovedAside) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "oblique_testing_earlier_reports";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string id = "Testing.aPassIsOneLineAndEarlierReportsAreMovedAside";
  std::ofstream(dir / (id + ".near_is_clip_plane.md")) << "an earlier failure\n";
  std::ofstream(dir / (id + ".near_is_clip_plane.json")) << "{}\n";
  std::ofstream(dir / (id + ".no_clipping.md")) << "another property's\n";
  ASSERT_EQ(::setenv("OBLIQUE_REPORT_DIR", dir.c_str(), 1), 0);
  Contract one;
  one.properties = {properties::Property::near_is_clip_plane};
  one.statuses = properties::StatusContract::answers_only;
  ::testing::internal::CaptureStdout();
  testing::check_properties(gl_only, one);
  const std::string out = ::testing::internal::GetCapturedStdout();
  ::unsetenv("OBLIQUE_REPORT_DIR");
  EXPECT_EQ(out.find("families:"), std::string::npos) << out;
  EXPECT_EQ(out.rfind("near_is_clip_plane: OK, passed 100 tests", 0), 0u) << out;
  EXPECT_FALSE(fs::exists(dir / (id + ".near_is_clip_plane.md")));
  EXPECT_TRUE(fs::exists(dir / (id + ".no_clipping.md")));
  int moved = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "earlier")) {
    const std::string name = entry.path().filename().string();
    moved += name == id + ".near_is_clip_plane.md" || name == id + ".near_is_clip_plane.json";
  }
  EXPECT_EQ(moved, 2);
}

// The presets admit what adapter.h's table says, family by family, in every convention.
TEST(Presets, admitTheFamiliesTheirTableLists) {
  using generators::Family;
  const Family engine[] = {Family::perspective, Family::off_axis, Family::jittered,
                           Family::infinite};
  const Family shape_only[] = {Family::y_flipped, Family::x_flipped, Family::xy_flipped};
  rc::Random random(20261203);
  for (Family f : generators::all_families) {
    const bool in_engine = std::find(std::begin(engine), std::end(engine), f) != std::end(engine);
    const bool in_shape = in_engine || std::find(std::begin(shape_only), std::end(shape_only), f) !=
                                           std::end(shape_only);
    for (int i = 0; i < 60; ++i) {
      const generators::Case<double> c =
          generators::valid_case_of<double>(f)(random.split(), i % 101).value();
      EXPECT_EQ(perspective_shape_only<double>(c.convention, c.matrix), in_shape)
          << generators::family_name(f) << " " << convention_name(c.convention);
      EXPECT_EQ(engine_perspective_only<double>(c.convention, c.matrix), in_engine)
          << generators::family_name(f) << " " << convention_name(c.convention);
    }
  }
  Matrix4<double> left_handed = frustum<double>(-1, 1, -1, 1, 1, 10, Convention::gl);
  left_handed.col(2) *= -1;  // M43 = +1
  EXPECT_TRUE(perspective_shape_only<double>(Convention::gl, left_handed));
  EXPECT_FALSE(engine_perspective_only<double>(Convention::gl, left_handed));
}

/// Lengyel's Listing 5.1 as printed (GL, no guards), pointer-style.
void listing_5_1(double m[16], const double plane[4]) {
  const Matrix4<double> result =
      seeded::listing_5_1<double>(adapting::load(m, Layout::column_major),
                                  Vector4<double>(plane[0], plane[1], plane[2], plane[3]));
  adapting::store(result, Layout::column_major, m);
}

// What the presets are for: the printed closed form holds on the matrices an engine builds (and
// the unit-normal planes it builds: as printed, 2 / (C . Q) overflows for an all-subnormal
// plane), and is caught on the rest of the perspective shape.
const auto listing_on_engine_matrices =
    adapt<double>("listing_5_1", Layout::column_major, Convention::gl, listing_5_1,
                  engine_perspective_only<double>);
Contract unit_planes() {
  Contract c;
  c.planes = Planes::unit;
  return c;
}
OBLIQUE_PROPERTY_TEST(Presets, listing51HoldsOnTheMatricesAndPlanesAnEngineBuilds,
                      listing_on_engine_matrices, unit_planes())

TEST(Presets, listing51IsCaughtOnTheRestOfThePerspectiveShape) {
  const auto on_every_shape = adapt<double>("listing_5_1", Layout::column_major, Convention::gl,
                                            listing_5_1, perspective_shape_only<double>);
  ::testing::TestPartResultArray failures;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    testing::check_properties(on_every_shape, unit_planes());
  }
  EXPECT_GT(failures.size(), 0) << "Listing 5.1 passed on flipped matrices";
}

// The in-process accuracy profile: the GL function's report beside the core's three methods; a
// function whose answers violate the properties fails the test (they are not profiled).
TEST(Accuracy, aFunctionsProfileIsWrittenBesideTheCoresMethods) {
  namespace fs = std::filesystem;
  testing::AccuracySettings settings;
  settings.cases = 500;
  settings.directory = (fs::path(::testing::TempDir()) / "oblique_testing_accuracy").string();
  fs::remove_all(settings.directory);
  ::testing::internal::CaptureStdout();
  testing::profile_accuracy(gl_only, Contract{}, settings);
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(out.rfind("accuracy: ", 0), 0u) << out;
  std::ifstream in(fs::path(settings.directory) / "accuracy.md");
  const std::string md{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (const char* row : {"| make_oblique_gl | double |", "| core closed_form | double |",
                          "| core general | double |", "| core accurate | double |"})
    EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  EXPECT_NE(md.find(" a call |"), std::string::npos) << md;
}

TEST(Accuracy, aProfileWithoutAnswersFails) {
  testing::AccuracySettings none;
  none.cases = 0;
  none.directory =
      (std::filesystem::path(::testing::TempDir()) / "oblique_testing_accuracy_none").string();
  EXPECT_NONFATAL_FAILURE(testing::profile_accuracy(gl_only, Contract{}, none),
                          "no answer of make_oblique_gl was profiled");
}

TEST(Accuracy, answersThatViolateThePropertiesFailTheProfile) {
  const auto wrong =
      properties::mistaken_implementation<double>({properties::Mistake::zero_one_formula_on_gl});
  Contract gl;
  gl.conventions = {Convention::gl};
  testing::AccuracySettings settings;
  settings.cases = 200;
  settings.directory =
      (std::filesystem::path(::testing::TempDir()) / "oblique_testing_accuracy_wrong").string();
  ::testing::internal::CaptureStdout();
  EXPECT_NONFATAL_FAILURE(testing::profile_accuracy(wrong, gl, settings),
                          "answers violate the properties and are not profiled");
  ::testing::internal::GetCapturedStdout();
}

}  // namespace
}  // namespace oblique
