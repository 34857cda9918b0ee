// The references of the code around the matrix (depth_reconstruction.h, kept_region.h,
// pass_camera.h) and the consumer properties (consumers.h): each property holds for the right
// answer and for it a few ulps off, and alone rejects the wrong answers it exists for.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/oracle/exact.h"
#include "oblique/projection.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace {

using oblique::Convention;
using oblique::DepthBuffer;
using oblique::Matrix4;
using oblique::Vector3;
using oblique::Vector4;
using oblique::oracle::ConsumerCheck;
using oblique::oracle::ConsumerFinding;

const Convention kConventions[] = {Convention::gl, Convention::zero_one, Convention::reversed_z};

Matrix4<double> perspective(Convention convention, double n = 0.5, double f = 200) {
  return oblique::perspective<double>(1.2, 16.0 / 9.0, n, f, convention);
}

/// A water-like plane, tilted, 2 units in front of the camera, keeping the far side.
Vector4<double> tilted_plane() {
  return oblique::plane_from_normal_and_point<double>(Vector3<double>(0.3, 0.4, -1),
                                                      Vector3<double>(0, 0, -2));
}

Matrix4<double> oblique_of(const Matrix4<double>& m, const Vector4<double>& c, Convention k) {
  const auto result = oblique::apply<double>(m, c, k);
  EXPECT_EQ(result.status, oblique::Status::ok);
  return result.projection;
}

/// A point of the kept region: the mean of its finite vertices.
Vector4<double> kept_centre(const Matrix4<double>& m, const Vector4<double>& c, Convention k) {
  Vector4<double> sum = Vector4<double>::Zero();
  int n = 0;
  for (const auto& v : oblique::kept_region_vertices(m, c, k)) {
    if (v.w() != 0) {
      sum += v;
      ++n;
    }
  }
  return sum / n;
}

const ConsumerFinding& find(const std::vector<ConsumerFinding>& findings, ConsumerCheck check) {
  for (const auto& f : findings) {
    if (f.check == check) return f;
  }
  throw std::logic_error("no such finding");
}

Vector3<double> nudged(Vector3<double> v, int ulps) {
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < ulps; ++k) v(i) = std::nextafter(v(i), 2 * v(i) + 1);
  }
  return v;
}

TEST(DepthReconstruction, viewPositionInvertsTheWindowDepth) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> p(0.7, -0.3, -5, 1);
    const Vector4<double> clip = m * p;
    const double depth = oblique::window_depth(clip.z() / clip.w(), k);
    const Vector3<double> back =
        oblique::view_position(m, clip.x() / clip.w(), clip.y() / clip.w(), depth, k);
    EXPECT_NEAR((back - p.head<3>()).norm(), 0, 1e-12) << convention_name(k);
    EXPECT_EQ(oblique::view_axis_sign(m, k), -1);
    EXPECT_NEAR(oblique::linear_depth(m, clip.x() / clip.w(), clip.y() / clip.w(), depth, k, -1), 5,
                1e-12);
  }
}

TEST(DepthReconstruction, rightAnswersHoldAndTheOriginalMatrixIsCaught) {
  for (Convention k : kConventions) {
    for (DepthBuffer buffer : {DepthBuffer::fixed24, DepthBuffer::float32}) {
      const Matrix4<double> m = perspective(k);
      const Vector4<double> c = tilted_plane();
      const Matrix4<double> mo = oblique_of(m, c, k);
      const auto sample = oblique::oracle::depth_sample(mo, m, k, buffer, kept_centre(m, c, k));
      ASSERT_TRUE(sample.has_value());
      const Vector3<double> right =
          oblique::view_position(mo, sample->ndc_x, sample->ndc_y, sample->depth, k);
      EXPECT_TRUE(oblique::oracle::judge_view_position(*sample, right).holds);
      EXPECT_TRUE(oblique::oracle::judge_view_position(*sample, nudged(right, 4)).holds);
      // The same depth read through M instead of M'.
      const Vector3<double> wrong =
          oblique::view_position(m, sample->ndc_x, sample->ndc_y, sample->depth, k);
      const ConsumerFinding f = oblique::oracle::judge_view_position(*sample, wrong);
      EXPECT_TRUE(f.judged);
      EXPECT_FALSE(f.holds) << describe(f);
    }
  }
}

/// A pass camera's view: a rotation, a translation far from the origin, mirrored or not.
Matrix4<double> far_pass_view(bool mirrored) {
  Matrix4<double> v = Matrix4<double>::Identity();
  v.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(0.7, Vector3<double>(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  v.topRightCorner<3, 1>() = Vector3<double>(3000.5, -1200.25, 4100);
  if (mirrored) v.col(0) = -v.col(0);
  return v;
}

// world_position: the right world point (through the inverse view-projection as handed, and
// through the view position and the inverse view, in double and float) holds; the camera's own
// view-projection and the view matrix where its inverse belongs are caught; and the view
// position judged as a world one (the view left out) is caught: the property alone rejects an
// answer in the wrong space.
TEST(DepthReconstruction, worldPositionHoldsEitherRouteAndCatchesItsMistakes) {
  for (Convention k : kConventions) {
    for (bool mirrored : {false, true}) {
      const Matrix4<double> m = perspective(k);
      const Vector4<double> c = tilted_plane();
      const Matrix4<double> mo = oblique_of(m, c, k);
      auto sample =
          oblique::oracle::depth_sample(mo, m, k, DepthBuffer::fixed24, kept_centre(m, c, k));
      ASSERT_TRUE(sample.has_value());
      sample->view = far_pass_view(mirrored);
      const Matrix4<double> to_world = sample->view.inverse();
      const Vector3<double> view_point =
          oblique::view_position(mo, sample->ndc_x, sample->ndc_y, sample->depth, k);
      // The inverse view-projection as an engine hands it (computed in double).
      const Vector4<double> clip(sample->ndc_x, sample->ndc_y, oblique::ndc_depth(sample->depth, k),
                                 1);
      const Vector4<double> h = (mo * sample->view).inverse() * clip;
      const Vector3<double> through_vp = h.head<3>() / h.w();
      const Vector3<double> through_view = (to_world * view_point.homogeneous()).head<3>();
      for (const Vector3<double>& right : {through_vp, through_view}) {
        const ConsumerFinding f = oblique::oracle::judge_world_position(*sample, right);
        EXPECT_TRUE(f.judged && f.holds) << describe(f);
      }
      const Vector3<double> original =
          oblique::world_position(m, sample->view, sample->ndc_x, sample->ndc_y, sample->depth, k);
      const Vector3<double> carried_by_view = (sample->view * view_point.homogeneous()).head<3>();
      for (const Vector3<double>& wrong : {original, carried_by_view, view_point}) {
        const ConsumerFinding f = oblique::oracle::judge_world_position(*sample, wrong);
        EXPECT_TRUE(f.judged);
        EXPECT_FALSE(f.holds) << describe(f);
      }
      // In float, from the float inputs: the same verdicts.
      oblique::oracle::DepthSample<float> fs;
      fs.projection = mo.cast<float>();
      fs.original = m.cast<float>();
      fs.view = sample->view.cast<float>();
      fs.convention = k;
      fs.buffer = sample->buffer;
      fs.ndc_x = static_cast<float>(sample->ndc_x);
      fs.ndc_y = static_cast<float>(sample->ndc_y);
      fs.depth = static_cast<float>(sample->depth);
      fs.stored = sample->stored;
      const Vector3<float> right_float =
          oblique::world_position(fs.projection, fs.view, fs.ndc_x, fs.ndc_y, fs.depth, k);
      const ConsumerFinding held = oblique::oracle::judge_world_position(
          fs, right_float, oblique::oracle::ConsumerArithmetic::gpu);
      EXPECT_TRUE(held.judged && held.holds) << describe(held);
      const Vector3<float> wrong_float =
          oblique::world_position(fs.original, fs.view, fs.ndc_x, fs.ndc_y, fs.depth, k);
      const ConsumerFinding caught = oblique::oracle::judge_world_position(fs, wrong_float);
      EXPECT_FALSE(caught.holds) << describe(caught);
    }
  }
}

// The textbook linearisation n f / (f - d (f - n)) ([0, 1] depth) with the camera's n and f, used
// on a depth written through M': caught, and the error it makes is a large part of the depth.
TEST(DepthReconstruction, textbookLinearisationOnAnObliqueMatrixIsCaughtWithItsError) {
  const double n = 0.5, f = 200;
  const Convention k = Convention::zero_one;
  const Matrix4<double> m = perspective(k, n, f);
  const Vector4<double> c = tilted_plane();
  const Matrix4<double> mo = oblique_of(m, c, k);
  const Vector4<double> point = kept_centre(m, c, k);
  const auto sample = oblique::oracle::depth_sample(mo, m, k, DepthBuffer::fixed24, point);
  ASSERT_TRUE(sample.has_value());
  const double textbook = n * f / (f - sample->depth * (f - n));
  const ConsumerFinding caught = oblique::oracle::judge_linear_depth(*sample, textbook);
  EXPECT_FALSE(caught.holds) << describe(caught);
  const double true_depth = -point.z();
  const double relative_error = std::fabs(textbook - true_depth) / true_depth;
  EXPECT_GT(relative_error, 0.1) << "textbook " << textbook << ", true " << true_depth;
  std::cout << "textbook linearisation on M': " << textbook << " for a point at depth "
            << true_depth << " (" << 100 * relative_error << "% off; " << describe(caught) << ")\n";
  // The same formula on the unmodified matrix's depth is right: the property accepts it there.
  const auto plain = oblique::oracle::depth_sample(m, m, k, DepthBuffer::fixed24, point);
  ASSERT_TRUE(plain.has_value());
  EXPECT_TRUE(
      oblique::oracle::judge_linear_depth(*plain, n * f / (f - plain->depth * (f - n))).holds);
}

// A camera whose projection turns its axis off z (the rotated family) has no linear depth along
// z: the sign of z along its axis is rounding noise (found by a long run).
TEST(DepthReconstruction, linearDepthIsNotJudgedOffTheZAxis) {
  const Convention k = Convention::gl;
  Matrix4<double> turn = Matrix4<double>::Identity();
  turn.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Vector3<double>::UnitY()).toRotationMatrix();
  const Matrix4<double> m = perspective(k) * turn;
  const Vector4<double> c =
      oblique::plane_in_camera<double>(turn.transpose(), tilted_plane());  // turn^T C
  const Matrix4<double> mo = oblique_of(m, c, k);
  const auto sample =
      oblique::oracle::depth_sample(mo, m, k, DepthBuffer::float32, kept_centre(m, c, k));
  ASSERT_TRUE(sample.has_value());
  EXPECT_FALSE(oblique::oracle::judge_linear_depth(*sample, 1.0).judged);
  EXPECT_TRUE(
      oblique::oracle::judge_view_position(
          *sample, oblique::view_position(mo, sample->ndc_x, sample->ndc_y, sample->depth, k))
          .holds);
}

// A clip plane 2e-6 from the eye, in float (found by the float consumer suite, seed 11): M'_34 is
// -7.7e-7, and a solve in float can reach w = 0 anywhere along the pixel's ray, so it cannot place
// the point on it, nor say on which side of the eye it is. Judged, not left out, by what float
// can reach: the ray's line. The answer's distance is not judged here (it is where w is
// determined: rightAnswersHoldAndTheOriginalMatrixIsCaught).
TEST(DepthReconstruction, aPointFloatCannotPlaceIsJudgedByItsRay) {
  const Convention k = Convention::zero_one;
  Matrix4<float> m;
  m << -0.22222221f, -0.0f, 0.25000003f, -0.0f, -0.0f, -0.5f, -1.0f, -0.0f, 0.0f, 0.0f, -1.0000004f,
      -1.3750004e-05f, 0.0f, 0.0f, -1.0f, 0.0f;
  const Vector4<float> c(-0.5f, -0.5f, 0.25f, -1.9642875e-06f);
  const auto result = oblique::apply<float>(m, c, k);
  ASSERT_EQ(result.status, oblique::Status::ok);
  const Matrix4<float>& mo = result.projection;
  const Vector4<float> point(-136.18764f, 96.84452f, -24.211132f, 1.0f);
  const auto sample = oblique::oracle::depth_sample(mo, m, k, DepthBuffer::fixed24, point);
  ASSERT_TRUE(sample.has_value());
  auto judge = [&](const Vector3<float>& answer) {
    return oblique::oracle::judge_view_position(*sample, answer);
  };
  const float inf = std::numeric_limits<float>::infinity();
  const ConsumerFinding at_infinity = judge(Vector3<float>(inf, inf, inf));
  ASSERT_TRUE(at_infinity.judged) << at_infinity.detail;
  EXPECT_TRUE(at_infinity.holds) << describe(at_infinity);
  EXPECT_NE(at_infinity.detail.find("can reach w = 0"), std::string::npos) << at_infinity.detail;
  // A finite coordinate beside a non-finite one is no divide by w^ = 0.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const ConsumerFinding mixed = judge(Vector3<float>(nan, 0.0f, 0.0f));
  EXPECT_TRUE(mixed.judged && !mixed.holds) << describe(mixed);
  for (const float along : {1.0f, 4.0f, 0.25f}) {
    const ConsumerFinding on_ray = judge(along * point.head<3>());
    EXPECT_TRUE(on_ray.judged && on_ray.holds) << along << ": " << describe(on_ray);
  }
  // Off the ray: violated, in x or in y.
  for (const Vector3<float>& off : {Vector3<float>(-point.x(), point.y(), point.z()),
                                    Vector3<float>(point.x(), 1.01f * point.y(), point.z())}) {
    const ConsumerFinding f = judge(off);
    EXPECT_TRUE(f.judged && !f.holds) << describe(f);
  }
  EXPECT_TRUE(oblique::oracle::judge_linear_depth(*sample, inf).holds);
  EXPECT_TRUE(oblique::oracle::judge_linear_depth(*sample, -point.z()).holds);
}

// A stiff orthographic case in double (found by fuzz_consumers, 2026-12-06): C = (0, 1, -5e-324,
// -5e-324) makes row 3 of M' (0, -1e6, 4.9e-318, 1), so one fixed24 depth step is 1e310 in view
// z, beyond double's range: the points a stored depth stands for reach past the largest double,
// a solve in double overflows there, and NaN or an infinity is what it can give. A finite answer
// is still judged by the segment.
TEST(DepthReconstruction, aSegmentBeyondTheTypesRangeAllowsAnOverflow) {
  const Convention k = Convention::reversed_z;
  Matrix4<double> m;
  m << 0x1.47ae147ae147bp-2, 0, 0, 0x1.147ae147ae148p+0, 0, -0x1.e848p+20, 0, 1, 0, 0, -0x1p-3,
      -0.0, 0, 0, 0, 1;
  const Vector4<double> c(0, 1, -0x0.0000000000001p-1022, -0x0.0000000000001p-1022);
  const auto result = oblique::apply<double>(m, c, k);
  ASSERT_EQ(result.status, oblique::Status::ok);
  const Vector4<double> point(-2.5910202655485675, 4.53529000698812e-07, -3.7756813417190775, 1);
  const auto sample =
      oblique::oracle::depth_sample(result.projection, m, k, DepthBuffer::fixed24, point);
  ASSERT_TRUE(sample.has_value());
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ConsumerFinding overflow =
      oblique::oracle::judge_view_position(*sample, Vector3<double>(nan, nan, -inf));
  ASSERT_TRUE(overflow.judged) << overflow.detail;
  EXPECT_TRUE(overflow.holds) << describe(overflow);
  EXPECT_NE(overflow.detail.find("beyond the largest finite"), std::string::npos)
      << overflow.detail;
  const ConsumerFinding off_ray = oblique::oracle::judge_view_position(
      *sample, Vector3<double>(-point.x() + 1, point.y(), point.z()));
  EXPECT_TRUE(off_ray.judged && !off_ray.holds) << describe(off_ray);
}

// Where float places the point, an infinity is not one of the answers it can give.
TEST(DepthReconstruction, infinityIsViolatedWhereFloatPlacesThePoint) {
  for (Convention k : kConventions) {
    const Matrix4<float> m = perspective(k).cast<float>();
    const Vector4<float> c = tilted_plane().cast<float>();
    const auto result = oblique::apply<float>(m, c, k);
    ASSERT_EQ(result.status, oblique::Status::ok);
    const auto sample = oblique::oracle::depth_sample(
        result.projection, m, k, DepthBuffer::float32,
        Vector4<float>(kept_centre(perspective(k), tilted_plane(), k).cast<float>()));
    ASSERT_TRUE(sample.has_value());
    const float inf = std::numeric_limits<float>::infinity();
    const ConsumerFinding f =
        oblique::oracle::judge_view_position(*sample, Vector3<float>(inf, inf, inf));
    EXPECT_TRUE(f.judged && !f.holds) << describe(f);
    const ConsumerFinding right = oblique::oracle::judge_view_position(
        *sample,
        oblique::view_position(result.projection, sample->ndc_x, sample->ndc_y, sample->depth, k));
    EXPECT_TRUE(right.judged && right.holds) << describe(right);
  }
}

TEST(CullingPlanes, rightPlanesHoldInEveryConvention) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    const auto findings =
        oblique::oracle::judge_culling_planes(m, c, k, mo, oblique::frustum_planes(mo, k));
    for (const auto& f : findings) EXPECT_TRUE(f.judged && f.holds) << describe(f);
    // Normalised planes are the same half-spaces.
    auto planes = oblique::frustum_planes(mo, k);
    for (Vector4<double>* p : {&planes.left, &planes.right, &planes.bottom, &planes.top,
                               &planes.near_plane, &planes.far_plane})
      *p /= p->head<3>().norm();
    for (const auto& f : oblique::oracle::judge_culling_planes(m, c, k, mo, planes))
      EXPECT_TRUE(f.holds) << describe(f);
  }
}

// Found by a long run: a float matrix whose third and fourth rows nearly agree puts the far
// plane beyond infinity in exact arithmetic (far corners with w < 0), so the "volume" wraps
// through infinity and a vertex where C crosses its edge lies outside every plane of it. Such a
// case has no kept region to judge culling by; the near plane is still judged.
TEST(CullingPlanes, aVolumeWithCornersBehindTheEyeIsNotJudged) {
  Matrix4<float> m;
  m << 0.13278781f, -0.15411554f, 0.089434415f, 0, 0.34675997f, 0.09754516f, -0.34675997f, 0,
      -0.4024549f, -0.69352f, -0.5975452f, -2.2500002f, -0.40245485f, -0.69351995f, -0.59754515f, 0;
  const Vector4<float> c(0, 0, -1, -1.1771363f);
  const auto result = oblique::apply<float>(m, c, Convention::gl);
  ASSERT_EQ(result.status, oblique::Status::ok);
  const auto findings = oblique::oracle::judge_culling_planes(
      m, c, Convention::gl, result.projection,
      oblique::frustum_planes(result.projection, Convention::gl));
  EXPECT_FALSE(find(findings, ConsumerCheck::culling_keeps_visible).judged);
  const ConsumerFinding& near = find(findings, ConsumerCheck::culling_near_is_c);
  EXPECT_TRUE(near.judged && near.holds) << describe(near);
}

TEST(CullingPlanes, nearIsCAloneRejectsGlRowsOnZeroOneAndReversedZ) {
  for (Convention k : {Convention::zero_one, Convention::reversed_z}) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    auto planes = oblique::frustum_planes(mo, k);
    planes.near_plane = oblique::near_plane(mo, Convention::gl);
    const auto findings = oblique::oracle::judge_culling_planes(m, c, k, mo, planes);
    EXPECT_FALSE(find(findings, ConsumerCheck::culling_near_is_c).holds);
    EXPECT_TRUE(find(findings, ConsumerCheck::culling_keeps_visible).holds)
        << describe(find(findings, ConsumerCheck::culling_keeps_visible));
  }
}

TEST(CullingPlanes, keepsVisibleAloneRejectsAFarPlaneThatCullsTheKeptRegion) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    auto planes = oblique::frustum_planes(mo, k);
    // The far plane of the unmodified matrix moved in by a tenth: it cuts the kept region.
    planes.far_plane = oblique::far_plane(m, k);
    planes.far_plane.w() *= 0.9;
    const auto findings = oblique::oracle::judge_culling_planes(m, c, k, mo, planes);
    EXPECT_FALSE(find(findings, ConsumerCheck::culling_keeps_visible).holds) << convention_name(k);
    EXPECT_TRUE(find(findings, ConsumerCheck::culling_near_is_c).holds);
  }
}

// Hostile answers: a NaN or an infinity in any plane is judged "not finite", never converted to
// a rational first (GMP ended the process with SIGFPE on the near plane's NaN).
// Non-finite planes are judged by what they cull (an engine culls x when P . x < 0), never
// converted: a near plane that is not finite is never C; a NaN plane culls nothing (NaN < 0 is
// false), conservative; +-inf in an entry culls the kept region's vertices where that term is
// -inf, and then violates.
TEST(CullingPlanes, nonFinitePlanesAreJudgedByWhatTheyCullNotACrash) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
      auto planes = oblique::frustum_planes(mo, k);
      planes.near_plane(1) = bad;  // the kept region has vertices with y < 0 and y > 0
      const auto near_only = oblique::oracle::judge_culling_planes(m, c, k, mo, planes);
      EXPECT_FALSE(find(near_only, ConsumerCheck::culling_near_is_c).holds);
      const ConsumerFinding keeps = find(near_only, ConsumerCheck::culling_keeps_visible);
      EXPECT_TRUE(keeps.judged);
      EXPECT_EQ(keeps.holds, std::isnan(bad)) << describe(keeps);
      for (Vector4<double>* p :
           {&planes.left, &planes.right, &planes.bottom, &planes.top, &planes.far_plane})
        p->fill(bad);
      for (const auto& f : oblique::oracle::judge_culling_planes(m, c, k, mo, planes)) {
        EXPECT_TRUE(f.judged) << describe(f);
        EXPECT_EQ(f.holds, f.check == ConsumerCheck::culling_keeps_visible && std::isnan(bad))
            << describe(f);
      }
    }
  }
}

// The false alarm of issue 44: a head-on clip plane whose far plane an engine's float
// normalisation takes to (0, 0, 0, inf) or NaN (the far plane's normal rounds to zero). Both cull
// nothing: culling_keeps_visible holds; (0, 0, 0, -inf), which culls everything, violates.
TEST(CullingPlanes, aFarPlaneAtInfinityThatCullsNothingHolds) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c(0, 0, -1, -2);  // head-on
    const Matrix4<double> mo = oblique_of(m, c, k);
    for (const double w : {HUGE_VAL, std::nan(""), -HUGE_VAL}) {
      auto planes = oblique::frustum_planes(mo, k);
      planes.far_plane = Vector4<double>(0, 0, 0, w);
      const ConsumerFinding keeps = find(oblique::oracle::judge_culling_planes(m, c, k, mo, planes),
                                         ConsumerCheck::culling_keeps_visible);
      EXPECT_TRUE(keeps.judged) << describe(keeps);
      EXPECT_EQ(keeps.holds, !(w < 0)) << convention_name(k) << " " << describe(keeps);
    }
  }
}

TEST(Exact, aNonFiniteNumberIsRefusedNotConverted) {
  EXPECT_THROW(oblique::oracle::exact::to_rational(std::nan("")), std::domain_error);
  EXPECT_THROW(oblique::oracle::exact::to_rational(HUGE_VALF), std::domain_error);
  EXPECT_THROW(oblique::oracle::exact::to_rational(-HUGE_VALL), std::domain_error);
  EXPECT_EQ(oblique::oracle::exact::to_rational(0.5), oblique::oracle::exact::Rational(1, 2));
}

struct PassCase {
  Matrix4<double> view = Matrix4<double>::Identity();
  Vector4<double> plane;
  Matrix4<double> pass_view;
  std::vector<Vector4<double>> on_plane;
  Vector4<double> front;
};

/// A mirror 6 units ahead of a camera at (1, 2, 3), turned 30 degrees.
PassCase mirror_case() {
  PassCase p;
  const double a = M_PI / 6;
  Matrix4<double> rotation = Matrix4<double>::Identity();
  rotation(0, 0) = std::cos(a);
  rotation(0, 2) = std::sin(a);
  rotation(2, 0) = -std::sin(a);
  rotation(2, 2) = std::cos(a);
  Matrix4<double> translation = Matrix4<double>::Identity();
  translation.block<3, 1>(0, 3) = Vector3<double>(-1, -2, -3);
  p.view = rotation * translation;
  p.plane = oblique::plane_from_normal_and_point<double>(Vector3<double>(0.2, 0.1, 1),
                                                         Vector3<double>(1, 2, -3));
  p.pass_view = oblique::mirror_view(p.view, p.plane);
  const Vector3<double> n = p.plane.head<3>();
  const Vector3<double> base = -p.plane.w() * n / n.squaredNorm();
  const Vector3<double> t1 = n.unitOrthogonal(), t2 = n.cross(t1).normalized();
  for (double s : {-3.0, 0.0, 5.0})
    p.on_plane.push_back((Vector4<double>() << base + s * t1 + (2 - s) * t2, 1).finished());
  p.front << base + 4 * n.normalized(), 1;
  return p;
}

TEST(PassCamera, rightPlaneHoldsAndEachPropertyAloneRejectsItsMistake) {
  const PassCase p = mirror_case();
  const Vector4<double> right = oblique::plane_in_camera(p.pass_view, p.plane);
  EXPECT_LT(right.w(), 0) << "the mirror's camera is behind its plane";
  for (const auto& f :
       oblique::oracle::judge_camera_plane(p.pass_view, p.plane, p.on_plane, p.front, right))
    EXPECT_TRUE(f.holds) << describe(f);
  const Vector4<double> unit = right / right.head<3>().norm();
  for (const auto& f :
       oblique::oracle::judge_camera_plane(p.pass_view, p.plane, p.on_plane, p.front, unit))
    EXPECT_TRUE(f.holds) << describe(f);
  // Wrong side: on the surface, but keeping the mirror's back.
  auto findings = oblique::oracle::judge_camera_plane(p.pass_view, p.plane, p.on_plane, p.front,
                                                      Vector4<double>(-right));
  EXPECT_TRUE(find(findings, ConsumerCheck::plane_on_surface).holds);
  EXPECT_FALSE(find(findings, ConsumerCheck::plane_kept_side).holds);
  // Wrong space: the normal rotated, the distance kept from world space; on the right side.
  Vector4<double> no_translation;
  no_translation << p.pass_view.topLeftCorner<3, 3>() * p.plane.head<3>(), p.plane.w();
  findings = oblique::oracle::judge_camera_plane(p.pass_view, p.plane, p.on_plane, p.front,
                                                 no_translation);
  EXPECT_FALSE(find(findings, ConsumerCheck::plane_on_surface).holds);
  // The main view's plane (the reflection forgotten): points of the mirror still land on it, but
  // it keeps the wrong side.
  findings = oblique::oracle::judge_camera_plane(p.pass_view, p.plane, p.on_plane, p.front,
                                                 oblique::plane_in_camera(p.view, p.plane));
  EXPECT_TRUE(find(findings, ConsumerCheck::plane_on_surface).holds);
  EXPECT_FALSE(find(findings, ConsumerCheck::plane_kept_side).holds);
}

TEST(PassCamera, mirrorAndPortalViews) {
  const PassCase p = mirror_case();
  EXPECT_TRUE(oblique::oracle::judge_mirror_view(p.view, p.plane, p.pass_view).holds);
  EXPECT_LT(p.pass_view.block(0, 0, 3, 3).determinant(), 0) << "a mirror flips the winding";
  // The main view: not mirrored.
  EXPECT_FALSE(oblique::oracle::judge_mirror_view(p.view, p.plane, p.view).holds);
  // A portal: the map carries the linked portal's front to behind this one.
  Matrix4<double> frame = Matrix4<double>::Identity(), linked = Matrix4<double>::Identity();
  frame.block<3, 1>(0, 3) = Vector3<double>(0, 0, -5);
  linked.block<3, 3>(0, 0) << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // turned a quarter about up
  linked.block<3, 1>(0, 3) = Vector3<double>(20, 0, 0);
  const Matrix4<double> right = oblique::portal_view(p.view, frame, linked);
  EXPECT_TRUE(oblique::oracle::judge_portal_view(p.view, frame, linked, right).holds);
  const Matrix4<double> no_turn = p.view * frame * linked.inverse();
  EXPECT_FALSE(oblique::oracle::judge_portal_view(p.view, frame, linked, no_turn).holds);
  // In front of the linked portal is behind this one.
  const Vector4<double> ahead_of_linked = linked * Vector4<double>(0, 0, 3, 1);
  const Vector4<double> seen = oblique::portal_map(frame, linked) * ahead_of_linked;
  EXPECT_NEAR(seen.z(), -8, 1e-12);
}

// The mirror pass built as a proper camera (issue 44's false alarm): diag(-1, 1, 1, 1) view R,
// the horizontal flip done in the projection or the texture lookup. Named as that design when it
// is not declared (and the declared design answered the other way is named too); declared, it
// holds; a broken mirror is neither.
TEST(PassCamera, theProperCameraMirrorDesignIsNamedAndHoldsWhenDeclared) {
  using oblique::oracle::judge_mirror_view;
  using oblique::oracle::MirrorDesign;
  const PassCase p = mirror_case();
  Matrix4<double> proper = p.pass_view;
  proper.row(0) *= -1;
  EXPECT_GT(proper.block(0, 0, 3, 3).determinant(), 0);
  const ConsumerFinding undeclared = judge_mirror_view(p.view, p.plane, proper);
  EXPECT_FALSE(undeclared.holds);
  EXPECT_NE(undeclared.detail.find("the answer is the proper_camera design"), std::string::npos)
      << undeclared.detail;
  const ConsumerFinding declared =
      judge_mirror_view(p.view, p.plane, proper, MirrorDesign::proper_camera);
  EXPECT_TRUE(declared.holds) << describe(declared);
  const ConsumerFinding other =
      judge_mirror_view(p.view, p.plane, p.pass_view, MirrorDesign::proper_camera);
  EXPECT_FALSE(other.holds);
  EXPECT_NE(other.detail.find("the answer is the reflected_view design"), std::string::npos)
      << other.detail;
  // A broken mirror (the main view, or the flip on y) is named as neither design.
  Matrix4<double> y_flip = p.pass_view;
  y_flip.row(1) *= -1;
  for (const Matrix4<double>& wrong : {p.view, y_flip}) {
    for (MirrorDesign d : {MirrorDesign::reflected_view, MirrorDesign::proper_camera}) {
      const ConsumerFinding f = judge_mirror_view(p.view, p.plane, wrong, d);
      EXPECT_FALSE(f.holds);
      EXPECT_EQ(f.detail.find("design"), std::string::npos) << f.detail;
    }
  }
}

// What a report draws for a pass camera's finding: the cameras, the planes and the points, where
// they are. A mirror 5 units ahead of an eye at the origin: the mirror pass's eye is 10 units
// ahead, looking back.
TEST(PassCamera, violatedFindingsCarryWhatTheirPicturesDraw) {
  const Matrix4<double> view = Matrix4<double>::Identity();
  const Vector4<double> mirror(0, 0, 1, 5);  // z = -5, its front toward the eye
  const ConsumerFinding wrong = oblique::oracle::judge_mirror_view(view, mirror, view);
  ASSERT_FALSE(wrong.holds);
  EXPECT_EQ(wrong.drawn_space, "world space");
  ASSERT_EQ(wrong.drawn.size(), 4u);
  ASSERT_EQ(wrong.drawn[1].points.size(), 1u);
  EXPECT_NEAR((wrong.drawn[1].points[0] - Vector3<double>(0, 0, -10)).norm(), 0, 1e-12)
      << "the mirror pass's eye, as it should be";
  EXPECT_NEAR((wrong.drawn[2].points[0] - Vector3<double>(0, 0, 0)).norm(), 0, 1e-12)
      << "the eye as answered";
  // The reflected camera looks back along +z, toward the mirror.
  const Vector3<double> look = wrong.drawn[1].lines[0].second - wrong.drawn[1].lines[0].first;
  EXPECT_GT(look.z(), 0);
  for (const auto& [a, b] : wrong.drawn[3].lines) {  // the mirror's square (and its normal)
    EXPECT_NEAR(a.z(), -5, 1e-12);
    EXPECT_GE(b.z(), -5 - 1e-12);
  }
  EXPECT_TRUE(oblique::oracle::judge_mirror_view(view, mirror, oblique::mirror_view(view, mirror))
                  .drawn.empty())
      << "a finding that holds draws nothing";

  const PassCase p = mirror_case();
  const auto findings = oblique::oracle::judge_camera_plane(
      p.pass_view, p.plane, p.on_plane, p.front,
      Vector4<double>(-oblique::plane_in_camera(p.pass_view, p.plane)));
  const ConsumerFinding& side = find(findings, ConsumerCheck::plane_kept_side);
  ASSERT_FALSE(side.holds);
  EXPECT_EQ(side.drawn_space, "the pass camera's space");
  ASSERT_EQ(side.drawn.size(), 5u);
  // The square of the plane as it should be lies in it, and its normal points to the front.
  const Vector4<double> should = oblique::plane_in_camera(p.pass_view, p.plane);
  const auto& square = side.drawn[1].lines;
  ASSERT_EQ(square.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(should.head<3>().dot(square[i].first) + should.w(), 0,
                1e-9 * should.head<3>().norm() * (1 + square[i].first.norm()));
  EXPECT_GT(should.head<3>().dot(square[4].second) + should.w(), 0);
  EXPECT_TRUE(find(findings, ConsumerCheck::plane_on_surface).drawn.empty());
}

TEST(Corners, keptRegionVerticesHoldAndTheObliqueMatrixCornersAreCaught) {
  // Where C cuts an edge of the volume behind the eye (found by the property suite).
  Matrix4<double> m;
  m << 2, 0, 0, 0, 0, -2, 0, 0, 0, 0, -3, -4, 0, 0, -1, 0;
  const Vector4<double> c(-1, 0, 0.25, -2.0 / 15);
  const Convention k = Convention::gl;
  const Matrix4<double> mo = oblique_of(m, c, k);
  std::vector<Vector3<double>> kept, naive;
  for (const auto& v : oblique::kept_region_vertices(m, oblique::near_plane(mo, k), k))
    kept.push_back(v.head<3>());
  int behind = 0;
  for (const auto& v : oblique::view_volume_corners(mo, k)) {
    naive.push_back(v.head<3>() / v.w());
    behind += v.w() < 0;
  }
  EXPECT_GT(behind, 0) << "the case has corners behind the eye";
  const ConsumerFinding right = oblique::oracle::judge_corners(m, c, k, mo, kept);
  EXPECT_TRUE(right.holds) << describe(right);
  EXPECT_NEAR(right.depth_waste, 1, 1e-9);
  const ConsumerFinding wrong = oblique::oracle::judge_corners(m, c, k, mo, naive);
  EXPECT_FALSE(wrong.holds) << describe(wrong);
  // The original volume's corners bound the kept region too, with depth to spare.
  std::vector<Vector3<double>> original;
  for (const auto& v : oblique::view_volume_corners(m, k)) original.push_back(v.head<3>() / v.w());
  const ConsumerFinding loose = oblique::oracle::judge_corners(m, c, k, mo, original);
  EXPECT_TRUE(loose.holds) << describe(loose);
  EXPECT_GE(loose.depth_waste, 1);
}

TEST(Corners, obliqueMatrixCornersBoundWhereAllAreInFront) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    // A plane parallel to the near plane: M' keeps a far plane parallel to it, and every corner
    // is in front of the eye. (Tilted by as little as (0.05, 0.05, -1), three far corners of
    // M' already lie behind it: corners_of_oblique_matrix's mistake.)
    const Vector4<double> c = oblique::plane_from_normal_and_point<double>(
        Vector3<double>(0, 0, -1), Vector3<double>(0, 0, -2));
    const Matrix4<double> mo = oblique_of(m, c, k);
    std::vector<Vector3<double>> corners;
    bool all_in_front = true;
    for (const auto& v : oblique::view_volume_corners(mo, k)) {
      corners.push_back(v.head<3>() / v.w());
      all_in_front = all_in_front && v.w() > 0;
    }
    ASSERT_TRUE(all_in_front);
    const ConsumerFinding f = oblique::oracle::judge_corners(m, c, k, mo, corners);
    EXPECT_TRUE(f.holds) << describe(f);
    EXPECT_NEAR(f.depth_waste, 1, 1e-9) << "for a parallel plane M' volume is the kept region";
    // The near face's corners and the eye: the far part is lost.
    std::vector<Vector3<double>> near_and_eye;
    const std::size_t first_near = k == Convention::reversed_z ? 4 : 0;
    for (std::size_t i = first_near; i < first_near + 4; ++i) near_and_eye.push_back(corners[i]);
    near_and_eye.push_back(Vector3<double>::Zero());
    corners = near_and_eye;
    EXPECT_FALSE(oblique::oracle::judge_corners(m, c, k, mo, corners).holds);
  }
}

// Corners on one line bound no solid: judged by each kept vertex's distance to their segment
// against the bound. Two far-apart right corners (a diagonal of the kept region) leave the other
// vertices far off it: violated. Where a solve in T collapses the right corners onto a line (M
// singular in T, the bound as large) they hold: the fuzz_consumers regression
// corners_collapsed_onto_a_line, which the judge once failed whatever the bound.
TEST(Corners, cornersOnOneLineAreJudgedByTheirDistanceToIt) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    std::vector<Vector3<double>> kept;
    for (const auto& v : oblique::kept_region_vertices(m, oblique::near_plane(mo, k), k))
      kept.push_back(v.head<3>());
    ASSERT_GE(kept.size(), 4u);
    std::size_t a = 0, b = 1;  // the two vertices farthest apart
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (std::size_t j = i + 1; j < kept.size(); ++j)
        if ((kept[i] - kept[j]).norm() > (kept[a] - kept[b]).norm()) a = i, b = j;
    const std::vector<Vector3<double>> diagonal = {kept[a], kept[b], (kept[a] + kept[b]) / 2};
    const ConsumerFinding f = oblique::oracle::judge_corners(m, c, k, mo, diagonal);
    EXPECT_FALSE(f.holds) << describe(f);
    EXPECT_NE(f.detail.find("lie on one line"), std::string::npos) << f.detail;
    EXPECT_GT(f.ratio, 1);
    EXPECT_FALSE(oblique::oracle::judge_corners(m, c, k, mo, {kept[a]}).holds);
    EXPECT_FALSE(oblique::oracle::judge_corners(m, c, k, mo, {}).holds);
  }
}

// Corners far from the right ones are judged by the bound of the right ones: a bound taken from
// the answer itself grew past w = 0 for corners 1e300 away, and the round was left out, not failed.
TEST(Corners, farAwayCornersAreJudgedByTheRightOnesBound) {
  for (Convention k : kConventions) {
    const Matrix4<double> m = perspective(k);
    const Vector4<double> c = tilted_plane();
    const Matrix4<double> mo = oblique_of(m, c, k);
    std::vector<Vector3<double>> kept, far_away, scaled_up;
    for (const auto& v : oblique::kept_region_vertices(m, oblique::near_plane(mo, k), k))
      kept.push_back(v.head<3>());
    for (int i = 0; i < 8; ++i)
      far_away.push_back(Vector3<double>(i & 1 ? 1.1e300 : 1e300, i & 2 ? 1.1e300 : 1e300,
                                         i & 4 ? 1.1e300 : 1e300));
    const ConsumerFinding far = oblique::oracle::judge_corners(m, c, k, mo, far_away);
    EXPECT_TRUE(far.judged && !far.holds) << describe(far);
    // The right corners, and a box around them 1e300 wide, still hold: conservative, not wrong.
    const ConsumerFinding right = oblique::oracle::judge_corners(m, c, k, mo, kept);
    EXPECT_TRUE(right.judged && right.holds) << describe(right);
    for (int i = 0; i < 8; ++i)
      scaled_up.push_back(
          Vector3<double>(i & 1 ? 1e300 : -1e300, i & 2 ? 1e300 : -1e300, i & 4 ? 1e300 : -1e300));
    const ConsumerFinding big = oblique::oracle::judge_corners(m, c, k, mo, scaled_up);
    EXPECT_TRUE(big.judged && big.holds) << describe(big);
  }
}

TEST(Corners, aPointCloudIsRefusedNotHung) {
  const Convention k = Convention::gl;
  const Matrix4<double> m = perspective(k);
  const Vector4<double> c = tilted_plane();
  const Matrix4<double> mo = oblique_of(m, c, k);
  std::vector<Vector3<double>> cloud;
  for (int i = 0; i < 1000; ++i) cloud.emplace_back(i, -i, -1 - i);
  const ConsumerFinding f = oblique::oracle::judge_corners(m, c, k, mo, cloud);
  EXPECT_FALSE(f.judged);
  EXPECT_NE(f.detail.find("1000 distinct points"), std::string::npos) << f.detail;
}

// Consumers::accepts: a refused camera's round asks none of the functions that take its
// projection (each finding left out, "refused by accepts"), and still asks the others.
TEST(ConsumerRound, aCameraAcceptsRefusesIsNotAskedOfTheProjectionsFunctions) {
  auto consumers = oblique::oracle::reference_consumers<double>();
  consumers.name = "upright_only";
  int asked_depth = 0;
  const auto depth = consumers.linear_depth;
  consumers.linear_depth = [&](const oblique::oracle::DepthSample<double>& s) {
    ++asked_depth;
    return depth(s);
  };
  const Convention k = Convention::gl;
  const Matrix4<double> m = perspective(k);
  const Vector4<double> c = tilted_plane();
  int picked = 0;
  const oblique::oracle::Pick pick = [&](int lo, int hi) { return lo + (picked++ % (hi - lo)); };
  for (const bool refuse : {true, false}) {
    consumers.accepts = [refuse](Convention, const Matrix4<double>&) { return !refuse; };
    std::map<ConsumerCheck, ConsumerFinding> seen;
    asked_depth = 0;
    oblique::oracle::consumer_round<double>(
        m, c, k, consumers, pick,
        [&](const ConsumerFinding& f, const std::string&, bool) { seen[f.check] = f; });
    for (ConsumerCheck check :
         {ConsumerCheck::view_position, ConsumerCheck::linear_depth,
          ConsumerCheck::culling_keeps_visible, ConsumerCheck::culling_near_is_c,
          ConsumerCheck::corners_contain_kept}) {
      ASSERT_TRUE(seen.count(check)) << consumer_check_name(check);
      const bool refused =
          !seen[check].judged && seen[check].detail == "refused by accepts (upright_only)";
      EXPECT_EQ(refused, refuse) << consumer_check_name(check) << ": " << seen[check].detail;
    }
    if (refuse) {
      EXPECT_EQ(asked_depth, 0);
    }
    // The pass-camera functions do not take the projection: asked either way.
    EXPECT_TRUE(seen.count(ConsumerCheck::mirror_view) && seen[ConsumerCheck::mirror_view].judged);
    EXPECT_TRUE(seen.count(ConsumerCheck::plane_on_surface));
  }
}

TEST(ConsumerChecks, namesRoundTrip) {
  for (ConsumerCheck c : oblique::oracle::all_consumer_checks)
    EXPECT_EQ(oblique::oracle::parse_consumer_check(oblique::oracle::consumer_check_name(c)), c);
  EXPECT_FALSE(oblique::oracle::parse_consumer_check("near_plane").has_value());
}

}  // namespace
