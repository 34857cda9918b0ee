// oblique::testing's raster check (oblique/testing/raster.h) on a user's function: the core's
// answers pass in every convention, float and double; each class of wrong matrix the raster
// judgement exists for is caught by it alone, with a report of the flagged pixels. Skipped, with
// what to install, where the machine has no EGL.
#include "oblique/testing/raster.h"

#include <gtest/gtest-spi.h>

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"

namespace oblique {
namespace {

template <class T>
oracle::Implementation<T> core() {
  return adapt<T>(
      "the_core", Layout::row_major,
      [](const Matrix4<T>& m, const Vector4<T>& c, Convention k) { return apply<T>(m, c, k); });
}

OBLIQUE_RASTER_TEST(TestingRaster, theCoreInDoublePassesEveryConvention, core<double>(), Contract{})
OBLIQUE_RASTER_TEST(TestingRaster, theCoreInFloatPassesEveryConvention, core<float>(), Contract{})

/// The files of `dir` whose names end with `suffix`.
std::vector<std::filesystem::path> files_ending(const std::filesystem::path& dir,
                                                const std::string& suffix) {
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(entry.path());
  }
  return out;
}

/// Runs the raster check on `mistake` under `contract` in a fresh report folder: it must fail
/// on the rasterizer with `flag` among the samples flagged, and write a report with the pixels'
/// picture data.
void expect_caught(mistakes::Mistake mistake, const Contract& contract, const std::string& flag) {
  namespace fs = std::filesystem;
  const auto wrong = mistakes::mistaken_implementation<double>({mistake});
  const fs::path dir =
      fs::path(::testing::TempDir()) /
      ("oblique_testing_raster_" + std::string(mistakes::mistake_entry(mistake).name));
  fs::remove_all(dir);
  ASSERT_EQ(::setenv("OBLIQUE_REPORT_DIR", dir.c_str(), 1), 0);
  EXPECT_NONFATAL_FAILURE(testing::check_on_rasterizer(wrong, contract),
                          wrong.name + " fails on the rasterizer");
  ::unsetenv("OBLIQUE_REPORT_DIR");
  const auto reports = files_ending(dir, ".rasterizer.md");
  ASSERT_EQ(reports.size(), 1u) << dir;
  std::ifstream in(reports.front());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("# Counterexample: the rasterizer (" + wrong.name), std::string::npos)
      << text;
  EXPECT_NE(text.find("| " + flag + " |"), std::string::npos) << text;
  EXPECT_NE(text.find("RC_PARAMS="), std::string::npos) << text;
  // The frame as drawn with the flagged samples over it, linked from the report.
  EXPECT_EQ(files_ending(dir, ".rasterizer.pixels.png").size(), 1u) << dir;
  EXPECT_NE(text.find("with the flagged samples over it"), std::string::npos) << text;
}

// Skips where there is no EGL (the reason printed), as check_on_rasterizer() itself does.
#define REQUIRE_RASTERIZER()                                                        \
  if (const auto opened = raster::Rasterizer::open({raster::Device::software, 16}); \
      !opened && opened.error().rfind("no EGL", 0) == 0)                            \
  GTEST_SKIP() << opened.error()

TEST(TestingRaster, theZeroOneFormulaOnGlIsDrawnBehindC) {
  REQUIRE_RASTERIZER();
  Contract gl;
  gl.conventions = {Convention::gl};
  expect_caught(mistakes::Mistake::zero_one_formula_on_gl, gl, "drawn_behind_c");
}

TEST(TestingRaster, cameraSpaceSignsOnYFlippedMatricesClipTheKeptRegion) {
  REQUIRE_RASTERIZER();
  Contract y_flipped;
  y_flipped.families = {cases::Family::y_flipped};
  y_flipped.conventions = {Convention::gl};
  expect_caught(mistakes::Mistake::camera_space_signs, y_flipped, "clipped_kept");
}

TEST(TestingRaster, aFrameSizeOutOfRangeIsSaid) {
  testing::RasterSettings tiny;
  tiny.size = 8;
  EXPECT_NONFATAL_FAILURE(testing::check_on_rasterizer(core<double>(), Contract{}, tiny),
                          "RasterSettings::size must be within [16, 4096] pixels, not 8");
}

TEST(TestingRaster, aContractNamingAConventionTheFunctionDoesNotServeFails) {
  auto gl_only = core<double>();
  gl_only.name = "gl_only";
  gl_only.conventions = {Convention::gl};  // as adapt() makes a function that takes none
  Contract zero_one;
  zero_one.conventions = {Convention::zero_one};
  EXPECT_NONFATAL_FAILURE(testing::check_on_rasterizer(gl_only, zero_one),
                          "the contract names convention zero_one, which gl_only");
}

}  // namespace
}  // namespace oblique
