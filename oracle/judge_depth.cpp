// The depth judges (consumers.h): view_position and linear_depth, against the segment of the
// pixel's ray that the stored depth stands for, in exact arithmetic; compiled once for float,
// double and long double.
#include "consumer_judging.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"
#include "recent.h"

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

/// A closed interval of doubles that encloses a real number. Each operation rounds outward: one
/// step past the round-to-nearest result, which is within half a step of the exact one (or of
/// the exact one's nearest subnormal).
struct Interval {
  double lo = 0, hi = 0;
  bool finite() const { return std::isfinite(lo) && std::isfinite(hi); }
  /// The least and the largest |x| of x in the interval.
  double magnitude_below() const { return lo > 0 ? lo : hi < 0 ? -hi : 0; }
  double magnitude_above() const { return std::max(std::fabs(lo), std::fabs(hi)); }
};

double down(double x) {
  return std::nextafter(x, -std::numeric_limits<double>::infinity());
}
double up(double x) {
  return std::nextafter(x, std::numeric_limits<double>::infinity());
}
Interval operator+(const Interval& a, const Interval& b) {
  return {down(a.lo + b.lo), up(a.hi + b.hi)};
}
Interval operator-(const Interval& a, const Interval& b) {
  return {down(a.lo - b.hi), up(a.hi - b.lo)};
}
Interval operator*(const Interval& a, const Interval& b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {down(*std::min_element(p, p + 4)), up(*std::max_element(p, p + 4))};
}
Interval exactly(double x) {
  return {x, x};
}
/// A rational's enclosure: its double (mpq_get_d truncates toward zero) and the next one away
/// from zero, unless the double is the rational.
Interval enclosure(const Rational& r) {
  const double d = r.get_d();
  if (!std::isfinite(d)) return {-std::numeric_limits<double>::infinity(), d};  // not finite()
  if (r == d) return {d, d};
  const double away = r > 0 ? up(d) : down(d);
  return {std::min(d, away), std::max(d, away)};
}

constexpr const char* kNoAxis =
    "the camera does not look along z (M's fourth row is not (0, 0, a, b))";

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
/// Whether an input of the sample is nonzero and below T's smallest normal number.
template <class T>
bool has_subnormal_input(const DepthSample<T>& s) {
  const T smallest = std::numeric_limits<T>::min();
  auto subnormal = [&](T x) { return x != 0 && std::fabs(x) < smallest; };
  bool any = subnormal(s.ndc_x) || subnormal(s.ndc_y) || subnormal(s.depth);
  for (int i = 0; i < 16; ++i) any = any || subnormal(s.projection(i / 4, i % 4));
  return any;
}

template <class T>
std::string gpu_unbounded(const DepthSample<T>& s, const Rational& det, const Vec (&ends)[2]) {
  if (has_subnormal_input(s))
    return "an input below the smallest normal number, which a GPU may flush to 0";
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
/// inverse, M's axis, and the GPU's divisor M' determinant (a solve's exact error bound is
/// solve_error_of(), asked only by the exact path).
struct MatrixAnalysis {
  std::string why;  ///< not empty: no segment can be judged on these matrices
  Mat m, inv;
  Rational det;
  bool axis_is_z = true;
  int axis = -1;
  /// For the certified floating-point path (certified_holds()): M'^-1 enclosed entry by entry,
  /// the solve's bound from below, and whether they could be (every enclosure finite).
  bool enclosed = false;
  std::array<std::array<Interval, 4>, 4> inv_enclosure{};
  std::array<std::array<double, 4>, 4> error_below{};
  bool det_outside_gpu_range = false;  ///< |det M'| outside [2^-126, 2^126]
};

template <class T>
MatrixAnalysis analyse_matrices(const DepthSample<T>& s, int bits) {
  MatrixAnalysis out;
  const std::shared_ptr<const Inverse> projection = inverse_of(s.projection);
  const std::shared_ptr<const Inverse> original = inverse_of(s.original);
  out.m = projection->m;
  if (!projection->inv || !original->inv) {
    out.why = "a singular projection";
    return out;
  }
  out.inv = *projection->inv;
  // The view axis is z only where M's fourth row is (0, 0, a, b); elsewhere (a rotated or
  // general matrix) linear depth has no axis to be measured along.
  out.axis_is_z = original->m[3][0] == 0 && original->m[3][1] == 0;
  if (out.axis_is_z) out.axis = axis_sign_of(s.original, s.convention, bits);
  const std::shared_ptr<const SolveBound> bound = solve_bound_of(s.projection, bits);
  if (!bound->exists) {
    out.why =
        "the projection's determinant is within T's rounding of 0: its inverse is not "
        "determined in T";
    return out;
  }
  if (bits < oracle::tolerance::precision_bits<T>()) {
    out.det = determinant(out.m);
    out.det_outside_gpu_range = oracle::exact::abs(out.det) < oracle::exact::power_of_two(-126) ||
                                oracle::exact::abs(out.det) > oracle::exact::power_of_two(126);
  }
  out.enclosed = bound->ranged;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      out.inv_enclosure[i][j] = enclosure(out.inv[i][j]);
      out.error_below[i][j] = bound->range[i][j].lo;
      out.enclosed =
          out.enclosed && out.inv_enclosure[i][j].finite() && std::isfinite(out.error_below[i][j]);
    }
  }
  return out;
}

/// What a sample's judges key their kept analyses by: the sample's fields each analysis reads
/// (`view` only for the world position's) and the arithmetic's bits.
template <class T>
struct SampleKey {
  Matrix4<T> projection, original, view;
  Convention convention = Convention::gl;
  DepthBuffer buffer = DepthBuffer::fixed24;
  T ndc_x = 0, ndc_y = 0, ndc_error = 0, depth = 0;
  std::uint32_t stored = 0;
  int bits = 0;

  enum class Reads { matrices, ray, world };
  SampleKey() = default;
  SampleKey(const DepthSample<T>& s, int b, Reads reads)
      : projection(s.projection), original(s.original), convention(s.convention), bits(b) {
    view.setIdentity();
    if (reads == Reads::matrices) return;
    buffer = s.buffer;
    ndc_x = s.ndc_x;
    ndc_y = s.ndc_y;
    ndc_error = s.ndc_error;
    depth = s.depth;
    stored = s.stored;
    if (reads == Reads::world) view = s.view;
  }
  bool operator==(const SampleKey& o) const {
    return bits == o.bits && convention == o.convention && buffer == o.buffer && ndc_x == o.ndc_x &&
           ndc_y == o.ndc_y && ndc_error == o.ndc_error && depth == o.depth && stored == o.stored &&
           projection == o.projection && original == o.original && view == o.view;
  }
};

/// analyse_matrices() of the last matrices seen on this thread (Recent): a run asks many pixels
/// of one oblique matrix (a shader's batch, a scene's samples), and this is most of a sample's
/// exact analysis.
template <class T>
std::shared_ptr<const MatrixAnalysis> matrix_analysis_of(const DepthSample<T>& s, int bits) {
  thread_local Recent<SampleKey<T>, MatrixAnalysis, 4> recent;
  return recent.get(SampleKey<T>(s, bits, SampleKey<T>::Reads::matrices),
                    [&] { return analyse_matrices(s, bits); });
}

template <class T>
Segment ray_segment(const DepthSample<T>& s, int bits) {
  Segment out;
  const std::shared_ptr<const MatrixAnalysis> analysis = matrix_analysis_of(s, bits);
  const MatrixAnalysis& a = *analysis;
  if (!a.why.empty()) {
    out.why = a.why;
    return out;
  }
  out.axis_is_z = a.axis_is_z;
  out.axis = a.axis;
  const Mat* const inv = &a.inv;
  const std::shared_ptr<const std::optional<Mat>> exact_error = solve_error_of(s.projection, bits);
  const Mat* const error = &**exact_error;
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
    Vec dv = oracle::exact::mul(*error, oracle::exact::abs(b));
    // A position handed as a GPU hands it: the NDC the consumer derives is within ndc_error of
    // (x, y) in each, which M'^-1 carries to |M'^-1|'s first two columns times it.
    if (s.ndc_error != 0) {
      const Rational delta = oracle::exact::to_rational(s.ndc_error);
      for (int i = 0; i < 4; ++i)
        dv[i] += (oracle::exact::abs((*inv)[i][0]) + oracle::exact::abs((*inv)[i][1])) * delta;
    }
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

/// x / y for intervals, y away from 0 (its interval on one side), rounded outward.
Interval operator/(const Interval& x, const Interval& y) {
  const double q[4] = {x.lo / y.lo, x.lo / y.hi, x.hi / y.lo, x.hi / y.hi};
  return {down(*std::min_element(q, q + 4)), up(*std::max_element(q, q + 4))};
}

/// What the certified path of the depth judges knows of ray_segment(): its ends (homogeneous)
/// enclosed, and its box and the solve's part of it (dv) from below, which only makes holding
/// harder. Empty where the segment is a case ray_segment() leaves out, or might.
struct CertifiedSegment {
  std::array<Interval, 4> ends[2];
  std::array<Interval, 4> b[2];  ///< (x, y, z, 1) at each end: the window depth's z enclosed
  std::array<double, 4> box{0, 0, 0, 0}, dv_ends[2];
  double u = 0;  ///< the arithmetic's unit roundoff
  int axis = -1;
};

template <class T>
std::optional<CertifiedSegment> certified_segment(const DepthSample<T>& s, int bits) {
  if constexpr (std::numeric_limits<T>::digits > std::numeric_limits<double>::digits) {
    return std::nullopt;  // inputs a double cannot hold
  } else {
    const std::shared_ptr<const MatrixAnalysis> analysis = matrix_analysis_of(s, bits);
    const MatrixAnalysis& a = *analysis;
    if (!a.why.empty() || !a.enclosed) return std::nullopt;
    const bool gpu = bits < oracle::tolerance::precision_bits<T>();
    if (gpu && (a.det_outside_gpu_range || has_subnormal_input(s))) return std::nullopt;
    // The window depths the stored value stands for (depth_interval()), enclosed.
    Interval lo, hi;
    if (s.buffer == DepthBuffer::fixed24) {
      const double k = static_cast<double>(s.stored), steps = 16777215.0;  // 2^24 - 1
      const double l = (k - 0.5) / steps, h = (k + 0.5) / steps;
      lo = {down(l), up(l)};
      hi = {down(h), up(h)};
    } else {
      float f;
      std::memcpy(&f, &s.stored, sizeof f);
      // Sums of two neighbouring floats and their halves are exact in double.
      lo = exactly((static_cast<double>(f) + std::nextafter(f, -1.0f)) / 2);
      hi = exactly((static_cast<double>(f) + std::nextafter(f, 2.0f)) / 2);
    }
    const double read = static_cast<double>(s.depth);
    lo = {std::max(0.0, std::min(lo.lo, read)), std::max(0.0, std::min(lo.hi, read))};
    hi = {std::min(1.0, std::max(hi.lo, read)), std::min(1.0, std::max(hi.hi, read))};
    CertifiedSegment out;
    out.u = std::ldexp(1.0, -bits);
    out.axis = a.axis;
    for (int e = 0; e < 2; ++e) {
      const Interval window = e == 0 ? lo : hi;
      const Interval z = s.convention == Convention::gl ? exactly(2) * window - exactly(1) : window;
      out.b[e] = {exactly(static_cast<double>(s.ndc_x)), exactly(static_cast<double>(s.ndc_y)), z,
                  exactly(1)};
      const std::array<Interval, 4>& b = out.b[e];
      for (int i = 0; i < 4; ++i) {
        Interval v{0, 0};
        double dv = 0;
        for (int j = 0; j < 4; ++j) {
          v = v + a.inv_enclosure[i][j] * b[j];
          dv = std::max(
              0.0, down(dv + std::max(0.0, down(a.error_below[i][j] * b[j].magnitude_below()))));
        }
        if (s.ndc_error != 0) {
          // As ray_segment(): |M'^-1|'s first two columns times ndc_error, from below.
          const double delta = static_cast<double>(s.ndc_error);
          dv = std::max(
              0.0, down(dv + std::max(0.0, down(a.inv_enclosure[i][0].magnitude_below() * delta))));
          dv = std::max(
              0.0, down(dv + std::max(0.0, down(a.inv_enclosure[i][1].magnitude_below() * delta))));
        }
        if (!v.finite() || !std::isfinite(dv)) return std::nullopt;
        out.ends[e][i] = v;
        out.dv_ends[e][i] = dv;
        const double divide =
            i < 3 ? std::max(0.0, down(out.u * down(v.magnitude_below() + dv))) : 0.0;
        out.box[i] = std::max(out.box[i], std::max(0.0, down(dv + divide)));
      }
    }
    // The segment must be one ray_segment() judges: w of both ends away from 0, one sign (and,
    // on a GPU, within the range its quotient is stated for).
    const Interval& wa = out.ends[0][3];
    const Interval& wb = out.ends[1][3];
    if (!((wa.lo > 0 && wb.lo > 0) || (wa.hi < 0 && wb.hi < 0))) return std::nullopt;
    if (gpu) {
      const double low = std::ldexp(1.0, -126), high = std::ldexp(1.0, 126);
      for (const Interval* w : {&wa, &wb})
        if (w->magnitude_below() < low || w->magnitude_above() > high) return std::nullopt;
    }
    return out;
  }
}

/// Whether the point p (homogeneous, w = 1, each coordinate enclosed; an interval that holds 0
/// must be 0 exactly) provably lies within `box` of the segment `ends`: on_projected_segment() at
/// scale 1, shown by a witness t, a place on the segment where some lambda meets every
/// constraint for every value the enclosures allow. False where that cannot be shown (a close
/// call, or a violation): the exact path then decides.
bool certified_witness(const std::array<Interval, 4> (&ends)[2], const std::array<double, 4>& box,
                       const std::array<Interval, 4>& p, const std::vector<int>& coordinates) {
  std::array<int, 4> all{};
  std::size_t count = 0;
  for (int i : coordinates) all[count++] = i;
  all[count++] = 3;
  for (std::size_t k = 0; k < count; ++k) {
    const Interval& q = p[static_cast<std::size_t>(all[k])];
    if (!q.finite() || (q.lo <= 0 && q.hi >= 0 && !(q.lo == 0 && q.hi == 0))) return false;
  }
  // Where to look for a witness: the ends, and where the middles' constraint lines cross
  // (the double search of on_projected_segment(), without its verdict).
  std::array<double, 4> ma, mb, mp;
  for (int i = 0; i < 4; ++i) {
    ma[i] = (ends[0][i].lo + ends[0][i].hi) / 2;
    mb[i] = (ends[1][i].lo + ends[1][i].hi) / 2;
    mp[i] = (p[i].lo + p[i].hi) / 2;
  }
  // (At most 3 + 8 + 28 places: kept in place, this runs for every answer judged.)
  std::array<double, 40> candidates{0, 1, 0.5};
  std::size_t candidate_count = 3;
  {
    struct Line {
      double at0, slope;
    };
    std::array<Line, 8> lines{};
    std::size_t line_count = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const int i = all[k];
      const double d = mb[i] - ma[i];
      if (mp[i] == 0) {
        if (d != 0) {
          candidates[candidate_count++] = (-ma[i] - box[i]) / d;
          candidates[candidate_count++] = (-ma[i] + box[i]) / d;
        }
        continue;
      }
      lines[line_count++] = {(ma[i] - box[i]) / mp[i], d / mp[i]};
      lines[line_count++] = {(ma[i] + box[i]) / mp[i], d / mp[i]};
    }
    for (std::size_t i = 0; i < line_count; ++i)
      for (std::size_t j = i + 1; j < line_count; ++j)
        if (lines[i].slope != lines[j].slope)
          candidates[candidate_count++] =
              (lines[j].at0 - lines[i].at0) / (lines[i].slope - lines[j].slope);
  }
  auto witness = [&](double t) {
    double most = -std::numeric_limits<double>::infinity();
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < count; ++k) {
      const int i = all[k];
      const Interval v = ends[0][i] + exactly(t) * (ends[1][i] - ends[0][i]);
      if (p[i].lo == 0 && p[i].hi == 0) {
        if (!(v.magnitude_above() <= box[i])) return false;
        continue;
      }
      // lambda p_i within box_i of v_i(t) for every p_i and v_i the enclosures hold: lambda at
      // least the largest of (v_i - box_i) / p_i (p_i > 0; (v_i + box_i) / p_i for p_i < 0), and
      // at most the least of the other.
      const Interval below{down(v.lo - box[i]), up(v.hi - box[i])};
      const Interval above{down(v.lo + box[i]), up(v.hi + box[i])};
      const bool positive = p[i].lo > 0;
      const Interval floor = (positive ? below : above) / p[i];
      const Interval ceiling = (positive ? above : below) / p[i];
      most = std::max(most, floor.hi);
      least = std::min(least, ceiling.lo);
    }
    return most <= least;
  };
  for (std::size_t k = 0; k < candidate_count; ++k) {
    const double t = candidates[k];
    if (std::isfinite(t) && t >= 0 && t <= 1 && witness(t)) return true;
  }
  return false;
}

/// The ratio of an answer that holds, for the words: the least scale of the box that holds the
/// middles, to 2^-30.
double certified_ratio(const std::array<double, 4>& a, const std::array<double, 4>& b,
                       const std::array<double, 4>& box, const std::array<double, 4>& p,
                       const std::vector<int>& coordinates) {
  auto within = [&](double scale) {
    return on_projected_segment<double>(a, b, box, p, coordinates, scale);
  };
  double top = 1, bottom = 0;
  for (int k = 0; k < 30; ++k) {
    const double mid = (bottom + top) / 2;
    (within(mid) ? top : bottom) = mid;
  }
  return std::min(top, 1.0);
}

/// The middles of finite intervals (halved first: lo + hi may overflow).
std::array<double, 4> middles(const std::array<Interval, 4>& x) {
  return {x[0].lo * 0.5 + x[0].hi * 0.5, x[1].lo * 0.5 + x[1].hi * 0.5,
          x[2].lo * 0.5 + x[2].hi * 0.5, x[3].lo * 0.5 + x[3].hi * 0.5};
}

/// The certified floating-point path of view_position and linear_depth: whether the answer p
/// (homogeneous, w = 1, as doubles) provably holds (certified_segment(), certified_witness()).
/// Where it holds, the finding (its ratio and words from the enclosures' middles); none where it
/// cannot show that: the exact path then decides.
template <class T>
std::optional<ConsumerFinding> certified_holds(ConsumerCheck check, const DepthSample<T>& s,
                                               const std::array<double, 4>& p,
                                               const std::vector<int>& coordinates, int bits,
                                               const std::string& answered) {
  const bool linear = check == ConsumerCheck::linear_depth;
  if (linear) {
    const std::shared_ptr<const MatrixAnalysis> analysis = matrix_analysis_of(s, bits);
    const MatrixAnalysis& a = *analysis;
    if (!a.why.empty() || !a.axis_is_z || a.axis == 0) return std::nullopt;  // the exact path says
  }
  const std::optional<CertifiedSegment> seg = certified_segment(s, bits);
  if (!seg) return std::nullopt;
  const std::array<Interval, 4> point{exactly(p[0]), exactly(p[1]), exactly(p[2]), exactly(p[3])};
  if (!certified_witness(seg->ends, seg->box, point, coordinates)) return std::nullopt;
  // The finding, its numbers from the middles.
  ConsumerFinding f;
  f.check = check;
  const std::array<double, 4> ma = middles(seg->ends[0]), mb = middles(seg->ends[1]);
  f.ratio = certified_ratio(ma, mb, seg->box, p, coordinates);
  const double u = seg->u;
  Vec ea, eb;  // the ends divided by w, as Rationals for the words
  std::array<double, 3> bound{0, 0, 0};
  bool determined = true;
  for (int e = 0; e < 2; ++e) {
    const std::array<double, 4>& m = e == 0 ? ma : mb;
    const double w = std::fabs(m[3]), dw = seg->dv_ends[e][3];
    if (dw >= w) determined = false;
    for (int i = 0; i < 3; ++i) {
      const double q = m[i] / m[3];
      if (!std::isfinite(q)) return std::nullopt;  // the exact path has the words for it
      (e == 0 ? ea : eb)[i] = Rational(q);
      if (dw < w)
        bound[i] = std::max(bound[i],
                            (seg->dv_ends[e][i] + std::fabs(q) * dw) / (w - dw) + u * std::fabs(q));
    }
    (e == 0 ? ea : eb)[3] = 1;
  }
  f.points = {approx_point(ea), approx_point(eb)};
  f.points_what = "the ends of the pixel ray's segment the stored depth stands for";
  if (!linear) {
    f.points.insert(f.points.begin(), Eigen::Vector3d(p[0], p[1], p[2]));
    f.points_what = "the answer, and " + f.points_what;
  }
  const std::array<double, 4>& box = seg->box;
  std::string within_words;
  if (!determined) {
    within_words =
        "; a solve in T can reach w = 0 there, so the answer is judged in "
        "homogeneous coordinates: (x, y, z, w) within (" +
        protocol::format_number(box[0]) + ", " + protocol::format_number(box[1]) + ", " +
        protocol::format_number(box[2]) + ", " + protocol::format_number(box[3]) +
        ") of the segment's";
  } else if (coordinates.size() == 1) {
    within_words = ", within " + protocol::format_number(bound[2]);
  } else {
    within_words = ", each coordinate within (" + protocol::format_number(bound[0]) + ", " +
                   protocol::format_number(bound[1]) + ", " + protocol::format_number(bound[2]) +
                   ")";
  }
  f.detail =
      "answered " + answered +
      (linear ? "; the stored depth stands for linear depths from " +
                    text(Rational(seg->axis * ea[2])) + " to " + text(Rational(seg->axis * eb[2]))
              : "; the stored depth stands for the points from " + text(ea, 3) + " to " +
                    text(eb, 3)) +
      within_words;
  return f;
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

template <class T>
DepthSample<T> at_pixel(const DepthSample<T>& sample, Pixel target, Sampling sampling) {
  DepthSample<T> s = sample;
  if (target.width < 1 || target.height < 1) return s;
  // The pixel holding NDC v: floor((v + 1) / 2 size), the edges' pixels for what is outside.
  auto index = [](T v, int size) {
    const Rational at = (oracle::exact::to_rational(v) + 1) * size / 2;
    if (at < 0) return 0;
    const mpz_class floor = at.get_num() / at.get_den();  // truncation: at >= 0
    if (floor >= size) return size - 1;
    return static_cast<int>(floor.get_si());
  };
  auto centre = [](int p, int size) -> Rational {
    return Rational(2 * p + 1) / Rational(size) - 1;
  };
  s.pixel = target;
  s.pixel.x = index(sample.ndc_x, target.width);
  s.pixel.y = index(sample.ndc_y, target.height);
  s.pixel.at_centre = sampling == Sampling::pixels;
  if (s.pixel.at_centre) {
    // The centre: (2 p + 1) / size - 1.
    s.ndc_x = oracle::exact::round_to<T>(centre(s.pixel.x, target.width));
    s.ndc_y = oracle::exact::round_to<T>(centre(s.pixel.y, target.height));
  }
  return s;
}

template <class T>
T ndc_error_of(PixelInput input, ConsumerArithmetic arithmetic) {
  if (input == PixelInput::ndc) return 0;
  return std::ldexp(T(oracle::tolerance::kPixelToNdcRoundings), -arithmetic_bits<T>(arithmetic));
}

/// ray_segment() of the last samples judged on this thread (Recent): a round asks view_position
/// and linear_depth of the same sample, and its exact analysis is most of either judge's time.
template <class T>
std::shared_ptr<const Segment> ray_segment_of(const DepthSample<T>& s,
                                              ConsumerArithmetic arithmetic) {
  thread_local Recent<SampleKey<T>, Segment, 4> recent;
  const int bits = arithmetic_bits<T>(arithmetic);
  return recent.get(SampleKey<T>(s, bits, SampleKey<T>::Reads::ray),
                    [&] { return ray_segment(s, bits); });
}

template <class T>
ConsumerFinding judge_view_position(const DepthSample<T>& s, const Vector3<T>& answer,
                                    ConsumerArithmetic arithmetic, Arithmetic method) {
  if (method == Arithmetic::filtered && answer.allFinite()) {
    const std::array<double, 4> p{static_cast<double>(answer(0)), static_cast<double>(answer(1)),
                                  static_cast<double>(answer(2)), 1.0};
    if (auto f = certified_holds(ConsumerCheck::view_position, s, p, {0, 1, 2},
                                 arithmetic_bits<T>(arithmetic), numbers_text(answer)))
      return *f;
  }
  const std::shared_ptr<const Segment> segment = ray_segment_of(s, arithmetic);
  const Segment& seg = *segment;
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

namespace {

/// What judge_world_position() judges by: the sample's segment (ray_segment()) in the pass
/// camera's space, its box the larger of two routes' errors in world space (tolerance.h, world
/// position) carried back into that space by |view|; `view` exactly, to carry the answer there.
struct WorldSegment {
  Segment seg;
  Mat view;
};

template <class T>
WorldSegment world_segment(const DepthSample<T>& s, ConsumerArithmetic arithmetic) {
  const int bits = arithmetic_bits<T>(arithmetic);
  WorldSegment out;
  out.seg = *ray_segment_of(s, arithmetic);
  if (!out.seg.judged) return out;
  Segment& seg = out.seg;
  auto refuse = [&seg](const std::string& why) {
    seg.judged = false;
    seg.why = why;
  };
  const std::shared_ptr<const Inverse> view = inverse_of(s.view);
  const Mat& v = view->m;
  out.view = v;
  if (v[3][0] != 0 || v[3][1] != 0 || v[3][2] != 0 || v[3][3] != 1) {
    refuse("the view is not affine (its last row is not (0, 0, 0, 1))");
    return out;
  }
  const std::optional<Mat>& v_inv = view->inv;
  if (!v_inv) {
    refuse("a singular view");
    return out;
  }
  const std::shared_ptr<const MatrixAnalysis> analysis = matrix_analysis_of(s, bits);
  const MatrixAnalysis& a = *analysis;
  const std::shared_ptr<const std::optional<Mat>> projection_error =
      solve_error_of(s.projection, bits);
  const std::shared_ptr<const std::optional<Mat>> view_error_ptr = solve_error_of(s.view, bits);
  const std::optional<Mat>& view_error = *view_error_ptr;
  if (!view_error) {
    refuse(
        "the view's determinant is within T's rounding of 0: its inverse is not determined "
        "in T");
    return out;
  }
  // (M' view)^-1 = view^-1 M'^-1, exactly: the inverse view-projection as handed, rounded once.
  const Mat vp_inv = mul(*v_inv, a.inv);
  const Rational g_handed = gamma_of<T>(oracle::tolerance::kViewProjectionRoundings, bits);
  const Rational g_view = gamma_of<T>(oracle::tolerance::kWorldViewRoundings, bits);
  const Rational u = unit<T>(bits);
  const auto [lo, hi] = depth_interval(s);
  const Rational x = oracle::exact::to_rational(s.ndc_x), y = oracle::exact::to_rational(s.ndc_y);
  const Rational delta = oracle::exact::to_rational(s.ndc_error);
  const Mat abs_v = oracle::exact::abs(v), abs_v_inv = oracle::exact::abs(*v_inv);
  const Mat abs_inv = oracle::exact::abs(a.inv), abs_vp_inv = oracle::exact::abs(vp_inv);
  const Rational largest = oracle::exact::to_rational(std::numeric_limits<T>::max());
  Vec box{0, 0, 0, 0};
  const Rational depths[2] = {lo, hi};
  for (int e = 0; e < 2; ++e) {
    const Vec b{x, y, ndc_of(depths[e], s.convention), 1};
    const Vec abs_b = oracle::exact::abs(b);
    const Vec view_point = oracle::exact::mul(a.inv, b);
    const Vec world = oracle::exact::mul(*v_inv, view_point);
    // Through the view position: its solve's error (as ray_segment(), the pixel's handing
    // included, and its divide by w), carried by |view^-1|, and view^-1's own (handed rounded,
    // or inverted in T, and applied; or multiplied with M'^-1 first):
    // (S_view + gamma |view^-1|) (|M'^-1| |b| + dv).
    Vec dv = oracle::exact::mul(**projection_error, abs_b);
    const Vec reach_b = oracle::exact::mul(abs_inv, abs_b);
    Vec through_view, through_vp;
    for (int i = 0; i < 4; ++i) dv[i] += (abs_inv[i][0] + abs_inv[i][1]) * delta;
    // The view position may be divided by w before view^-1 is applied: (p^ v^_w, v^_w) is within
    // dv + u (|v| + dv) of v in x, y and z (the divide's rounding).
    for (int i = 0; i < 3; ++i) dv[i] += u * (oracle::exact::abs(view_point[i]) + dv[i]);
    Vec carried;
    for (int i = 0; i < 4; ++i) carried[i] = reach_b[i] + dv[i];
    const Vec route_a1 = oracle::exact::mul(abs_v_inv, dv);
    const Vec route_a2 = oracle::exact::mul(*view_error, carried);
    const Vec route_a3 = oracle::exact::mul(abs_v_inv, carried);
    // Through the inverse view-projection as handed: its rounding and its application, and
    // the pixel's handing carried by its first two columns.
    const Vec route_b = oracle::exact::mul(abs_vp_inv, abs_b);
    Vec error;
    for (int i = 0; i < 4; ++i) {
      through_view[i] = route_a1[i] + route_a2[i] + g_view * route_a3[i];
      through_vp[i] = g_handed * route_b[i] + (abs_vp_inv[i][0] + abs_vp_inv[i][1]) * delta;
      error[i] = std::max(through_view[i], through_vp[i]);
    }
    // Carried into the pass camera's space by |view| (its last row keeps w), with the divide's
    // rounding u |h^| in x, y and z.
    const Vec in_view = oracle::exact::mul(abs_v, error);
    Vec reach_h;
    for (int i = 0; i < 4; ++i) reach_h[i] = oracle::exact::abs(world[i]) + error[i];
    reach_h[3] = 0;
    const Vec divide = oracle::exact::mul(abs_v, reach_h);
    for (int i = 0; i < 4; ++i) {
      const Rational b_i = i < 3 ? Rational(in_view[i] + u * divide[i]) : error[3];
      box[i] = std::max(box[i], b_i);
      if (oracle::exact::abs(world[i]) + error[i] >= largest ||
          (world[3] != 0 && oracle::exact::abs(world[i] / world[3]) >= largest))
        seg.beyond_range = true;
    }
  }
  seg.box = box;
  seg.bound.reset();
  seg.w_reaches_zero =
      seg.box[3] >= std::min(oracle::exact::abs(seg.ha[3]), oracle::exact::abs(seg.hb[3]));
  return out;
}

/// world_segment() of the last samples judged on this thread (Recent; a shader's batch asks
/// many).
template <class T>
std::shared_ptr<const WorldSegment> world_segment_of(const DepthSample<T>& s,
                                                     ConsumerArithmetic arithmetic) {
  thread_local Recent<SampleKey<T>, WorldSegment, 4> recent;
  return recent.get(SampleKey<T>(s, arithmetic_bits<T>(arithmetic), SampleKey<T>::Reads::world),
                    [&] { return world_segment(s, arithmetic); });
}

/// The certified path of world_position: the answer carried into the pass camera's space by the
/// view (enclosed), judged as certified_holds() judges a view position, against
/// certified_segment()'s ends with world_segment()'s box from below (every term of both routes,
/// each rounded down). Where it holds, the finding (its numbers from the enclosures' middles);
/// none where it cannot show that: the exact path then decides.
template <class T>
std::optional<ConsumerFinding> certified_world_holds(const DepthSample<T>& s,
                                                     const Vector3<T>& answer, int bits) {
  if constexpr (std::numeric_limits<T>::digits > std::numeric_limits<double>::digits) {
    return std::nullopt;  // inputs a double cannot hold
  } else {
    // A view world_segment() judges by: affine, invertible, its inverse determined in T.
    if (s.view(3, 0) != 0 || s.view(3, 1) != 0 || s.view(3, 2) != 0 || s.view(3, 3) != 1)
      return std::nullopt;
    const std::shared_ptr<const Inverse> view = inverse_of(s.view);
    if (!view->inv) return std::nullopt;
    const std::shared_ptr<const SolveBound> view_error = solve_bound_of(s.view, bits);
    if (!view_error->exists || !view_error->ranged) return std::nullopt;
    const std::optional<CertifiedSegment> seg = certified_segment(s, bits);
    if (!seg) return std::nullopt;
    const std::shared_ptr<const MatrixAnalysis> analysis = matrix_analysis_of(s, bits);
    const MatrixAnalysis& a = *analysis;
    // Products and sums of magnitudes, from below.
    auto times = [](double x, double y) { return std::max(0.0, down(x * y)); };
    auto plus = [](double x, double y) { return std::max(0.0, down(x + y)); };
    std::array<std::array<Interval, 4>, 4> v_inv, vp_inv;
    std::array<std::array<double, 4>, 4> s_view, abs_v;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        v_inv[i][j] = enclosure((*view->inv)[i][j]);
        s_view[i][j] = view_error->range[i][j].lo;
        abs_v[i][j] = std::fabs(static_cast<double>(s.view(i, j)));
        if (!v_inv[i][j].finite() || !std::isfinite(s_view[i][j])) return std::nullopt;
      }
    }
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        Interval x{0, 0};
        for (int k = 0; k < 4; ++k) x = x + v_inv[i][k] * a.inv_enclosure[k][j];
        if (!x.finite()) return std::nullopt;
        vp_inv[i][j] = x;
      }
    }
    const double u = seg->u;
    const double g_handed =
        gamma_of<T>(oracle::tolerance::kViewProjectionRoundings, bits).get_d();  // truncated
    const double g_view = gamma_of<T>(oracle::tolerance::kWorldViewRoundings, bits).get_d();
    const double delta = static_cast<double>(s.ndc_error);
    std::array<double, 4> box{0, 0, 0, 0};
    for (int e = 0; e < 2; ++e) {
      const std::array<Interval, 4>& b = seg->b[e];
      const std::array<Interval, 4>& point = seg->ends[e];
      // As world_segment(), term by term.
      std::array<double, 4> dv = seg->dv_ends[e], carried, error;
      for (int i = 0; i < 3; ++i)
        dv[i] = plus(dv[i], times(u, plus(point[i].magnitude_below(), dv[i])));
      for (int i = 0; i < 4; ++i) {
        double reach_b = 0;
        for (int j = 0; j < 4; ++j)
          reach_b =
              plus(reach_b, times(a.inv_enclosure[i][j].magnitude_below(), b[j].magnitude_below()));
        carried[i] = plus(reach_b, dv[i]);
      }
      std::array<Interval, 4> world;
      for (int i = 0; i < 4; ++i) {
        double a1 = 0, a2 = 0, a3 = 0, route_b = 0;
        Interval w{0, 0};
        for (int j = 0; j < 4; ++j) {
          a1 = plus(a1, times(v_inv[i][j].magnitude_below(), dv[j]));
          a2 = plus(a2, times(s_view[i][j], carried[j]));
          a3 = plus(a3, times(v_inv[i][j].magnitude_below(), carried[j]));
          route_b = plus(route_b, times(vp_inv[i][j].magnitude_below(), b[j].magnitude_below()));
          w = w + v_inv[i][j] * point[j];
        }
        const double through_view = plus(plus(a1, a2), times(g_view, a3));
        const double through_vp = plus(
            times(g_handed, route_b),
            times(plus(vp_inv[i][0].magnitude_below(), vp_inv[i][1].magnitude_below()), delta));
        error[i] = std::max(through_view, through_vp);
        world[i] = w;
      }
      for (int i = 0; i < 4; ++i) {
        double in_view = 0, divide = 0;
        for (int j = 0; j < 4; ++j) {
          in_view = plus(in_view, times(abs_v[i][j], error[j]));
          if (j < 3)
            divide = plus(divide, times(abs_v[i][j], plus(world[j].magnitude_below(), error[j])));
        }
        const double b_i = i < 3 ? plus(in_view, times(u, divide)) : error[3];
        box[i] = std::max(box[i], b_i);
      }
      if (!std::isfinite(box[0] + box[1] + box[2] + box[3])) return std::nullopt;
    }
    // The answer in the pass camera's space: view (answer, 1), enclosed (w is 1 exactly).
    std::array<Interval, 4> p;
    for (int i = 0; i < 3; ++i) {
      Interval x = exactly(static_cast<double>(s.view(i, 3)));
      for (int j = 0; j < 3; ++j)
        x = x +
            exactly(static_cast<double>(s.view(i, j))) * exactly(static_cast<double>(answer(j)));
      p[static_cast<std::size_t>(i)] = x;
    }
    p[3] = exactly(1);
    if (!certified_witness(seg->ends, box, p, {0, 1, 2})) return std::nullopt;
    ConsumerFinding f;
    f.check = ConsumerCheck::world_position;
    const std::array<double, 4> ma = middles(seg->ends[0]), mb = middles(seg->ends[1]);
    const std::array<double, 4> mp = middles(p);
    f.ratio = certified_ratio(ma, mb, box, mp, {0, 1, 2});
    // The words, from the middles (the exact path's, in doubles).
    auto divided = [](const std::array<double, 4>& h) {
      return Vec{Rational(h[0] / h[3]), Rational(h[1] / h[3]), Rational(h[2] / h[3]), Rational(1)};
    };
    // Every number of the words finite (GMP has no infinity), else the exact path's words.
    for (const std::array<double, 4>* h : {&ma, &mb})
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite((*h)[i] / (*h)[3])) return std::nullopt;
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(mp[static_cast<std::size_t>(i)])) return std::nullopt;
    const Vec ea = divided(ma), eb = divided(mb);
    const Vec in_view{Rational(mp[0]), Rational(mp[1]), Rational(mp[2]), Rational(1)};
    const Vec wa = oracle::exact::mul(*view->inv, ea), wb = oracle::exact::mul(*view->inv, eb);
    f.points = {approx_point(in_view), approx_point(ea), approx_point(eb)};
    f.points_what =
        "the answer in the pass camera's space, and the ends of the pixel ray's segment the "
        "stored depth stands for";
    f.detail = "answered " + numbers_text(answer) + " (in the pass camera's space " +
               text(in_view, 3) + "); the stored depth stands for the world points from " +
               text(wa, 3) + " to " + text(wb, 3) + " (in that space " + text(ea, 3) + " to " +
               text(eb, 3) + "); judged there in homogeneous coordinates: (x, y, z, w) within (" +
               protocol::format_number(box[0]) + ", " + protocol::format_number(box[1]) + ", " +
               protocol::format_number(box[2]) + ", " + protocol::format_number(box[3]) +
               ") of the segment's";
    return f;
  }
}

}  // namespace

template <class T>
ConsumerFinding judge_world_position(const DepthSample<T>& s, const Vector3<T>& answer,
                                     ConsumerArithmetic arithmetic, Arithmetic method) {
  if (method == Arithmetic::filtered && answer.allFinite()) {
    if (auto f = certified_world_holds(s, answer, arithmetic_bits<T>(arithmetic))) return *f;
  }
  const std::shared_ptr<const WorldSegment> held = world_segment_of(s, arithmetic);
  const WorldSegment& world = *held;
  const Segment& seg = world.seg;
  if (auto early = before_the_answer(ConsumerCheck::world_position, seg, answer.allFinite(),
                                     !answer.array().isFinite().any(), numbers_text(answer)))
    return *early;
  // The answer in the pass camera's space, exactly: view (answer, 1).
  const Vec in_view = oracle::exact::mul(world.view, point_of(answer));
  ConsumerFinding f;
  f.check = ConsumerCheck::world_position;
  const auto [ok, ratio] = judge_on_segment(seg, in_view, {0, 1, 2});
  f.holds = ok;
  f.ratio = ratio;
  f.points = {approx_point(in_view), approx_point(seg.a), approx_point(seg.b)};
  f.points_what =
      "the answer in the pass camera's space, and the ends of the pixel ray's segment the stored "
      "depth stands for";
  const std::shared_ptr<const Inverse> view = inverse_of(s.view);
  const Vec wa = oracle::exact::mul(*view->inv, seg.a), wb = oracle::exact::mul(*view->inv, seg.b);
  f.detail = "answered " + numbers_text(answer) + " (in the pass camera's space " +
             text(in_view, 3) + "); the stored depth stands for the world points from " +
             text(wa, 3) + " to " + text(wb, 3) + " (in that space " + text(seg.a, 3) + " to " +
             text(seg.b, 3) + "); judged there in homogeneous coordinates: (x, y, z, w) within " +
             text(seg.box, 4) + " of the segment's";
  return f;
}

template <class T>
ConsumerFinding judge_linear_depth(const DepthSample<T>& s, T answer, ConsumerArithmetic arithmetic,
                                   Arithmetic method) {
  if (method == Arithmetic::filtered && std::isfinite(answer)) {
    const std::shared_ptr<const MatrixAnalysis> analysis =
        matrix_analysis_of(s, arithmetic_bits<T>(arithmetic));
    const MatrixAnalysis& a = *analysis;
    if (a.why.empty() && !a.axis_is_z) {
      // No axis to measure along, whatever the pixel (the exact path says the same after the
      // segment's own reasons, which need no pixel's analysis here).
      ConsumerFinding f;
      f.check = ConsumerCheck::linear_depth;
      f.judged = false;
      f.detail = kNoAxis;
      return f;
    }
    const std::array<double, 4> p{0, 0, a.axis * static_cast<double>(answer), 1};
    if (auto f = certified_holds(ConsumerCheck::linear_depth, s, p, {2},
                                 arithmetic_bits<T>(arithmetic), protocol::format_number(answer)))
      return *f;
  }
  const std::shared_ptr<const Segment> segment = ray_segment_of(s, arithmetic);
  const Segment& seg = *segment;
  if (auto early = before_the_answer(ConsumerCheck::linear_depth, seg, std::isfinite(answer),
                                     !std::isfinite(answer), protocol::format_number(answer)))
    return *early;
  ConsumerFinding f;
  f.check = ConsumerCheck::linear_depth;
  if (!seg.axis_is_z) {
    f.judged = false;
    f.detail = kNoAxis;
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
  template DepthSample<T> at_pixel(const DepthSample<T>&, Pixel, Sampling);                        \
  template T ndc_error_of<T>(PixelInput, ConsumerArithmetic);                                      \
  template ConsumerFinding judge_view_position(const DepthSample<T>&, const Vector3<T>&,           \
                                               ConsumerArithmetic, Arithmetic);                    \
  template ConsumerFinding judge_linear_depth(const DepthSample<T>&, T, ConsumerArithmetic,        \
                                              Arithmetic);                                         \
  template ConsumerFinding judge_world_position(const DepthSample<T>&, const Vector3<T>&,          \
                                                ConsumerArithmetic, Arithmetic);
OBLIQUE_DEPTH_JUDGES(float)
OBLIQUE_DEPTH_JUDGES(double)
OBLIQUE_DEPTH_JUDGES(long double)
#undef OBLIQUE_DEPTH_JUDGES

}  // namespace oblique::oracle
