// The depth judges (consumers.h): view_position and linear_depth, against the segment of the
// pixel's ray that the stored depth stands for, in exact arithmetic; compiled once for float,
// double and long double.
#include "consumer_judging.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

using namespace consumer_judging;

namespace {

Rational ndc_of(const Rational& window, Convention convention) {
  return convention == Convention::gl ? Rational(2 * window - 1) : window;
}

Rational window_of(const Rational& ndc, Convention convention) {
  return convention == Convention::gl ? Rational((ndc + 1) / 2) : ndc;
}

/// The window depths the stored value stands for, with the value the shader reads, in [0, 1].
template <class T>
std::pair<Rational, Rational> depth_interval(const DepthSample<T>& s) {
  Rational lo, hi;
  if (s.buffer == DepthBuffer::fixed24) {
    const Rational k(static_cast<unsigned long>(s.stored));
    lo = (k - Rational(1, 2)) / kFixed24Max;
    hi = (k + Rational(1, 2)) / kFixed24Max;
  } else {
    float f;
    std::memcpy(&f, &s.stored, sizeof f);
    const Rational v = oracle::exact::to_rational(f);
    lo = (v + oracle::exact::to_rational(std::nextafter(f, -1.0f))) / 2;
    hi = (v + oracle::exact::to_rational(std::nextafter(f, 2.0f))) / 2;
  }
  const Rational read = oracle::exact::to_rational(s.depth);
  lo = std::max(Rational(0), std::min(lo, read));
  hi = std::min(Rational(1), std::max(hi, read));
  return {lo, hi};
}

/// What judge_view_position() and judge_linear_depth() share: the segment of the ray the stored
/// depth stands for, and how far a reconstruction computed in T may be from it. A solve in T
/// gives homogeneous coordinates v^ within `box` of v = M'^-1 (x, y, z, 1), z in the depth's
/// interval, and its divide by w rounds once more; the answer is judged against that set, which
/// stays bounded in homogeneous coordinates even where rounding can reach w = 0 (a point that
/// float cannot place along its ray is still judged by the ray and the depths it can reach).
struct Segment {
  bool judged = false;
  std::string why;
  Vec a, b;                  ///< the ends (w = 1)
  Vec ha, hb;                ///< the ends in homogeneous coordinates, v at the interval's ends
  Vec box;                   ///< |v^ - v| (with the divide's rounding), per coordinate (x, y, z, w)
  std::optional<Vec> bound;  ///< per coordinate (x, y, z) of the point, where w is determined
  bool w_reaches_zero = false;  ///< whether box_w reaches the segment's w (it keeps its sign)
  /// Whether a coordinate of the segment (homogeneous, with its box, or divided by w) reaches
  /// the largest finite T: a reconstruction in T may overflow there.
  bool beyond_range = false;
  int axis = -1;  ///< view_axis_sign of the original; 0 where rounding in T decides it
  bool axis_is_z = true;
};

/// What a depth judge says before it looks at the answer: not judged where the stored depth
/// has no segment to judge by, violated where the answer is not finite; empty otherwise.
std::optional<ConsumerFinding> before_the_answer(ConsumerCheck check, const Segment& seg,
                                                 bool finite, bool none_finite,
                                                 const std::string& answered) {
  ConsumerFinding f;
  f.check = check;
  if (!seg.judged) {
    f.judged = false;
    f.detail = seg.why;
    return f;
  }
  if (finite) return std::nullopt;
  if (seg.w_reaches_zero && none_finite) {
    // A correct solve in T can give w^ = 0 here, and its divide then gives an infinity (or
    // 0 / 0) in every coordinate: what it answered is one of the answers float arithmetic
    // allows. A finite coordinate beside a non-finite one is not.
    f.holds = true;
    f.ratio = 1;
    f.detail = "answered " + answered + ": a solve in T can reach w = 0 at this depth (w within " +
               text(seg.box[3]) + " of the segment's), and then divides by 0";
    return f;
  }
  if (seg.beyond_range) {
    // The points the stored depth stands for reach beyond T's largest finite value: a solve in T
    // overflows there, and an infinity, carried through its other steps (inf - inf, 0 inf),
    // may leave NaN or an infinity in any coordinate.
    f.holds = true;
    f.ratio = 1;
    f.detail = "answered " + answered +
               ": the points this stored depth stands for reach beyond the largest finite " +
               "number of the type, where a solve in it overflows";
    return f;
  }
  f.holds = false;
  f.ratio = std::numeric_limits<double>::infinity();
  f.detail = "answered " + answered + ", not finite";
  return f;
}

/// The significand bits of the arithmetic's unit roundoff (tolerance.h).
template <class T>
int arithmetic_bits(ConsumerArithmetic arithmetic) {
  return oracle::tolerance::precision_bits<T>() -
         (arithmetic == ConsumerArithmetic::gpu ? oracle::tolerance::kGpuLostBits : 0);
}

/// det(m), by the 2 x 2 minors of its first two rows and of its last two (Laplace).
Rational determinant(const Mat& m) {
  auto minor = [&m](int r, int a, int b) -> Rational {
    return m[r][a] * m[r + 1][b] - m[r][b] * m[r + 1][a];
  };
  const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  const int sign[6] = {1, -1, 1, 1, -1, 1};
  Rational det = 0;
  for (int k = 0; k < 6; ++k)
    det +=
        sign[k] * minor(0, pairs[k][0], pairs[k][1]) * minor(2, pairs[5 - k][0], pairs[5 - k][1]);
  return det;
}

/// Why a GPU's arithmetic (tolerance.h, kGpuLostBits) has no bound on the sample's
/// reconstruction, or "": a nonzero input below T's smallest normal number (it may be flushed to
/// 0), or a divisor (the determinant of M', or w at the segment's ends) whose exact value is
/// outside [2^-126, 2^126], where the shading language bounds no quotient. (Where only w's error
/// reaches below that, the answer is judged in homogeneous coordinates, as on the CPU.)
template <class T>
std::string gpu_unbounded(const DepthSample<T>& s, const Rational& det, const Vec (&ends)[2]) {
  const T smallest = std::numeric_limits<T>::min();
  auto subnormal = [&](T x) { return x != 0 && std::fabs(x) < smallest; };
  bool flushed = subnormal(s.ndc_x) || subnormal(s.ndc_y) || subnormal(s.depth);
  for (int i = 0; i < 16; ++i) flushed = flushed || subnormal(s.projection(i / 4, i % 4));
  if (flushed) return "an input below the smallest normal number, which a GPU may flush to 0";
  const Rational low = oracle::exact::power_of_two(-126), high = oracle::exact::power_of_two(126);
  auto outside = [&](const Rational& x) {
    return oracle::exact::abs(x) < low || oracle::exact::abs(x) > high;
  };
  if (outside(det) || outside(ends[0][3]) || outside(ends[1][3]))
    return "a divisor (M''s determinant, or w) outside [2^-126, 2^126], where a GPU's quotient "
           "has no stated precision";
  return "";
}

/// What ray_segment() needs of the sample's matrices alone, whatever the pixel: M' exactly, its
/// inverse and a solve's error bound, M's axis, and the GPU's divisor M' determinant.
struct MatrixAnalysis {
  std::string why;  ///< not empty: no segment can be judged on these matrices
  Mat m, inv, error;
  Rational det;
  bool axis_is_z = true;
  int axis = -1;
};

template <class T>
MatrixAnalysis analyse_matrices(const DepthSample<T>& s, int bits) {
  MatrixAnalysis out;
  out.m = oracle::exact::to_rational(s.projection);
  const std::optional<Mat> inv = oracle::exact::inverse(out.m);
  const std::optional<Mat> original_inv =
      oracle::exact::inverse(oracle::exact::to_rational(s.original));
  if (!inv || !original_inv) {
    out.why = "a singular projection";
    return out;
  }
  out.inv = *inv;
  {
    // The view axis is z only where M's fourth row is (0, 0, a, b); elsewhere (a rotated or
    // general matrix) linear depth has no axis to be measured along.
    const Mat original = oracle::exact::to_rational(s.original);
    out.axis_is_z = original[3][0] == 0 && original[3][1] == 0;
    if (out.axis_is_z)
      out.axis =
          axis_sign(*original_inv, s.convention, solve_error<T>(original, *original_inv, bits));
  }
  const std::optional<Mat> error = solve_error<T>(out.m, out.inv, bits);
  if (!error) {
    out.why =
        "the projection's determinant is within T's rounding of 0: its inverse is not "
        "determined in T";
    return out;
  }
  out.error = *error;
  if (bits < oracle::tolerance::precision_bits<T>()) out.det = determinant(out.m);
  return out;
}

/// analyse_matrices() of the last matrices seen on this thread: a run asks many pixels of one
/// oblique matrix (a shader's batch, a scene's samples), and this is most of a sample's exact
/// analysis.
template <class T>
const MatrixAnalysis& matrix_analysis_of(const DepthSample<T>& s, int bits) {
  struct Key {
    Matrix4<T> projection, original;
    Convention convention;
    int bits;
  };
  thread_local std::optional<std::pair<Key, MatrixAnalysis>> last;
  const bool same = last && last->first.bits == bits && last->first.convention == s.convention &&
                    last->first.projection == s.projection && last->first.original == s.original;
  if (!same)
    last.emplace(Key{s.projection, s.original, s.convention, bits}, analyse_matrices(s, bits));
  return last->second;
}

template <class T>
Segment ray_segment(const DepthSample<T>& s, int bits) {
  Segment out;
  const MatrixAnalysis& a = matrix_analysis_of(s, bits);
  if (!a.why.empty()) {
    out.why = a.why;
    return out;
  }
  out.axis_is_z = a.axis_is_z;
  out.axis = a.axis;
  const Mat* const inv = &a.inv;
  const Mat* const error = &a.error;
  const auto [lo, hi] = depth_interval(s);
  const Rational x = oracle::exact::to_rational(s.ndc_x), y = oracle::exact::to_rational(s.ndc_y);
  const Rational u = unit<T>(bits);
  Vec ends[2];
  out.box = {0, 0, 0, 0};
  Vec bound{0, 0, 0, 0};
  bool determined = true;
  const Rational depths[2] = {lo, hi};
  for (int e = 0; e < 2; ++e) {
    const Vec b{x, y, ndc_of(depths[e], s.convention), 1};
    const Vec v = oracle::exact::mul(*inv, b);
    if (v[3] == 0) {
      out.why = "the stored depth's interval reaches the ray's point at infinity";
      return out;
    }
    ends[e] = v;
    // |v^ - v| <= dv; the divide v^_i / v^_w rounds once: the answer times v^_w is within
    // u |v^_i| <= u (|v_i| + dv_i) of v^_i. Along the segment, |b| and |v| are at most the
    // larger of their ends' (both linear in the depth, which keeps its sign or passes 0).
    const Vec dv = oracle::exact::mul(*error, oracle::exact::abs(b));
    for (int i = 0; i < 4; ++i) {
      const Rational divide =
          i < 3 ? Rational(u * (oracle::exact::abs(v[i]) + dv[i])) : Rational(0);
      out.box[i] = std::max(out.box[i], Rational(dv[i] + divide));
    }
    if (dv[3] >= oracle::exact::abs(v[3])) {
      determined = false;
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      const Rational p = v[i] / v[3];
      const Rational bound_i =
          (dv[i] + oracle::exact::abs(p) * dv[3]) / (oracle::exact::abs(v[3]) - dv[3]) +
          u * oracle::exact::abs(p);
      bound[i] = std::max(bound[i], bound_i);
    }
  }
  if (ends[0][3] * ends[1][3] < 0) {
    out.why = "the stored depth's interval reaches the ray's point at infinity";
    return out;
  }
  if (bits < oracle::tolerance::precision_bits<T>()) {
    if (std::string why = gpu_unbounded(s, a.det, ends); !why.empty()) {
      out.why = why;
      return out;
    }
  }
  if (determined) out.bound = bound;
  out.w_reaches_zero =
      out.box[3] >= std::min(oracle::exact::abs(ends[0][3]), oracle::exact::abs(ends[1][3]));
  out.ha = ends[0];
  out.hb = ends[1];
  for (int i = 0; i < 4; ++i) {
    out.a[i] = ends[0][i] / ends[0][3];
    out.b[i] = ends[1][i] / ends[1][3];
  }
  const Rational largest = oracle::exact::to_rational(std::numeric_limits<T>::max());
  for (int i = 0; i < 4; ++i) {
    for (const Vec* end : {&out.ha, &out.hb}) {
      if (oracle::exact::abs((*end)[i]) + out.box[i] >= largest) out.beyond_range = true;
    }
    if (oracle::exact::abs(out.a[i]) >= largest || oracle::exact::abs(out.b[i]) >= largest)
      out.beyond_range = true;
  }
  out.judged = true;
  return out;
}

/// Whether some lambda and t in [0, 1] put lambda p within `scale` box of v(t) = a + t (b - a)
/// in every coordinate of `coordinates` and lambda within `scale` box_w of v_w(t): whether the
/// point p is the divide of a homogeneous point within the box of the segment. Exact for
/// Rational. Each constraint bounds lambda by lines in t (or, where p_i = 0, bounds t alone);
/// max(lower lines) - min(upper lines) is convex in t, so it is least at an end of t's range or
/// where two of the lines cross.
template <class R>
bool on_projected_segment(const std::array<R, 4>& a, const std::array<R, 4>& b,
                          const std::array<R, 4>& box, const std::array<R, 4>& p,
                          const std::vector<int>& coordinates, const R& scale) {
  struct Line {
    R at0, slope;  // at0 + slope t
    R at(const R& t) const { return at0 + slope * t; }
  };
  // At most four constraints each way (x, y, z and w): kept in place, this runs for every
  // answer judged (and dozens of times for its ratio).
  std::array<Line, 4> lower, upper;
  std::size_t lows = 0, highs = 0;
  R t_lo = 0, t_hi = 1;
  std::array<int, 4> all{};
  std::size_t count = 0;
  for (int i : coordinates) all[count++] = i;
  all[count++] = 3;
  for (std::size_t k = 0; k < count; ++k) {
    const int i = all[k];
    const R d = b[i] - a[i];
    const R low = a[i] - scale * box[i], high = a[i] + scale * box[i];
    if (p[i] == 0) {
      // low + d t <= 0 <= high + d t
      if (d == 0) {
        if (low > 0 || high < 0) return false;
        continue;
      }
      R t1 = -high / d, t2 = -low / d;
      if (t1 > t2) std::swap(t1, t2);
      t_lo = std::max(t_lo, t1);
      t_hi = std::min(t_hi, t2);
      continue;
    }
    Line l{low / p[i], d / p[i]}, h{high / p[i], d / p[i]};
    if (p[i] < 0) std::swap(l, h);
    lower[lows++] = l;
    upper[highs++] = h;
  }
  if (t_lo > t_hi) return false;
  if (lows == 0) return true;  // every p_i = 0: t's range alone decides
  auto gap = [&](const R& t) {
    R most = lower[0].at(t), least = upper[0].at(t);
    for (std::size_t k = 1; k < lows; ++k) most = std::max(most, lower[k].at(t));
    for (std::size_t k = 1; k < highs; ++k) least = std::min(least, upper[k].at(t));
    return most <= least;
  };
  if (gap(t_lo) || gap(t_hi)) return true;
  std::array<Line, 8> lines;
  for (std::size_t k = 0; k < lows; ++k) lines[k] = lower[k];
  for (std::size_t k = 0; k < highs; ++k) lines[lows + k] = upper[k];
  const std::size_t line_count = lows + highs;
  for (std::size_t i = 0; i < line_count; ++i) {
    for (std::size_t j = i + 1; j < line_count; ++j) {
      const R ds = lines[i].slope - lines[j].slope;
      if (ds == 0) continue;
      const R t = (lines[j].at0 - lines[i].at0) / ds;
      if (t > t_lo && t < t_hi && gap(t)) return true;
    }
  }
  return false;
}

/// How far a reconstruction in T may be from the segment, for a finding's detail: per
/// coordinate of the point where w is determined, else in homogeneous coordinates.
std::string within_text(const Segment& seg, const std::vector<int>& coordinates) {
  if (seg.bound) {
    if (coordinates.size() == 1) return ", within " + text((*seg.bound)[coordinates.front()]);
    return ", each coordinate within " + text(*seg.bound, 3);
  }
  return "; a solve in T can reach w = 0 there, so the answer is judged in homogeneous "
         "coordinates: (x, y, z, w) within " +
         text(seg.box, 4) + " of the segment's";
}

/// The verdict of on_projected_segment() at scale 1, exactly, with the ratio residual / bound:
/// the least scale of the box that holds p (by bisection in double, kept on the verdict's side
/// of 1).
std::pair<bool, double> judge_on_segment(const Segment& seg, const Vec& p,
                                         const std::vector<int>& coordinates) {
  const bool holds = on_projected_segment<Rational>(seg.ha, seg.hb, seg.box, p, coordinates, 1);
  std::array<double, 4> a, b, box, q;
  for (int i = 0; i < 4; ++i) {
    a[i] = seg.ha[i].get_d();
    b[i] = seg.hb[i].get_d();
    box[i] = seg.box[i].get_d();
    q[i] = p[i].get_d();
  }
  auto within = [&](double scale) {
    return on_projected_segment<double>(a, b, box, q, coordinates, scale);
  };
  double hi = 1;
  for (int k = 0; k < 64 && !within(hi); ++k) hi *= 2;
  double ratio = std::numeric_limits<double>::infinity();
  if (within(hi)) {
    double lo = 0;
    for (int k = 0; k < 60; ++k) {
      const double mid = (lo + hi) / 2;
      (within(mid) ? hi : lo) = mid;
    }
    ratio = hi;
  }
  if (holds) return {true, std::min(ratio, 1.0)};
  return {false, std::max(ratio, std::nextafter(1.0, 2.0))};
}

}  // namespace

template <class T>
std::optional<DepthSample<T>> depth_sample(const Matrix4<T>& projection, const Matrix4<T>& original,
                                           Convention convention, DepthBuffer buffer,
                                           const Vector4<T>& point) {
  if (!projection.allFinite() || !point.allFinite()) return std::nullopt;
  const Vec clip =
      oracle::exact::mul(oracle::exact::to_rational(projection), oracle::exact::to_rational(point));
  if (!(clip[3] > 0)) return std::nullopt;
  const Rational window = window_of(clip[2] / clip[3], convention);
  if (window < 0 || window > 1) return std::nullopt;
  DepthSample<T> s;
  s.projection = projection;
  s.original = original;
  s.convention = convention;
  s.buffer = buffer;
  s.ndc_x = oracle::exact::round_to<T>(clip[0] / clip[3]);
  s.ndc_y = oracle::exact::round_to<T>(clip[1] / clip[3]);
  if (buffer == DepthBuffer::fixed24) {
    const Rational scaled = window * kFixed24Max + Rational(1, 2);
    const mpz_class k = scaled.get_num() / scaled.get_den();  // floor: both positive
    s.stored = static_cast<std::uint32_t>(k.get_ui());
    s.depth = oracle::exact::round_to<T>(Rational(k) / kFixed24Max);
  } else {
    const float f = oracle::exact::round_to<float>(window);
    std::memcpy(&s.stored, &f, sizeof f);
    s.depth = static_cast<T>(f);
  }
  return s;
}

/// ray_segment() of the last sample judged on this thread: a round asks view_position and
/// linear_depth of the same sample, and its exact analysis is most of either judge's time.
template <class T>
const Segment& ray_segment_of(const DepthSample<T>& s, ConsumerArithmetic arithmetic) {
  thread_local std::optional<std::pair<DepthSample<T>, Segment>> last;
  thread_local ConsumerArithmetic last_arithmetic = ConsumerArithmetic::ieee;
  const bool same = last && last_arithmetic == arithmetic &&
                    last->first.projection == s.projection && last->first.original == s.original &&
                    last->first.convention == s.convention && last->first.buffer == s.buffer &&
                    last->first.ndc_x == s.ndc_x && last->first.ndc_y == s.ndc_y &&
                    last->first.depth == s.depth && last->first.stored == s.stored;
  if (!same) {
    last.emplace(s, ray_segment(s, arithmetic_bits<T>(arithmetic)));
    last_arithmetic = arithmetic;
  }
  return last->second;
}

template <class T>
ConsumerFinding judge_view_position(const DepthSample<T>& s, const Vector3<T>& answer,
                                    ConsumerArithmetic arithmetic) {
  const Segment& seg = ray_segment_of(s, arithmetic);
  if (auto early = before_the_answer(ConsumerCheck::view_position, seg, answer.allFinite(),
                                     !answer.array().isFinite().any(), numbers_text(answer)))
    return *early;
  ConsumerFinding f;
  f.check = ConsumerCheck::view_position;
  const auto [ok, ratio] = judge_on_segment(seg, point_of(answer), {0, 1, 2});
  f.holds = ok;
  f.ratio = ratio;
  f.points = {answer.template cast<double>(), approx_point(seg.a), approx_point(seg.b)};
  f.points_what = "the answer, and the ends of the pixel ray's segment the stored depth stands for";
  f.detail = "answered " + numbers_text(answer) + "; the stored depth stands for the points from " +
             text(seg.a, 3) + " to " + text(seg.b, 3) + within_text(seg, {0, 1, 2});
  return f;
}

template <class T>
ConsumerFinding judge_linear_depth(const DepthSample<T>& s, T answer,
                                   ConsumerArithmetic arithmetic) {
  const Segment& seg = ray_segment_of(s, arithmetic);
  if (auto early = before_the_answer(ConsumerCheck::linear_depth, seg, std::isfinite(answer),
                                     !std::isfinite(answer), protocol::format_number(answer)))
    return *early;
  ConsumerFinding f;
  f.check = ConsumerCheck::linear_depth;
  if (!seg.axis_is_z) {
    f.judged = false;
    f.detail = "the camera does not look along z (M's fourth row is not (0, 0, a, b))";
    return f;
  }
  if (seg.axis == 0) {
    // Which way the camera looks (the sign of its view volume's centre's z) is rounding in T.
    f.judged = false;
    f.detail =
        "the camera's axis is not determined in T (its view volume's centre is within a "
        "solve's rounding of z = 0 or of w = 0)";
    return f;
  }
  const Rational sign = seg.axis;
  // The answer is axis z: the point's z is axis times it.
  const Vec given{0, 0, sign * oracle::exact::to_rational(answer), 1};
  const auto [ok, ratio] = judge_on_segment(seg, given, {2});
  f.holds = ok;
  f.ratio = ratio;
  f.points = {approx_point(seg.a), approx_point(seg.b)};
  f.points_what = "the ends of the pixel ray's segment the stored depth stands for";
  f.detail = "answered " + protocol::format_number(answer) +
             "; the stored depth stands for linear depths from " + text(Rational(sign * seg.a[2])) +
             " to " + text(Rational(sign * seg.b[2])) + within_text(seg, {2});
  return f;
}

#define OBLIQUE_DEPTH_JUDGES(T)                                                                    \
  template std::optional<DepthSample<T>> depth_sample(const Matrix4<T>&, const Matrix4<T>&,        \
                                                      Convention, DepthBuffer, const Vector4<T>&); \
  template ConsumerFinding judge_view_position(const DepthSample<T>&, const Vector3<T>&,           \
                                               ConsumerArithmetic);                                \
  template ConsumerFinding judge_linear_depth(const DepthSample<T>&, T, ConsumerArithmetic);
OBLIQUE_DEPTH_JUDGES(float)
OBLIQUE_DEPTH_JUDGES(double)
OBLIQUE_DEPTH_JUDGES(long double)
#undef OBLIQUE_DEPTH_JUDGES

}  // namespace oblique::oracle
