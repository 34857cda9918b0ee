// The reference scene of a finding (oblique/raster/case_scene.h): what the answer clips or draws
// that the correct M' does not is marked, rendered and shows in the difference; the core's own
// answer shows none.
#include "oblique/raster/case_scene.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"
#include "oblique/projection.h"

namespace {

using Eigen::Matrix4d;
using Eigen::Vector4d;
using oblique::Convention;
namespace raster = oblique::raster;

struct Case {
  const char* name;
  Matrix4d m;
  Vector4d c;
  Convention convention;
};

/// A water plane below and ahead of the eye, tilted; in each convention, finite and infinite.
std::vector<Case> cases() {
  std::vector<Case> out;
  const Vector4d c = Vector4d(0.15, 0.9, -0.35, -1.2).normalized();
  for (Convention k : oblique::all_conventions) {
    out.push_back(
        {"perspective", oblique::frustum<double>(-0.16, 0.16, -0.1, 0.1, 0.1, 200, k), c, k});
    out.push_back(
        {"infinite", oblique::infinite_frustum<double>(-0.16, 0.16, -0.1, 0.1, 0.1, k), c, k});
    out.push_back({"orthographic", oblique::orthographic<double>(-8, 8, -5, 5, 0.5, 60, k), c, k});
  }
  return out;
}

Matrix4d core_answer(const Case& c) {
  const auto r = oblique::apply<double>(c.m, c.c, c.convention);
  EXPECT_EQ(r.status, oblique::Status::ok) << c.name;
  return r.projection;
}

/// The wrong answers: the mistakes of the catalogue that change what is clipped here.
Matrix4d mistaken(const Case& c, oblique::mistakes::Mistake mistake) {
  const auto implementation = oblique::mistakes::mistaken_implementation<double>({mistake});
  return implementation.run(c.m, c.c, c.convention).projection;
}

#define SKIP_WITHOUT_EGL(result)                               \
  if (!(result) && (result).error().rfind("no EGL", 0) == 0) { \
    GTEST_SKIP() << (result).error();                          \
  }

TEST(CaseScene, keepsIsTheClipVolumeOfEachConvention) {
  const Matrix4d m = oblique::frustum<double>(-1, 1, -1, 1, 1, 10, Convention::gl);
  EXPECT_TRUE(raster::keeps(m, Vector4d(0, 0, -5, 1), Convention::gl));
  EXPECT_FALSE(raster::keeps(m, Vector4d(0, 0, -11, 1), Convention::gl));
  EXPECT_FALSE(raster::keeps(m, Vector4d(0, 0, -0.5, 1), Convention::gl));
  EXPECT_FALSE(raster::keeps(m, Vector4d(6, 0, -5, 1), Convention::gl));
  const Matrix4d r = oblique::frustum<double>(-1, 1, -1, 1, 1, 10, Convention::reversed_z);
  EXPECT_TRUE(raster::keeps(r, Vector4d(0, 0, -5, 1), Convention::reversed_z));
  EXPECT_FALSE(raster::keeps(r, Vector4d(0, 0, -0.5, 1), Convention::reversed_z));
}

TEST(CaseScene, disagreementsAreWhereOneMatrixKeepsAndTheOtherClips) {
  for (const Case& c : cases()) {
    const Matrix4d right = core_answer(c);
    EXPECT_TRUE(raster::disagreements(c.m, right, right, c.convention).empty()) << c.name;
    // The original M keeps what is behind C (M' clips it there), and M' keeps some of what
    // is beyond M's far plane (its far plane is tilted through the far corner).
    const auto marks = raster::disagreements(c.m, right, c.m, c.convention);
    ASSERT_FALSE(marks.empty()) << c.name;
    for (const Vector4d& p : marks) {
      EXPECT_NE(raster::keeps(right, p, c.convention), raster::keeps(c.m, p, c.convention));
      if (raster::keeps(c.m, p, c.convention)) {
        EXPECT_LT(c.c.dot(p), 0) << c.name << ": M keeps it, M' clips it: behind C";
      }
    }
  }
}

TEST(CaseScene, theSceneIsInFrontOfTheEyeAndStraddlesC) {
  for (const Case& c : cases()) {
    const raster::Mesh mesh = raster::reference_scene(c.m, c.c, c.convention, {});
    ASSERT_FALSE(mesh.points.empty()) << c.name;
    long seen = 0, in_front = 0, behind = 0;
    for (const Eigen::Vector4f& p : mesh.points) {
      const Vector4d q = p.cast<double>();
      seen += raster::keeps(c.m, q, c.convention);
      (c.c.dot(q) >= 0 ? in_front : behind) += 1;
    }
    EXPECT_GT(seen, static_cast<long>(mesh.points.size() / 4)) << c.name;
    EXPECT_GT(in_front, 0) << c.name;
    EXPECT_GT(behind, 0) << c.name;
  }
}

// The difference is empty for the core's own answer and, for a wrong one, not empty where the
// finding is: red within a few pixels of each mark.
TEST(CaseScene, theDifferenceShowsTheFaultAndNothingForTheRightAnswer) {
  using oblique::mistakes::Mistake;
  const char* keep = std::getenv("OBLIQUE_CASE_SCENE_PICTURES");  // a folder to look at them in
  int visible = 0;
  for (const Case& c : cases()) {
    const Matrix4d right = core_answer(c);
    const auto same = raster::render_case(c.m, c.c, right, right, c.convention, {}, 160);
    SKIP_WITHOUT_EGL(same);
    ASSERT_TRUE(same) << same.error();
    EXPECT_EQ(same->differing, 0) << c.name;
    EXPECT_TRUE(same->marks.empty());
    for (Mistake mistake : {Mistake::wrong_face, Mistake::camera_space_signs}) {
      const Matrix4d wrong = mistaken(c, mistake);
      if (raster::disagreements(c.m, right, wrong, c.convention).empty()) continue;
      const auto renders = raster::render_case(c.m, c.c, right, wrong, c.convention, {}, 160);
      ASSERT_TRUE(renders) << renders.error();
      if (renders->differing == 0) {
        // Below what the picture resolves: every place they disagree was left out, and said.
        EXPECT_TRUE(renders->marks.empty()) << c.name;
        EXPECT_GT(renders->unseen_marks, 0) << c.name;
        continue;
      }
      ++visible;
      ASSERT_EQ(renders->mark_pixels.size(), renders->marks.size());
      for (std::size_t k = 0; k < renders->marks.size(); ++k) {
        const auto [x, y] = renders->mark_pixels[k];
        long red = 0;
        for (int v = y - 3; v <= y + 3; ++v)
          for (int u = x - 3; u <= x + 3; ++u)
            if (u >= 0 && v >= 0 && u < 160 && v < 160) {
              const std::uint8_t* p = renders->difference.at(u, v);
              red += p[0] == 220 && p[1] == 20 && p[2] == 30;
            }
        // Red at the mark, or in the zoom around it (a thin difference).
        bool zoomed = false;
        for (const auto& zoom : renders->zooms) zoomed |= zoom.mark == static_cast<int>(k);
        EXPECT_TRUE(red > 0 || (zoomed && renders->mark_shown[k]))
            << c.name << " " << oblique::mistakes::mistake_entry(mistake).name
            << ": no difference at the mark (" << x << ", " << y << ")";
        EXPECT_EQ(renders->mark_shown[k], red > 0 || zoomed) << c.name;
      }
      if (keep) {
        const std::string stem = std::string(keep) + "/" + c.name + "_" +
                                 std::string(oblique::convention_name(c.convention)) + "_" +
                                 std::string(oblique::mistakes::mistake_entry(mistake).name);
        const auto row = oblique::report::side_by_side(
            {&renders->expected.colour, &renders->answered.colour, &renders->difference,
             &renders->expected_depth, &renders->answered_depth},
            6);
        std::ofstream(stem + ".png", std::ios::binary) << oblique::report::png_bytes(row);
      }
    }
  }
  // Most of these mistakes move a plane by far more than a pixel.
  EXPECT_GE(visible, 9);
}

}  // namespace
