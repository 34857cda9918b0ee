// oblique::raster: the core's answers pass on llvmpipe in every convention and depth buffer; each
// class of wrong matrix is caught by the raster judgement alone; the judge's self-checks turn a
// renderer that misbehaves into "inconclusive", never a verdict. Skipped, with the reason, where
// the machine has no EGL.
#include <gtest/gtest.h>

#include <cmath>

#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/raster/check_pipeline.h"
#include "oblique/raster/raster.h"

namespace {

using Eigen::Matrix4d;
using Eigen::Vector4d;
using oblique::Convention;
using oblique::DepthBuffer;
using oblique::raster::Outcome;
using oblique::raster::Rasterizer;

/// One rasterizer for the whole test program (opening one costs its self-check).
const oblique::Expected<std::shared_ptr<Rasterizer>>& opened() {
  static const auto once = Rasterizer::open({oblique::raster::Device::software, 256});
  return once;
}
Rasterizer* shared() {
  return opened() ? opened()->get() : nullptr;
}

// Skipped where the machine has no EGL (the reason printed); a self-check that trips on a machine
// with EGL is a failure, not a skip.
#define REQUIRE_RASTERIZER()                                       \
  if (!shared()) {                                                 \
    if (opened().error().rfind("no EGL", 0) == 0) {                \
      GTEST_SKIP() << opened().error();                            \
    }                                                              \
    FAIL() << "the rasterizer did not open: " << opened().error(); \
  }

struct Case {
  const char* name;
  Matrix4d m;
  Vector4d c;
};

std::vector<Case> cases(Convention convention) {
  using oblique::frustum;
  Matrix4d y_flipped = oblique::perspective<double>(1.1, 1.5, 0.25, 500.0, convention);
  y_flipped.row(1) *= -1;
  return {
      {"perspective", oblique::perspective<double>(0.9, 1.0, 0.1, 100.0, convention),
       Vector4d(0.2, -0.9, -0.3, -1.5)},
      {"off_axis", frustum<double>(-0.3, 0.7, -0.2, 0.4, 0.5, 300.0, convention),
       Vector4d(-0.4, 0.5, -0.7, -3.0)},
      {"y_flipped", y_flipped, Vector4d(0.1, 0.8, -0.5, -2.0)},
      {"orthographic", oblique::orthographic<double>(-4, 4, -3, 3, 0.5, 50.0, convention),
       Vector4d(0.3, 0.2, -0.9, -6.0)},
      {"infinite", oblique::infinite_perspective<double>(1.0, 1.3, 0.2, convention),
       Vector4d(0.1, -0.6, -0.8, -1.0)},
  };
}

TEST(Raster, theCoresAnswersPassInEveryConventionAndBuffer) {
  REQUIRE_RASTERIZER();
  for (const Convention convention : oblique::all_conventions) {
    for (const Case& k : cases(convention)) {
      const auto answer = oblique::apply<double>(k.m, k.c, convention);
      ASSERT_EQ(answer.status, oblique::Status::ok) << k.name;
      for (const DepthBuffer buffer : {DepthBuffer::fixed24, DepthBuffer::float32}) {
        const auto r = shared()->check(k.m, k.c, answer.projection, convention, buffer, 11);
        EXPECT_EQ(r.outcome, Outcome::pass)
            << k.name << ", " << oblique::convention_name(convention) << ", "
            << oblique::depth_buffer_name(buffer) << ": " << r.why;
        // The frame is a real test: most samples drawn, some decided on each side of C.
        EXPECT_GT(r.drawn, r.placed / 10) << k.name;
        EXPECT_GT(r.placed, r.samples * 9 / 10) << k.name;
        EXPECT_LE(r.worst_depth_ratio, 1.0);
        EXPECT_GT(r.depth.bits, 1.0) << k.name;
      }
    }
  }
}

/// The answer with `mistake` made, for (M, C) in `convention`.
Matrix4d mistaken(oblique::mistakes::Mistake mistake, const Matrix4d& m, const Vector4d& c,
                  Convention convention) {
  const auto impl = oblique::mistakes::mistaken_implementation<double>({mistake});
  return impl.run(m, c, convention).projection;
}

// EGL gives every rasterizer of a process the same display: closing one must not end another's
// context (eglTerminate() would).
TEST(Raster, closingOneRasterizerLeavesAnotherWorking) {
  REQUIRE_RASTERIZER();
  {
    const auto second = Rasterizer::open({oblique::raster::Device::software, 16});
    ASSERT_TRUE(second) << second.error();
  }
  const Case k = cases(Convention::gl)[0];
  const auto answer = oblique::apply<double>(k.m, k.c, Convention::gl);
  const auto r =
      shared()->check(k.m, k.c, answer.projection, Convention::gl, DepthBuffer::fixed24, 5);
  EXPECT_EQ(r.outcome, Outcome::pass) << r.why;
}

// Found by a 10-minute verify --rasterize run of the correct example: C passes 5e-13 from the
// camera, where every pixel's ray meets; a sample that close lies off its ray's centre (double's
// rounding of a point near the eye), 0.0007 pixel from an edge, and llvmpipe's snap to its
// subpixel grid (1/256) drew it into the neighbouring pixel. Such samples are no longer placed
// (tolerance.h, kRasterSubpixel); the frame seeds below each had one.
TEST(Raster, aSampleTheSubpixelSnapCouldMoveIsNotPlaced) {
  REQUIRE_RASTERIZER();
  Matrix4d m;
  m << 0.14142135623730953, 0.044721359549995794, -0.1341640786499874, 0, -0.08944271909999159,
      0.3882842712474619, 0.0351471862576143, 0, 2.68338890855609e-05, 3.5148592201302354e-06,
      2.945702240361186e-05, 1.87507500300012, -0.6708203932499369, -0.08786796564403575,
      -0.7363961030678928, 0;
  const Vector4d c(-0.5, -0.5, 2, -4.823324033076557e-13);
  const auto answer = oblique::apply<double>(m, c, Convention::reversed_z);
  ASSERT_EQ(answer.status, oblique::Status::ok);
  const auto small = Rasterizer::open({oblique::raster::Device::software, 128});
  ASSERT_TRUE(small) << small.error();
  for (const std::uint64_t seed : {5, 20, 25, 28, 33, 35, 40}) {
    const auto r = (*small)->check(m, c, answer.projection, Convention::reversed_z,
                                   DepthBuffer::fixed24, seed);
    EXPECT_EQ(r.outcome, Outcome::pass) << "frame seed " << seed << ": " << r.why;
  }
}

TEST(Raster, theZeroOneFormulaOnGlIsDrawnBehindC) {
  REQUIRE_RASTERIZER();
  const Case k = cases(Convention::gl)[0];
  const Matrix4d reference = oblique::apply<double>(k.m, k.c, Convention::gl).projection;
  const Matrix4d wrong =
      mistaken(oblique::mistakes::Mistake::zero_one_formula_on_gl, k.m, k.c, Convention::gl);
  ASSERT_NE(wrong, reference);
  const auto r = shared()->check(k.m, k.c, wrong, Convention::gl, DepthBuffer::fixed24, 3);
  EXPECT_EQ(r.outcome, Outcome::fail) << r.why;
  EXPECT_GT(r.drawn_behind_c, 0) << r.why;
}

TEST(Raster, cameraSpaceSignsOnAYFlippedMatrixClipTheOriginalVolume) {
  REQUIRE_RASTERIZER();
  const Case k = cases(Convention::zero_one)[2];
  const Matrix4d reference = oblique::apply<double>(k.m, k.c, Convention::zero_one).projection;
  const Matrix4d wrong =
      mistaken(oblique::mistakes::Mistake::camera_space_signs, k.m, k.c, Convention::zero_one);
  ASSERT_NE(wrong, reference);
  const auto r = shared()->check(k.m, k.c, wrong, Convention::zero_one, DepthBuffer::float32, 3);
  EXPECT_EQ(r.outcome, Outcome::fail) << r.why;
  EXPECT_GT(r.clipped_kept, 0) << r.why;
  EXPECT_EQ(r.drawn_behind_c, 0) << r.why;
}

// Row 3 scaled by 1 + 1e-4: in gl and reversed Z the near plane becomes (1 + e) a C - e M_4, no
// longer C: it clips kept samples at C (M_4 . v = w > 0 there). In [0, 1] the near plane stays a C
// and only the far plane moves, by e at the far corner Q: what it clips is a sliver of the far
// face about e^2 of its pixels, none in a 256-pixel frame for e = 1e-2, so there e = 1e-1.
TEST(Raster, aThirdRowScaledALittleIsCaught) {
  REQUIRE_RASTERIZER();
  for (const Convention convention : oblique::all_conventions) {
    const Case k = cases(convention)[1];
    const Matrix4d reference = oblique::apply<double>(k.m, k.c, convention).projection;
    Matrix4d wrong = reference;
    const bool zero_one = convention == Convention::zero_one;
    wrong.row(2) *= zero_one ? 1 + 1e-1 : 1 + 1e-4;
    const auto r = shared()->check(k.m, k.c, wrong, convention, DepthBuffer::fixed24, 5);
    EXPECT_EQ(r.outcome, Outcome::fail) << oblique::convention_name(convention) << ": " << r.why;
    EXPECT_GT(r.clipped_kept, 0) << r.why;
  }
}

TEST(Raster, aMovedFourthRowDrawsIntoWrongPixels) {
  REQUIRE_RASTERIZER();
  const Case k = cases(Convention::gl)[0];
  const Matrix4d reference = oblique::apply<double>(k.m, k.c, Convention::gl).projection;
  Matrix4d wrong = reference;
  wrong(0, 0) *= 1.01;  // row 1 no longer M's: points move sideways
  const auto r = shared()->check(k.m, k.c, wrong, Convention::gl, DepthBuffer::fixed24, 5);
  EXPECT_EQ(r.outcome, Outcome::fail) << r.why;
  EXPECT_GT(r.wrong_pixel, 0) << r.why;
}

// The judge alone, on made-up read-backs: a renderer that ignores clipping, or writes one id into
// two pixels, is inconclusive, not a verdict about the answer.
TEST(RasterJudge, aRendererThatDrawsEverythingIsInconclusive) {
  const Case k = cases(Convention::gl)[0];
  const Matrix4d answer = oblique::apply<double>(k.m, k.c, Convention::gl).projection;
  const auto frame = oblique::raster::make_frame(k.m, k.c, answer, Convention::gl, 64, 1);
  oblique::raster::Readback all;
  all.ids.resize(frame.points.size());
  all.depths.assign(frame.points.size(), 0.5f);
  for (std::size_t p = 0; p < frame.points.size(); ++p)
    all.ids[p] = frame.placed[p] ? static_cast<std::uint32_t>(p + 1) : 0;
  const auto r =
      oblique::raster::judge_frame(frame, all, k.m, k.c, answer, answer,
                                   oblique::raster::accepted_row3(k.m, k.c, Convention::gl, 53),
                                   Convention::gl, DepthBuffer::fixed24);
  EXPECT_EQ(r.outcome, Outcome::inconclusive) << r.why;
  EXPECT_GT(r.renderer_disagrees, 0);
  EXPECT_EQ(r.drawn_behind_c, 0);  // never counted against the answer
}

TEST(RasterJudge, oneIdInTwoPixelsIsInconclusive) {
  const Case k = cases(Convention::zero_one)[0];
  const Matrix4d answer = oblique::apply<double>(k.m, k.c, Convention::zero_one).projection;
  const auto frame = oblique::raster::make_frame(k.m, k.c, answer, Convention::zero_one, 32, 1);
  oblique::raster::Readback none;
  none.ids.assign(frame.points.size(), 0);
  none.depths.assign(frame.points.size(), 1.0f);
  none.ids[0] = none.ids[1] = 5;
  const auto r = oblique::raster::judge_frame(
      frame, none, k.m, k.c, answer, answer,
      oblique::raster::accepted_row3(k.m, k.c, Convention::zero_one, 53), Convention::zero_one,
      DepthBuffer::float32);
  EXPECT_EQ(r.outcome, Outcome::inconclusive) << r.why;
  EXPECT_EQ(r.ids_inconsistent, 1);
}

TEST(RasterJudge, theFrameBunchesSamplesAtCOnBothSides) {
  const Case k = cases(Convention::reversed_z)[1];
  const Matrix4d answer = oblique::apply<double>(k.m, k.c, Convention::reversed_z).projection;
  const auto frame = oblique::raster::make_frame(k.m, k.c, answer, Convention::reversed_z, 128, 9);
  long near_front = 0, near_back = 0;
  for (std::size_t p = 0; p < frame.points.size(); ++p) {
    if (!frame.placed[p]) continue;
    const double d = k.c.dot(frame.points[p].cast<double>()) / k.c.head<3>().norm();
    if (std::abs(d) < 1e-3) ++(d > 0 ? near_front : near_back);
  }
  EXPECT_GT(near_front, 100);
  EXPECT_GT(near_back, 100);
}

// The pipeline (frames built and read-backs judged on threads of their own) gives each job the
// Result that Rasterizer::check() gives it, in submission order: right and wrong answers, and an
// input the core has no answer for (nothing drawn, the same reason said).
TEST(RasterPipeline, givesEachJobTheResultOfACheck) {
  REQUIRE_RASTERIZER();
  using oblique::raster::CheckPipeline;
  std::vector<CheckPipeline::Job> jobs;
  for (const Convention convention : oblique::all_conventions) {
    for (const Case& k : cases(convention)) {
      CheckPipeline::Job job;
      job.m = k.m;
      job.c = k.c;
      job.answer = oblique::apply<double>(k.m, k.c, convention).projection;
      job.convention = convention;
      job.buffer = jobs.size() % 2 ? DepthBuffer::float32 : DepthBuffer::fixed24;
      job.seed = 100 + jobs.size();
      job.tag = static_cast<long>(jobs.size());
      jobs.push_back(job);
      job.answer.row(2) *= 1 + 1e-1;  // wrong: caught
      job.tag = static_cast<long>(jobs.size());
      jobs.push_back(job);
    }
  }
  CheckPipeline::Job refused = jobs.front();
  refused.c = Vector4d(0, 0, -1, 1);  // C_w > 0: the core has no answer
  refused.tag = static_cast<long>(jobs.size());
  jobs.push_back(refused);
  std::vector<CheckPipeline::Done> done;
  {
    CheckPipeline pipeline(*shared());
    for (const CheckPipeline::Job& job : jobs) {
      std::vector<CheckPipeline::Done> now = pipeline.submit(job);
      EXPECT_LE(now.size(), 1u);
      for (auto& d : now) done.push_back(std::move(d));
    }
    for (auto& d : pipeline.drain()) done.push_back(std::move(d));
  }
  ASSERT_EQ(done.size(), jobs.size());
  long failed = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const CheckPipeline::Job& job = jobs[i];
    EXPECT_EQ(done[i].first, job.tag);
    const auto alone =
        shared()->check(job.m, job.c, job.answer, job.convention, job.buffer, job.seed);
    const auto& piped = done[i].second;
    EXPECT_EQ(piped.outcome, alone.outcome) << i << ": " << alone.why;
    EXPECT_EQ(piped.why, alone.why) << i;
    EXPECT_EQ(piped.rendered, alone.rendered) << i;
    EXPECT_EQ(piped.placed, alone.placed) << i;
    EXPECT_EQ(piped.drawn, alone.drawn) << i;
    EXPECT_EQ(piped.clipped_kept, alone.clipped_kept) << i;
    EXPECT_EQ(piped.drawn_behind_c, alone.drawn_behind_c) << i;
    failed += piped.outcome == Outcome::fail;
  }
  EXPECT_GT(failed, 0);
  EXPECT_FALSE(done.back().second.rendered);
}

// A frame is a function of its inputs and seed alone: drawn twice, the same samples (a raster
// report's frame seed replays its frame).
TEST(RasterJudge, aFrameSeedDrawsTheSameFrame) {
  const Case k = cases(Convention::gl)[1];
  const Matrix4d answer = oblique::apply<double>(k.m, k.c, Convention::gl).projection;
  const auto a = oblique::raster::make_frame(k.m, k.c, answer, Convention::gl, 64, 12345);
  const auto b = oblique::raster::make_frame(k.m, k.c, answer, Convention::gl, 64, 12345);
  const auto other = oblique::raster::make_frame(k.m, k.c, answer, Convention::gl, 64, 12346);
  ASSERT_EQ(a.points.size(), b.points.size());
  long differ = 0;
  for (std::size_t p = 0; p < a.points.size(); ++p) {
    EXPECT_EQ(a.placed[p], b.placed[p]);
    EXPECT_EQ(a.points[p], b.points[p]);
    differ += a.placed[p] && other.placed[p] && a.points[p] != other.points[p];
  }
  EXPECT_GT(differ, static_cast<long>(a.points.size()) / 2);
}

}  // namespace
