// The consumer judges that settle in certified floating-point bounds first (Arithmetic::filtered,
// the default) against the same judges in exact arithmetic throughout: on generated cases of every
// family, convention and precision, and on answers near the bound (the right corners shrunk so
// that a vertex of the kept region lies outside their hull by 0.5 to 3 times the bound; the right
// view position and linear depth moved off the pixel's segment by 2^-e of themselves), both
// must give the same verdict, the same message for a violation and the same ratio up to the
// rounding of the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "oblique/cases/generators.h"
#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/references/frustum_planes.h"
#include "oblique/references/kept_region.h"

namespace oblique::oracle {
namespace {

template <class T>
class FilteredConsumers : public ::testing::Test {};
using Precisions = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(FilteredConsumers, Precisions);

struct Tally {
  long judged = 0, held = 0, violated = 0, not_judged = 0;
};

/// `corners` moved away from (factor > 1) or toward (factor < 1) their mean.
template <class T>
std::vector<Vector3<T>> moved(const std::vector<Vector3<T>>& corners, long double factor) {
  Eigen::Matrix<long double, 3, 1> centre = Eigen::Matrix<long double, 3, 1>::Zero();
  for (const auto& p : corners) centre += p.template cast<long double>();
  centre /= static_cast<long double>(corners.size());
  std::vector<Vector3<T>> out;
  for (const auto& p : corners)
    out.push_back((centre + (p.template cast<long double>() - centre) * factor).template cast<T>());
  return out;
}

template <class T>
void expect_same_corners_verdict(const Matrix4<T>& m, const Vector4<T>& c, Convention k,
                                 const Matrix4<T>& mo, const std::vector<Vector3<T>>& corners,
                                 const std::string& what, Tally& tally) {
  const ConsumerFinding filtered = judge_corners(m, c, k, mo, corners, Arithmetic::filtered);
  const ConsumerFinding exact = judge_corners(m, c, k, mo, corners, Arithmetic::exact);
  const std::string where = what + " (" + describe(exact) + ")";
  ASSERT_EQ(filtered.judged, exact.judged) << where;
  ASSERT_EQ(filtered.holds, exact.holds) << where;
  EXPECT_EQ(filtered.depth_waste, exact.depth_waste) << where;
  if (!exact.judged) {
    ++tally.not_judged;
    EXPECT_EQ(filtered.detail, exact.detail) << where;
    return;
  }
  ++tally.judged;
  if (exact.holds) {
    ++tally.held;
    EXPECT_EQ(filtered.detail, exact.detail) << where;
    // The filtered ratio divides by the bound's range's top rather than the exact bound.
    EXPECT_LE(std::fabs(filtered.ratio - exact.ratio), 1e-12 * std::fmax(1.0, exact.ratio))
        << where;
  } else {
    ++tally.violated;
    EXPECT_EQ(filtered.detail, exact.detail) << where;
    EXPECT_EQ(filtered.ratio, exact.ratio) << where;
  }
}

TYPED_TEST(FilteredConsumers, cornersJudgeAgreesWithTheExactOne) {
  using T = TypeParam;
  const auto gen = cases::valid_case<T>();
  rc::Random random(17301);
  Tally tally;
  // The exact judge takes about 0.1 s a case in float, 0.5 s in double and 9 s in long double.
  const int wanted = std::is_same_v<T, float> ? 24 : std::is_same_v<T, double> ? 12 : 2;
  int cases = 0, probed = 0;
  for (int i = 0; cases < wanted && i < 400; ++i) {
    const cases::Case<T> g = gen(random.split(), i % 101).value();
    const ObliqueResult<T> r = apply<T>(g.matrix, g.plane, g.convention);
    if (r.status != Status::ok) continue;
    std::vector<Vector3<T>> kept;
    bool bounded = true;
    for (const auto& v :
         kept_region_vertices(g.matrix, near_plane(r.projection, g.convention), g.convention)) {
      bounded = bounded && v.w() != 0;
      kept.push_back(v.template head<3>() / v.w());
    }
    if (!bounded || kept.empty()) continue;
    ++cases;
    const std::string what = "case " + std::to_string(i) + ", family " +
                             std::string(cases::family_name(g.family)) + ", convention " +
                             std::string(convention_name(g.convention));
    expect_same_corners_verdict(g.matrix, g.plane, g.convention, r.projection, kept,
                                what + ": the kept region's vertices", tally);
    for (int e : {10, 30, 50, 60}) {
      expect_same_corners_verdict(g.matrix, g.plane, g.convention, r.projection,
                                  moved(kept, 1 + std::ldexp(1.0L, -e)),
                                  what + ": grown by 2^-" + std::to_string(e), tally);
    }
    // Shrunk so that the farthest vertex outside is at chosen multiples of the bound: the ratio
    // of the right corners shrunk by the cube root of T's epsilon (well outside the bound) is
    // about proportional to the shrinking.
    const long double probe = std::ldexp(1.0L, -std::numeric_limits<T>::digits / 3);
    const ConsumerFinding far = judge_corners(g.matrix, g.plane, g.convention, r.projection,
                                              moved(kept, 1 - probe), Arithmetic::exact);
    if (!far.judged || !(far.ratio > 0) || !std::isfinite(far.ratio)) continue;
    ++probed;
    for (long double target : {0.5L, 0.9L, 0.999L, 1.001L, 1.1L, 1.5L, 3.0L}) {
      const long double step = probe * target / static_cast<long double>(far.ratio);
      expect_same_corners_verdict(
          g.matrix, g.plane, g.convention, r.projection, moved(kept, 1 - step),
          what + ": shrunk to about " + std::to_string(double(target)) + " times the bound", tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_EQ(cases, wanted);
  EXPECT_GE(probed, wanted / 2);
  // Both verdicts were compared, on answers that hold and on answers just outside the bound.
  EXPECT_GT(tally.held, 0);
  EXPECT_GT(tally.violated, 0);
}

/// The verdicts the same; for an answer that holds, the ratio (words, from doubles in either path:
/// the exact path rounds the segment once, the certified one carries a few roundings) the same
/// within `ratio_tolerance`.
template <class F>
void expect_same_depth_verdict(const F& judge, const std::string& what, double ratio_tolerance,
                               Tally& tally) {
  const ConsumerFinding filtered = judge(Arithmetic::filtered);
  const ConsumerFinding exact = judge(Arithmetic::exact);
  const std::string where = what + " (" + describe(exact) + ")";
  ASSERT_EQ(filtered.judged, exact.judged) << where;
  ASSERT_EQ(filtered.holds, exact.holds) << where;
  if (!exact.judged) {
    ++tally.not_judged;
    return;
  }
  ++tally.judged;
  if (exact.holds) {
    ++tally.held;
    // The certified path's ratio comes from its enclosures' middles and the box from below.
    EXPECT_LE(std::fabs(filtered.ratio - exact.ratio), ratio_tolerance) << where;
  } else {
    ++tally.violated;
    EXPECT_EQ(filtered.detail, exact.detail) << where;
    EXPECT_EQ(filtered.ratio, exact.ratio) << where;
  }
}

TYPED_TEST(FilteredConsumers, depthJudgesAgreeWithTheExactOnes) {
  using T = TypeParam;
  const auto gen = cases::valid_case<T>();
  rc::Random random(20261206);
  std::mt19937_64 engine(11);
  Tally tally;
  Consumers<T> asking;
  std::vector<DepthSample<T>> samples;
  asking.view_position = [&samples](const DepthSample<T>& s) {
    samples.push_back(s);
    return Vector3<T>::Zero().eval();
  };
  // The world position's samples carry the pass camera's view.
  std::vector<DepthSample<T>> world_samples;
  asking.world_position = [&world_samples](const DepthSample<T>& s) {
    world_samples.push_back(s);
    return Vector3<T>::Zero().eval();
  };
  const Pick pick = [&engine](int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi - 1)(engine);
  };
  const int wanted = std::is_same_v<T, long double> ? 20 : 120;
  for (int i = 0; static_cast<int>(samples.size()) < wanted && i < 4 * wanted; ++i) {
    // Pixel centres and arbitrary positions, the pixel handed as NDC and as a GPU hands it.
    asking.sampling = i % 2 ? Sampling::arbitrary : Sampling::pixels;
    asking.pixel_input = i % 3 ? PixelInput::gpu : PixelInput::ndc;
    const cases::Case<T> g = gen(random.split(), i % 101).value();
    for (const auto& ask :
         consumer_asks<T>(g.matrix, g.plane, g.convention, asking, pick,
                          [](const ConsumerFinding&, const std::string&, bool) {}))
      (void)ask.call(asking);
  }
  ASSERT_GE(static_cast<int>(samples.size()), wanted);
  // A double's box is a few hundred of double's ulps of the segment: a few roundings of the ends
  // move the ratio's words by about 1%. A float's box is millions of them.
  const double ratio_tolerance = std::is_same_v<T, float> ? 1e-6 : 0.05;
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const DepthSample<T>& s = samples[n];
    const Vector3<T> right = view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
    const int axis = view_axis_sign(s.original, s.convention);
    for (const ConsumerArithmetic arithmetic :
         {ConsumerArithmetic::ieee, ConsumerArithmetic::gpu}) {
      for (int e = 0; e <= std::numeric_limits<T>::digits; e += 3) {
        const T moved = e == std::numeric_limits<T>::digits ? T(0) : std::ldexp(T(1), -e);
        const Vector3<T> answer = right * (T(1) + moved);
        const std::string what = "sample " + std::to_string(n) + ", moved by 2^-" +
                                 std::to_string(e) +
                                 (arithmetic == ConsumerArithmetic::gpu ? " (gpu)" : "");
        expect_same_depth_verdict(
            [&](Arithmetic method) { return judge_view_position(s, answer, arithmetic, method); },
            "view_position, " + what, ratio_tolerance, tally);
        expect_same_depth_verdict(
            [&](Arithmetic method) {
              return judge_linear_depth(s, T(axis) * answer.z(), arithmetic, method);
            },
            "linear_depth, " + what, ratio_tolerance, tally);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GT(tally.held, 0);
  EXPECT_GT(tally.violated, 0);
  // The world position: the right one (through the view position and the inverse view, in T),
  // moved off its place by 2^-e of itself.
  ASSERT_GE(static_cast<int>(world_samples.size()), wanted / 2);
  Tally world;
  for (std::size_t n = 0; n < world_samples.size(); ++n) {
    const DepthSample<T>& s = world_samples[n];
    const Vector3<T> right =
        world_position(s.projection, s.view, s.ndc_x, s.ndc_y, s.depth, s.convention);
    for (const ConsumerArithmetic arithmetic :
         {ConsumerArithmetic::ieee, ConsumerArithmetic::gpu}) {
      for (int e = 0; e <= std::numeric_limits<T>::digits; e += 3) {
        const T moved = e == std::numeric_limits<T>::digits ? T(0) : std::ldexp(T(1), -e);
        const Vector3<T> answer = right * (T(1) + moved);
        expect_same_depth_verdict(
            [&](Arithmetic method) { return judge_world_position(s, answer, arithmetic, method); },
            "world_position, sample " + std::to_string(n) + ", moved by 2^-" + std::to_string(e) +
                (arithmetic == ConsumerArithmetic::gpu ? " (gpu)" : ""),
            ratio_tolerance, world);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  EXPECT_GT(world.held, 0);
  EXPECT_GT(world.violated, 0);
}

// The culling judge's certified signs (a vertex certainly on a plane's kept side) against the exact
// ones: the right planes, and each plane moved toward the kept region by 2^-e of its size (some
// vertices culled by less than, some by more than the rounding allows): the same findings.
TYPED_TEST(FilteredConsumers, cullingJudgeAgreesWithTheExactOne) {
  using T = TypeParam;
  const auto gen = cases::valid_case<T>();
  rc::Random random(20261207);
  Tally tally;
  const int wanted = std::is_same_v<T, long double> ? 6 : 30;
  int cases = 0;
  for (int i = 0; cases < wanted && i < 400; ++i) {
    const cases::Case<T> g = gen(random.split(), i % 101).value();
    const ObliqueResult<T> r = apply<T>(g.matrix, g.plane, g.convention);
    if (r.status != Status::ok) continue;
    ++cases;
    const FrustumPlanes<T> right = frustum_planes(r.projection, g.convention);
    for (int e = 0; e <= std::numeric_limits<T>::digits + 6; e += 4) {
      for (int k = 0; k < 6; ++k) {
        FrustumPlanes<T> planes = right;
        Vector4<T>* moved[] = {&planes.left, &planes.right,      &planes.bottom,
                               &planes.top,  &planes.near_plane, &planes.far_plane};
        Vector4<T>& plane = *moved[k];
        if (e > 0) plane(3) -= std::ldexp(plane.template head<3>().norm(), -e);
        const std::string what = "case " + std::to_string(i) + ", plane " + std::to_string(k) +
                                 " moved by 2^-" + std::to_string(e);
        const auto filtered =
            judge_culling_planes(g.matrix, g.plane, g.convention, r.projection, planes);
        const auto exact = judge_culling_planes(g.matrix, g.plane, g.convention, r.projection,
                                                planes, Arithmetic::exact);
        ASSERT_EQ(filtered.size(), exact.size()) << what;
        for (std::size_t n = 0; n < exact.size(); ++n) {
          const std::string where = what + " (" + describe(exact[n]) + ")";
          ASSERT_EQ(filtered[n].judged, exact[n].judged) << where;
          ASSERT_EQ(filtered[n].holds, exact[n].holds) << where;
          EXPECT_EQ(filtered[n].ratio, exact[n].ratio) << where;
          EXPECT_EQ(filtered[n].detail, exact[n].detail) << where;
          if (!exact[n].judged)
            ++tally.not_judged;
          else
            ++(exact[n].holds ? tally.held : tally.violated);
        }
        if (e == 0) break;  // the right planes once
      }
    }
  }
  EXPECT_EQ(cases, wanted);
  EXPECT_GT(tally.held, 0);
  EXPECT_GT(tally.violated, 0);
}

// The ray is widened by ndc_error in NDC x and y, and by nothing else: an answer on the ray of a
// position within it holds, one beyond it is violated, with and without the widening, in both
// arithmetics (exact; the filtered path agrees, above).
TYPED_TEST(FilteredConsumers, theRayIsWidenedByTheNdcErrorAlone) {
  using T = TypeParam;
  const Matrix4<T> m = perspective<T>(T(1.2), T(1.5), T(1), T(100), Convention::gl);
  const auto sample = depth_sample<T>(m, m, Convention::gl, DepthBuffer::float32,
                                      Vector4<T>(T(0.75), T(-0.5), T(-4), T(1)));
  ASSERT_TRUE(sample.has_value());
  const T delta = T(1) / T(1024);
  for (const ConsumerArithmetic arithmetic : {ConsumerArithmetic::ieee, ConsumerArithmetic::gpu}) {
    auto at = [&](T dx) {
      return view_position(m, T(sample->ndc_x + dx), sample->ndc_y, sample->depth, Convention::gl);
    };
    DepthSample<T> widened = *sample;
    widened.ndc_error = delta;
    for (const Arithmetic method : {Arithmetic::exact, Arithmetic::filtered}) {
      EXPECT_TRUE(judge_view_position(widened, at(delta / 2), arithmetic, method).holds);
      EXPECT_FALSE(judge_view_position(*sample, at(delta / 2), arithmetic, method).holds);
      EXPECT_FALSE(judge_view_position(widened, at(delta * 4), arithmetic, method).holds);
      EXPECT_TRUE(judge_view_position(*sample, at(0), arithmetic, method).holds);
    }
  }
}

// A sample moved to a target's pixel: its centre's NDC (rounded to T) at Sampling::pixels, its
// own NDC in the pixel that holds it at Sampling::arbitrary; outside the target, the nearest
// edge pixel; the depth kept.
TYPED_TEST(FilteredConsumers, aSampleIsReadAtItsPixel) {
  using T = TypeParam;
  DepthSample<T> s;
  s.ndc_x = T(0.1);
  s.ndc_y = T(-1.5);
  s.depth = T(0.25);
  Pixel target;
  target.width = 1920;
  target.height = 1080;
  const DepthSample<T> centre = at_pixel(s, target, Sampling::pixels);
  EXPECT_EQ(centre.pixel.x, 1056);  // floor(1.1 / 2 * 1920)
  EXPECT_EQ(centre.pixel.y, 0);     // below the target: the bottom row
  EXPECT_TRUE(centre.pixel.at_centre);
  // (2 p + 1) / size - 1 rounded once: (2 p + 1 - size) / size.
  EXPECT_EQ(centre.ndc_x, T(2 * 1056 + 1 - 1920) / T(1920));
  EXPECT_EQ(centre.ndc_y, T(1 - 1080) / T(1080));
  EXPECT_EQ(centre.depth, s.depth);
  const DepthSample<T> own = at_pixel(s, target, Sampling::arbitrary);
  EXPECT_EQ(own.pixel.x, 1056);
  EXPECT_FALSE(own.pixel.at_centre);
  EXPECT_EQ(own.ndc_x, s.ndc_x);
  EXPECT_EQ(own.ndc_y, s.ndc_y);
}

}  // namespace
}  // namespace oblique::oracle
