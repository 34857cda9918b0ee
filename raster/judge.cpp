// The frame's samples, the judgement of what the rasterizer gave back, and a check prepared for
// the renderer (no GL here: the tests judge made-up read-backs too, and a frame is built on any
// thread). Bounds: oblique/oracle/tolerance.h, "The rasterizer".
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/raster/raster.h"

namespace oblique::raster {

namespace tol = oblique::oracle::tolerance;
using Eigen::Matrix4d;
using Eigen::Vector4d;
using Eigen::Vector4f;

namespace {

/// A value the renderer computes from a float32 point, and the bound on the renderer's error in
/// it (tolerance.h: a row, a clip test).
struct Bounded {
  double value = 0;
  double bound = 0;
  bool surely_positive() const { return value > bound; }
  bool surely_negative() const { return value < -bound; }
};

/// Row r of `m` at v, with the bound of a float32 evaluation of it.
Bounded row(const Matrix4d& m, int r, const Vector4d& v) {
  double value = 0, magnitude = 0;
  for (int i = 0; i < 4; ++i) {
    const double t = m(r, i) * v(i);
    value += t;
    magnitude += std::abs(t);
  }
  return {value,
          tol::raster_row_gamma() * magnitude + tol::kRasterRowRoundings * tol::kRasterFlush};
}

/// alpha z + beta w >= 0 as the renderer tests it.
Bounded clip_test(const Bounded& z, const Bounded& w, int alpha, int beta) {
  const double value = alpha * z.value + beta * w.value;
  const double bound = (std::abs(alpha) * z.bound + std::abs(beta) * w.bound +
                        tol::kRasterUnit * (std::abs(alpha * z.value) + std::abs(beta * w.value))) *
                       tol::kRasterBandSlack;
  return {value, bound};
}

/// The six clip tests of `m` at v: near, far, then x >= -w, x <= w, y >= -w, y <= w.
struct ClipTests {
  Bounded tests[6];
  Bounded z, w;
  bool surely_inside() const {
    for (const Bounded& t : tests)
      if (!t.surely_positive()) return false;
    return true;
  }
  bool surely_outside() const {
    for (const Bounded& t : tests)
      if (t.surely_negative()) return true;
    return false;
  }
};

/// The clip tests of `m` at v; with `accepted`, row 3 may be any that far from m's (an accepted
/// answer's, accepted_row3()), shaded in float32 as well.
ClipTests clip_tests(const Matrix4d& m, const Vector4d& v, Convention convention,
                     const Vector4d* accepted = nullptr) {
  ClipTests out;
  const Bounded x = row(m, 0, v), y = row(m, 1, v);
  out.z = row(m, 2, v);
  out.w = row(m, 3, v);
  if (accepted)
    out.z.bound += (1 + tol::raster_row_gamma()) * accepted->cwiseAbs().dot(v.cwiseAbs()) *
                   tol::kRasterBandSlack;
  const RowCombination n = near_rows(convention), f = far_rows(convention);
  out.tests[0] = clip_test(out.z, out.w, n.m3, n.m4);
  out.tests[1] = clip_test(out.z, out.w, f.m3, f.m4);
  out.tests[2] = clip_test(x, out.w, 1, 1);
  out.tests[3] = clip_test(x, out.w, -1, 1);
  out.tests[4] = clip_test(y, out.w, 1, 1);
  out.tests[5] = clip_test(y, out.w, -1, 1);
  return out;
}

/// p / w and its bound, from the rows' bounds (tolerance.h); nullopt-like: bound < 0 where w's
/// sign is not decided.
Bounded quotient(const Bounded& p, const Bounded& w) {
  if (!(w.value - w.bound > 0)) return {0, -1};
  const double q = p.value / w.value;
  const double bound = ((p.bound + std::abs(q) * w.bound) / (w.value - w.bound) +
                        tol::kRasterDivideRoundings * tol::kRasterUnit * std::abs(q)) *
                       tol::kRasterBandSlack;
  return {q, bound};
}

/// `plane` scaled by a power of two (exactly) so that its largest coefficient is in [0.5, 1): a C
/// of subnormal coefficients keeps its digits in C . v and in its scale in near'.
Vector4d scaled_plane(const Vector4d& plane) {
  const double largest = plane.cwiseAbs().maxCoeff();
  if (!(largest > 0) || !std::isfinite(largest)) return plane;
  int exponent = 0;
  std::frexp(largest, &exponent);
  Vector4d out;
  for (int i = 0; i < 4; ++i) out(i) = std::ldexp(plane(i), -exponent);
  return out;
}

/// The plane a * M_3 + b * M_4 of `m`.
Vector4d combined(const Matrix4d& m, RowCombination r) {
  return r.m3 * m.row(2).transpose() + r.m4 * m.row(3).transpose();
}

/// Whether v lies in the original volume of m in exact terms (to the judge's double rounding).
bool inside_original(const Matrix4d& m, const Vector4d& v, Convention convention) {
  const Vector4d clip = m * v;
  double magnitude[4];
  for (int r = 0; r < 4; ++r) magnitude[r] = (m.row(r).cwiseAbs() * v.cwiseAbs()).value();
  const double g = 8 * 0x1p-53;  // a row and a sum of two, in double
  const RowCombination n = near_rows(convention), f = far_rows(convention);
  auto positive = [&](int a, int ra, int b, int rb) {
    return a * clip(ra) + b * clip(rb) > g * (magnitude[ra] + magnitude[rb]);
  };
  return positive(n.m3, 2, n.m4, 3) && positive(f.m3, 2, f.m4, 3) && positive(1, 0, 1, 3) &&
         positive(-1, 0, 1, 3) && positive(1, 1, 1, 3) && positive(-1, 1, 1, 3);
}

/// Window position (pixels) of NDC p in a `size` frame, and its bound.
Bounded window(const Bounded& ndc, int size) {
  const double half = 0.5 * size;
  const double pixel = (ndc.value + 1) * half;
  return {pixel, (ndc.bound * half + tol::kRasterUnit * std::abs(pixel)) * tol::kRasterBandSlack};
}

/// The frame's random numbers: a SplitMix64 stream (Steele, Lea and Flood) for each pixel, started
/// from the frame's seed and the pixel's index, and uniform doubles in [0, 1) from its top 53
/// bits. Written out rather than std::uniform_real_distribution, whose values differ between
/// standard libraries, so that a raster report's frame seed draws the same frame everywhere; and
/// one stream a pixel, so that a pixel's sample does not depend on the pixels before it.
class PixelRandom {
 public:
  PixelRandom(std::uint64_t seed, std::uint64_t pixel) : state_(mix(seed + mix(pixel + 1))) {}
  double unit() { return static_cast<double>(mix(state_ += kGamma) >> 11) * 0x1p-53; }

 private:
  static constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

}  // namespace

Frame make_frame(const Matrix4d& m, const Vector4d& c, const Matrix4d& reference,
                 Convention convention, int size, std::uint64_t seed) {
  Frame frame;
  frame.size = size;
  const long count = static_cast<long>(size) * size;
  frame.points.assign(static_cast<std::size_t>(count), Vector4f::Zero());
  frame.placed.assign(static_cast<std::size_t>(count), 0);
  const Matrix4d inverse = m.inverse();
  const double z_near =
      convention == Convention::reversed_z ? 1 : clip_depth_range(convention).z_low;
  const double z_far = convention == Convention::reversed_z ? 0 : 1;
  // The planes the distances bunch at: C, the original near and far, the answer's far plane.
  const Vector4d planes[] = {scaled_plane(c), combined(m, near_rows(convention)),
                             combined(m, far_rows(convention)),
                             combined(reference, far_rows(convention))};
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const long k = static_cast<long>(j) * size + i;
      PixelRandom random(seed, static_cast<std::uint64_t>(k));
      const auto unit = [&random] { return random.unit(); };
      const double x = (2.0 * i + 1) / size - 1, y = (2.0 * j + 1) / size - 1;
      // On the pixel's ray, M P = (x, y, z(s), 1): s = 0 at the near plane, 1 at the far one.
      const Vector4d a = inverse * Vector4d(x, y, z_near, 1);
      const Vector4d b = inverse * Vector4d(x, y, z_far, 1);
      const double pick = unit();
      double s = -0.25 + 1.5 * unit();  // a quarter of the samples anywhere along the ray
      if (pick < 0.75) {
        // At a distance t from the plane, relative to the plane's terms where the ray crosses it:
        // Pi . P(s) = t P(s)_w, solved for s (Pi . v moves with s as a Mobius function: bunching
        // in s would not bunch in distance).
        const Vector4d& plane = planes[std::min(3, static_cast<int>(pick / 0.1875))];
        const double pa = plane.dot(a), pb = plane.dot(b);
        const double crossing = pa / (pa - pb);
        const Vector4d on = (1 - crossing) * a + crossing * b;
        const double magnitude = plane.cwiseAbs().dot((on / on.w()).cwiseAbs());
        const double sign = unit() < 0.5 ? -1 : 1;  // drawn in this order, the same everywhere
        const double t = sign * std::pow(10.0, -(1 + 7 * unit())) * magnitude;
        const double at = (pa - t * a.w()) / ((pa - pb) - t * (a.w() - b.w()));
        if (std::isfinite(at)) s = at;
      }
      for (int attempt = 0; attempt < 2; ++attempt, s = unit()) {
        const Vector4d p = (1 - s) * a + s * b;
        if (!(p.w() > 0)) continue;  // behind the eye in camera space
        const Vector4d v = p / p.w();
        if (!v.allFinite() || v.cwiseAbs().maxCoeff() > 1e30) continue;
        const Vector4f point(static_cast<float>(v.x()), static_cast<float>(v.y()),
                             static_cast<float>(v.z()), 1.0f);
        // Placed only where float32 shading cannot move it out of its pixel (the reference's
        // rows 1, 2 and 4 are M's),
        const Vector4d vd = point.cast<double>();
        const Bounded w = row(reference, 3, vd);
        const Bounded px = window(quotient(row(reference, 0, vd), w), size);
        const Bounded py = window(quotient(row(reference, 1, vd), w), size);
        if (px.bound < 0 || py.bound < 0) continue;
        // and where the snap to the subpixel grid cannot move it onto an edge (tolerance.h).
        const double xs = px.bound + tol::kRasterSubpixel, ys = py.bound + tol::kRasterSubpixel;
        if (px.value - xs <= i || px.value + xs >= i + 1) continue;
        if (py.value - ys <= j || py.value + ys >= j + 1) continue;
        frame.points[static_cast<std::size_t>(k)] = point;
        frame.placed[static_cast<std::size_t>(k)] = 1;
        break;
      }
    }
  }
  return frame;
}

namespace {

template <class T>
std::optional<Vector4d> accepted_in(const Matrix4d& m, const Vector4d& c, Convention convention) {
  const oracle::Problem<T> problem(m.cast<T>(), c.cast<T>(), convention);
  if (problem.exact_status() != Status::ok) return std::nullopt;
  const std::optional<oracle::exact::Vec> bounds = problem.row3_bounds();
  if (!bounds) return std::nullopt;
  const std::optional<oracle::exact::Rational> scale = problem.scale_error();
  const DepthRange range = clip_depth_range(convention);
  // Property 1's allowance, u lambda max|C_j|, for lambda up to a (1 + scale).
  const oracle::exact::Rational a =
      oracle::exact::Rational(range.z_high - range.z_low) / problem.corner_dot();
  oracle::exact::Rational largest = 0;
  for (int i = 0; i < 4; ++i)
    largest = std::max(largest, oracle::exact::abs(oracle::exact::to_rational(c(i))));
  const oracle::exact::Rational allowance =
      oracle::tolerance::unit_roundoff(oracle::tolerance::precision_bits<T>()) * a * (1 + *scale) *
      largest;
  Vector4d out;
  for (int i = 0; i < 4; ++i) {
    // Rounded up: get_d truncates, so one part in 2^50 more, and the smallest double more.
    const double b = oracle::approx((*bounds)[i] + allowance);
    out(i) = b * (1 + 0x1p-50) + std::numeric_limits<double>::denorm_min();
  }
  return out;
}

}  // namespace

std::optional<Vector4d> accepted_row3(const Matrix4d& m, const Vector4d& c, Convention convention,
                                      int precision_bits) {
  switch (precision_bits) {
    case 24: return accepted_in<float>(m, c, convention);
    case 64: return accepted_in<long double>(m, c, convention);
    default: return accepted_in<double>(m, c, convention);
  }
}

Result judge_frame(const Frame& frame, const Readback& readback, const Matrix4d& m,
                   const Vector4d& given_c, const Matrix4d& answer, const Matrix4d& reference,
                   const std::optional<Vector4d>& accepted_given, Convention convention,
                   DepthBuffer buffer) {
  // The reference (the core's accurate answer) is itself within 2 ulps of the exact one.
  std::optional<Vector4d> accepted = accepted_given;
  if (accepted)
    for (int i = 0; i < 4; ++i)
      *accepted += Vector4d::Unit(i) * 4 * 0x1p-53 * std::abs(reference(2, i));
  const Vector4d c = scaled_plane(given_c);  // C . v and the bands as for C itself, scaled
  Result r;
  r.rendered = true;
  const long count = static_cast<long>(frame.size) * frame.size;
  r.samples = count;
  if (static_cast<long>(readback.ids.size()) != count ||
      static_cast<long>(readback.depths.size()) != count) {
    r.why = "the read-back does not hold one id and one depth a pixel";
    return r;
  }
  const Vector4d near_reference = combined(reference, near_rows(convention));
  const double scale = near_reference.dot(c) / c.squaredNorm();  // near' = scale C
  if (!(scale > 0) || !std::isfinite(scale)) {
    r.why = "the reference's near plane is not a positive multiple of C";
    return r;
  }
  // Where each sample was drawn (ids are index + 1), and whether the id buffer is consistent.
  std::vector<long> drawn_at(static_cast<std::size_t>(count), -1);
  r.drawn_pixels.resize(static_cast<std::size_t>(count));
  for (long p = 0; p < count; ++p)
    r.drawn_pixels[static_cast<std::size_t>(p)] = readback.ids[static_cast<std::size_t>(p)] != 0;
  for (long p = 0; p < count; ++p) {
    const std::uint32_t id = readback.ids[static_cast<std::size_t>(p)];
    if (id == 0) continue;
    if (id > static_cast<std::uint64_t>(count) || !frame.placed[id - 1] || drawn_at[id - 1] >= 0) {
      ++r.ids_inconsistent;
      continue;
    }
    drawn_at[id - 1] = p;
  }
  auto note = [&r](Flag flag) {
    if (r.flagged.size() < (std::size_t{1} << 18)) r.flagged.emplace_back(flag.sample, flag.kind);
    long same = 0;
    for (const Flag& f : r.examples) same += f.kind == flag.kind;
    if (same < 3) r.examples.push_back(flag);
  };
  std::vector<float> kept_depths;
  const bool gl = convention == Convention::gl;
  for (long k = 0; k < count; ++k) {
    if (!frame.placed[static_cast<std::size_t>(k)]) continue;
    ++r.placed;
    const Vector4f& point = frame.points[static_cast<std::size_t>(k)];
    const Vector4d v = point.cast<double>();
    const long at = drawn_at[static_cast<std::size_t>(k)];
    const bool drawn = at >= 0;
    Flag flag;
    flag.sample = k;
    flag.pixel = at;
    flag.point = point;
    double c_magnitude = 0;
    for (int i = 0; i < 4; ++i) c_magnitude += std::abs(c(i) * v(i));
    flag.c_dot = c.dot(v);
    if (drawn) ++r.drawn;
    if (drawn && at != k) {
      ++r.wrong_pixel;
      flag.kind = Flag::Kind::wrong_pixel;
      note(flag);
      continue;
    }
    // The renderer against its own float32 arithmetic on the answer (a self-check).
    const ClipTests given = clip_tests(answer, v, convention);
    if ((drawn && given.surely_outside()) || (!drawn && given.surely_inside())) {
      ++r.renderer_disagrees;
      flag.kind = Flag::Kind::renderer_disagrees;
      note(flag);
      continue;
    }
    // Against C: the band is what the near plane of any accepted answer, shaded in float32,
    // cannot decide (the reference's clip test, widened by `accepted`, over the scale of C in
    // it), plus the judge's own C . v. Without an accepted envelope nothing is decided.
    bool decided = false, kept = false;
    if (accepted) {
      const ClipTests correct = clip_tests(reference, v, convention, &*accepted);
      flag.band =
          (correct.tests[0].bound / scale + 8 * 0x1p-53 * c_magnitude) * tol::kRasterBandSlack;
      kept = flag.c_dot > flag.band && inside_original(m, v, convention);
      decided = true;
      if (drawn && flag.c_dot < -flag.band) {
        ++r.drawn_behind_c;
        flag.kind = Flag::Kind::drawn_behind_c;
        note(flag);
      } else if (std::abs(flag.c_dot) <= flag.band) {
        decided = false;
      } else if (kept) {
        // Where an accepted answer's far or side planes cannot be decided (its far plane touches
        // the far corner Q, and its scale a is known only so well), a clipped sample is no
        // finding.
        bool others = true;
        for (int t = 1; t < 6; ++t) others = others && correct.tests[t].surely_positive();
        if (!others) {
          decided = false;
        } else if (!drawn) {
          ++r.clipped_kept;
          flag.kind = Flag::Kind::clipped_kept;
          note(flag);
        }
      }
    }
    if (!decided) ++r.undecidable;
    if (!drawn) continue;
    // The depth stored against the answer's exact window depth.
    const Bounded ndc = quotient(given.z, given.w);
    if (ndc.bound < 0) continue;
    const double exact = gl ? 0.5 * ndc.value + 0.5 : ndc.value;
    double bound =
        gl ? 0.5 * ndc.bound + tol::kRasterUnit : ndc.bound + tol::kRasterUnit * std::abs(exact);
    bound += buffer == DepthBuffer::fixed24
                 ? tol::kRasterFixed24Quantum + tol::kRasterUnit
                 : tol::kRasterUnit * std::abs(exact) + tol::kRasterFlush;
    bound *= tol::kRasterBandSlack;
    const double read = readback.depths[static_cast<std::size_t>(k)];
    const double ratio = std::abs(read - exact) / bound;
    r.worst_depth_ratio = std::max(r.worst_depth_ratio, ratio);
    if (!(ratio <= 1)) {
      ++r.depth_off;
      flag.kind = Flag::Kind::depth_off;
      flag.depth_read = read;
      flag.depth_exact = exact;
      flag.depth_bound = bound;
      note(flag);
    }
    if (kept) kept_depths.push_back(readback.depths[static_cast<std::size_t>(k)]);
  }
  // The buffer's values across the kept region, from the depths stored there.
  if (!kept_depths.empty()) {
    std::sort(kept_depths.begin(), kept_depths.end());
    r.depth.observed = std::unique(kept_depths.begin(), kept_depths.end()) - kept_depths.begin();
    r.depth.low = kept_depths.front();
    r.depth.high = kept_depths[static_cast<std::size_t>(r.depth.observed - 1)];
    r.depth.values = depth_buffer_values(r.depth.low, r.depth.high, buffer);
    r.depth.bits = std::log2(r.depth.values);
  }
  char line[256];
  if (r.ids_inconsistent > 0 || r.renderer_disagrees > 0 || r.depth_off > 0) {
    r.outcome = Outcome::inconclusive;
    std::snprintf(line, sizeof line,
                  "the renderer failed a self-check: %ld ids inconsistent, %ld samples clipped "
                  "against its own float32 arithmetic, %ld depths beyond their bound",
                  r.ids_inconsistent, r.renderer_disagrees, r.depth_off);
  } else if (r.drawn_behind_c > 0 || r.clipped_kept > 0 || r.wrong_pixel > 0) {
    r.outcome = Outcome::fail;
    std::snprintf(line, sizeof line,
                  "%ld samples drawn behind C, %ld of the original volume on C's kept side "
                  "clipped, %ld drawn into a wrong pixel (of %ld placed)",
                  r.drawn_behind_c, r.clipped_kept, r.wrong_pixel, r.placed);
  } else {
    r.outcome = Outcome::pass;
    std::snprintf(line, sizeof line, "%ld samples placed, %ld drawn, %ld within a band", r.placed,
                  r.drawn, r.undecidable);
  }
  r.why = line;
  return r;
}

AxisDepth measure_axis(const Readback& readback, Convention, DepthBuffer buffer) {
  AxisDepth out;
  std::vector<float> depths;
  for (std::size_t p = 0; p < readback.ids.size(); ++p)
    if (readback.ids[p] != 0) depths.push_back(readback.depths[p]);
  out.drawn = static_cast<long>(depths.size());
  if (depths.empty()) return out;
  std::sort(depths.begin(), depths.end());
  out.observed = std::unique(depths.begin(), depths.end()) - depths.begin();
  out.low = depths.front();
  out.high = depths[static_cast<std::size_t>(out.observed - 1)];
  out.values = depth_buffer_values(out.low, out.high, buffer);
  out.bits_lost = std::log2(depth_buffer_values(0.0, 1.0, buffer) / out.values);
  return out;
}

PreparedCheck prepare_check(const Matrix4d& m, const Vector4d& c, const Matrix4d& answer,
                            Convention convention, DepthBuffer buffer, int size, std::uint64_t seed,
                            int precision_bits) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  PreparedCheck p;
  p.m = m;
  p.c = c;
  p.answer = answer;
  p.convention = convention;
  p.buffer = buffer;
  const ObliqueResult<double> core = apply<double>(m, c, convention);
  if (core.status != Status::ok) {
    p.why = "the core has no answer for M and C to judge against (" +
            std::string(status_code(core.status)) + ")";
    return p;
  }
  p.reference = core.projection;
  p.frame = make_frame(m, c, p.reference, convention, size, seed);
  p.accepted = accepted_row3(m, c, convention, precision_bits);
  p.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return p;
}

Result judge_prepared(const PreparedCheck& p, const Readback& readback, double render_seconds) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  Result r = judge_frame(p.frame, readback, p.m, p.c, p.answer, p.reference, p.accepted,
                         p.convention, p.buffer);
  r.render_seconds = render_seconds;
  r.judge_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace oblique::raster
