// Every tolerance the project uses, in one place, as exact rationals derived from error bounds.
//
// u = 2^-p is the unit roundoff of the scalar type (p = 24, 53, 64 significand bits), and
// gamma(n) = n u / (1 - n u) bounds the relative error of n successive roundings (Higham, 3.1).
//
// A careful implementation computes, from exact inputs M and C,
//   Q   = M^-1 Q'   (closed form: 3 roundings per entry; LU solve: backward error gamma(3n)
//   |L||U|), d   = C . Q     (4 more roundings), a   = k / d     (k = 2 for gl, 1 for [0, 1]
//   depth), M'_3 = s (a C - t M_4)  (2 roundings per entry: the product and the difference).
// So the relative error of a is at most gamma(kScaleRoundings) * kappa, where kappa, the condition
// number of C . Q under relative perturbations of every entry of M and C, is
//   kappa = ( |C|.|Q| + |C|^T |M^-1| |M| |Q| + |C'|^T |M| |M^-1| |Q'| ) / (C . Q)
// (the last term covers a corner chosen from a C'_x or C'_y that rounding pushed across zero),
// and each entry of M'_3 carries gamma(kEntryRoundings) of its own. With eps = gamma(16) kappa
// bounding the relative error of C . Q, a = k / (C . Q) is within eps / (1 - eps) of itself
// relatively (not eps: the first-order bound fails as eps -> 1); at eps >= 1 the plane is within
// rounding of the far corner, a cannot be bounded, and the properties that depend on a (3 to 5 at
// the corners) are not judged there, while the status may be ok, plane_misses_view_volume or
// out_of_range.
#pragma once

#include <limits>
#include <optional>

#include "oblique/oracle/algebra.h"
#include "oblique/oracle/exact.h"

namespace oblique::oracle::tolerance {

/// Significand bits of the scalar type the implementation computes in.
template <class T>
constexpr int precision_bits() noexcept {
  return std::numeric_limits<T>::digits;
}

/// Roundings of a 4 x 4 solve by elimination: backward error gamma(3n), n = 4.
constexpr int kSolveRoundings = 12;

/// Roundings that reach the scale factor a: solve for Q and the dot product (4).
constexpr int kScaleRoundings = kSolveRoundings + 4;

/// Roundings in one entry of M'_3 given a: the product a C_i, the difference with M_4,
/// and one more for an implementation that forms k C_i / d instead of (k / d) C_i.
constexpr int kEntryRoundings = 3;

/// Property 1's allowance for what no rasterizer can see: a coefficient of near' may differ from
/// lambda C_i by kInvisiblePlaneUlps u lambda max_j |C_j| beyond its own rounding. That is a
/// normwise relative change of the plane below u, smaller than the rounding of its largest
/// coefficient when M' is stored in T: it moves a clip distance near' . v by at most
/// u lambda max|C| |v|_1, the size of the error a rasterizer evaluating near' . v in T makes at
/// a point whose large components meet C's large ones. It lets an implementation drop (or lose
/// to a power-of-two scaling) a component far below the plane's norm; a change of the plane a
/// rasterizer sees, u max|C| or more in one coefficient, is still a violation.
constexpr int kInvisiblePlaneUlps = 1;

// A row formed through another convention's: an engine may build the GL row and convert it,
// M'_3(zero_one) = (M'_3(gl) + M_4) / 2 (the same near plane). The GL row's entries are within
// gamma(2) (a_gl |C_i| + |M4_i|); the sum with M_4 rounds once more (u |a_gl C_i|, where M4_i is
// not 0; elsewhere it is exact) and the halving is exact, so with lambda = a_gl / 2 each entry is
// within gamma(3) (lambda |C_i| + |M4_i|): row 3's bound of every convention (Problem::row3_error,
// row3_accuracy), which property 1 now uses for [0, 1] too (it had no |M_4| term there). What a
// rasterizer sees of it: a [0, 1] rasterizer's near test evaluates M'_3 . v in float, a GL one
// M'_3 . v + M_4 . v; an |M_4| term in the row's error is the size of what the GL pipeline's own
// evaluation of w adds to its near test, and the tilt it allows (3e-7 on an orthographic box in
// float, where lambda C is small beside M_4w = 1) is no more than that.

/// The accurate method's promise: every entry of M' within this many units in the last place of
/// the correctly rounded exact answer (oracle::exact::ulp_distance).
constexpr double kAccurateUlps = 2;

// The code around the matrix (consumers.h) computes in T from inputs in T; its bounds:
//  - a solve with a projection (depth reconstruction, a view volume's corners): through an inverse
//    computed by elimination (|X^ - M^-1| <= gamma(3n) |M^-1| |L||U| |X^|, Higham 14.3) and
//    applied (n roundings), or an LU solve (backward error gamma(3n) |L||U|, the smaller); with
//    the window depth's conversion to NDC (2: a product and a difference) and the divide by w (1).
//    |L||U| is not bounded by |M| entry by entry (a zero of M, and projections have many, need
//    not be one of L U: fuzz_consumers found a reference 56,000 times off such a bound), but
//    with partial pivoting |l_ij| <= 1 and |u_ij| <= rho max|m|, rho <= 2^(n-1), so every entry
//    of |L||U| is at most n rho max|m| = 32 max|m| (lu_entry_bound()): the worst case, used for
//    the corners and the pass cameras. Depth reconstruction bounds it from the matrix at hand
//    instead (consumer_judging.cpp, solve_error()): |L^||U^| from the exact factors of every pivot
//    order rounding can choose, each computed factor within the elimination's error of its exact
//    value; and, for an inverse by cofactors (what Eigen, GLM and most engines do), each
//    cofactor within gamma(kCofactorRoundings) of the permanent of its minor of |M| and the
//    determinant within that of the permanent of |M|. The larger of the two gives
//    |v^ - v| <= S |b|, and the answer p with p v^_w within u |v^| of v^ (the divide) is judged
//    in homogeneous coordinates: that set stays bounded where rounding can reach w = 0.
//    Elsewhere p = v / v_w is within (|dv_i| + |p_i| |dv_w|) / (|v_w| - |dv_w|) + u |p_i|.
//  - a view volume's corner (corners_contain_kept): that solve's bound with M' (row 3's own error
//    bound carried through |M'^-1|) and with M (the original's corners, clipped by C), and, for a
//    point where C crosses an edge, gamma(kPlaneRoundings) |C| . |x| / max|n_C| across C.
//  - a plane from two rows (culling): 1 rounding per coefficient; normalised, 7 more (three
//    squares, two sums, the square root, the quotient): kPlaneRoundings.
//  - a pass camera's view (mirror: V R, R = I - 2 n n^T / |n|^2 with the normal normalised first
//    (8 roundings per component, two in a product) and 1 for the difference; portal: V F turn L^-1
//    with L^-1 by elimination, 12, bounded through |L^-1| G |L^-1|): the larger, 17, plus a
//    4-term product: kPassViewRoundings.
//  - the plane in a pass camera's space, W^-T P: an inverse by elimination (12) applied (4):
//    gamma(kCameraPlaneRoundings) |W^-T| G^T |W^-T| |P| (G as above, for W), and kPlaneRoundings
//    more for a plane the implementation normalises.
constexpr int kConsumerSolveRoundings = kSolveRoundings + 4 + 2;

// A consumer run on a GPU (a user's shader, oblique/shader): the shading language states each
// operation's precision, not IEEE's correct rounding everywhere (GLSL 4.50, 4.7.1; HLSL through
// SPIR-V the same on one driver):
//  - a + b, a - b, a * b, conversions: correctly rounded (u); a * b + c may be fused (one
//    rounding instead of two: no larger error);
//  - a / b, 1 / b: 2.5 ulp for |b| in [2^-126, 2^126]; an ulp of x is at most 2u |x|, so 5u;
//  - inverse(), determinant(): inherited from the operations they are made of (cofactors and a
//    quotient); inversesqrt: 2 ulp (4u), sqrt: inherited from it and a quotient;
//  - subnormal inputs and results may be flushed to 0.
// So every operation a depth reconstruction does errs by at most 5u < 2^3 u relatively, and its
// bounds are the CPU's with u replaced by 2^(kGpuLostBits - p): the arithmetic of a type with
// kGpuLostBits fewer significand bits. The GPU path leaves out what flushing to zero can change
// (a nonzero input below the smallest normal float) and divisors outside the stated range.
constexpr int kGpuLostBits = 3;

// A depth function handed the pixel as a GPU hands it (oblique/oracle/consumers.h,
// PixelInput::gpu: a texture coordinate, a fragment coordinate, a texel and the target's size)
// derives NDC itself; it is judged against the ray of the sample's NDC widened, in NDC x and y,
// by how far the NDC it can derive may be from it, in units u of its arithmetic (u >= 2^-24:
// 2^-24 for float, 2^-21 for a GPU's):
//  - handing: the sample's NDC is the position's rounded to float (|NDC| <= 1: 2^-25); a texture
//    coordinate is (NDC + 1) / 2 rounded to float (in [0, 1]: 2^-25, so 2^-24 in NDC); a fragment
//    coordinate is exact at a pixel's centre (px + 1/2) and (NDC + 1) / 2 W rounded to float off
//    it (2^-24 relative of at most W: 2^-23 in NDC); the size exact. At most 2^-25 + 2^-23 =
//    2.5 2^-24 <= 3u;
//  - deriving: q = position / size, or position times the size's reciprocal (set on the CPU,
//    rounded: 2^-24 <= u), with q <= 1: at most 3u; then 2 q - 1 (the factor 2 exact, the
//    difference at most u as |2 q - 1| <= 1): 2 (3u) + u = 7u. A flip (1 - 2 v, -y) is exact.
// So 3u + 7u: kPixelToNdcRoundings.
constexpr int kPixelToNdcRoundings = 10;

// A world position (judge_world_position()) is the view position carried through the pass
// camera's view V (world -> camera, affine) back to world space, h = V^-1 v; engines take one of
// two routes, and the answer is judged against the larger of their bounds, per coordinate of
// the homogeneous world point h (with |b| the NDC point's, S_X a solve's bound for X as above,
// dv the view solve's error with the pixel's handing, kPixelToNdcRoundings):
//  - through the view position (divided by w or not: dv + u (|v| + dv)) and the inverse view
//    (handed rounded, or inverted in T, then applied; or multiplied with M'^-1 first, then
//    applied): |V^-1| dv + (S_V + gamma(k) |V^-1|) (|M'^-1| |b| + dv), k =
//    kWorldViewRoundings: the inverse's rounding as handed (1), a 4-term matrix product (4) and
//    its application (4);
//  - through the inverse view-projection (M' V)^-1 as handed (computed on the CPU in double and
//    rounded: 1) and applied (4): gamma(kViewProjectionRoundings) |(M' V)^-1| |b|, and the
//    pixel's handing through its first two columns. A function that inverts M' V itself in
//    float is not given this bound: the componentwise condition of M' V grows with the square
//    of the camera's distance from the origin, and at a few thousand units such an inverse has
//    no correct digit left (its answers are caught; camera-relative matrices avoid it).
// The error E so bounded is carried into the camera's space by |V| (V's last row keeps w), with
// the divide's rounding u |V| (|h| + E) in x, y and z: the answer V p is judged against the
// camera-space segment there, as a view position is.
constexpr int kViewProjectionRoundings = 5;
constexpr int kWorldViewRoundings = 9;
constexpr int kPlaneRoundings = 8;
/// An inverse by cofactors: each cofactor a sum of six products of three (2 roundings each,
/// then 5 in a sum taken in order: 7); the determinant from a row and its cofactors (7, 1 for the
/// product, 3 for the sum: 11); the quotient, or a reciprocal and a product (1 more): 12, taken
/// for the cofactors and the determinant alike.
constexpr int kCofactorRoundings = 12;
constexpr int kPassViewRoundings = 17 + 4;
constexpr int kCameraPlaneRoundings = kSolveRoundings + 4;

/// n rho for n = 4 and partial pivoting's growth rho <= 2^(n-1): every entry of |L||U| for the
/// LU factors of m is at most kLuGrowth max|m| (above).
constexpr int kLuGrowth = 4 * 8;

/// kLuGrowth max|m|: the bound on every entry of |L||U| for the LU factors of m.
inline oracle::exact::Rational lu_entry_bound(const oracle::exact::Mat& m) {
  oracle::exact::Rational largest = 0;
  for (const auto& row : m)
    for (const auto& x : row) largest = std::max(largest, oracle::exact::abs(x));
  return kLuGrowth * largest;
}

/// eta = half the smallest subnormal of T: with gradual underflow a product or quotient that
/// lands in the subnormal range carries an absolute error up to eta besides its relative one
/// (fl(x op y) = (x op y)(1 + delta) + eta', |eta'| <= eta; sums and differences are exact there).
template <class T>
oracle::exact::Rational underflow_unit() {
  return oracle::exact::to_rational(std::numeric_limits<T>::denorm_min()) / 2;
}

/// u = 2^-p.
inline oracle::exact::Rational unit_roundoff(int precision_bits) {
  return oracle::exact::power_of_two(-precision_bits);
}

/// gamma(n) = n u / (1 - n u).
inline oracle::exact::Rational gamma(int n, int precision_bits) {
  const oracle::exact::Rational nu = n * unit_roundoff(precision_bits);
  return nu / (1 - nu);
}

// The bounds below are written once over the checker's arithmetic A (view_volume.h): the exact
// oracle's rationals (ExactArithmetic) and the filter's certified intervals (CertifiedArithmetic).
// A gives gamma(n), constant(x) and less(x, y); `underflow` is the underflow unit of T in the
// units of the quantity bounded (the filter scales its inputs by powers of two).

/// kappa's numerator (above) for a corner Q' = S Q of a matrix S: |C|.|Q| + |C|^T |S^-1| |S| |Q| +
/// |C'|^T |S| |S^-1| |Q'|, from the magnitudes |C|, |Q|, |C'|, |Q'|, |S| and |S^-1| (rationals,
/// or certified ranges of magnitudes).
template <class N>
N corner_dot_numerator(const algebra::Vec<N>& abs_c, const algebra::Vec<N>& abs_q,
                       const algebra::Vec<N>& abs_c_clip, const algebra::Vec<N>& abs_q_clip,
                       const algebra::Mat<N>& abs_s, const algebra::Mat<N>& abs_inverse) {
  return N(algebra::dot(abs_c, abs_q) +
           algebra::dot(abs_c, algebra::mul(abs_inverse, algebra::mul(abs_s, abs_q)))) +
         algebra::dot(abs_c_clip, algebra::mul(abs_s, algebra::mul(abs_inverse, abs_q_clip)));
}

/// The bound on the error of C . Q computed in T: gamma(kScaleRoundings) times kappa's numerator,
/// plus kScaleRoundings eta for underflow.
template <class A>
typename A::Num corner_dot_error(const typename A::Num& numerator,
                                 const typename A::Num& underflow) {
  return A::gamma(kScaleRoundings) * numerator + A::constant(kScaleRoundings) * underflow;
}

/// The bound on the relative error of a = k / (C . Q) from that of C . Q, eps = error / |C . Q|:
/// eps / (1 - eps) (not eps: the first-order bound fails as eps -> 1); none where eps >= 1.
template <class A>
std::optional<typename A::Num> scale_error(const typename A::Num& corner_dot_error,
                                           const typename A::Num& corner_dot) {
  using Num = typename A::Num;
  if (algebra::is_zero(corner_dot)) return std::nullopt;
  const Num eps = corner_dot_error / A::abs(corner_dot);
  if (!A::less(eps, A::constant(1))) return std::nullopt;
  return Num(eps / (A::constant(1) - eps));
}

/// The bound on one entry of M'_3 = s (a C_i - t M4_i) computed in T given a's relative error
/// `scale`: gamma(kEntryRoundings) (|a C_i| + |t M4_i|) + |a C_i| scale + kEntryRoundings eta.
template <class A>
typename A::Num row3_entry_bound(const typename A::Num& abs_ac, const typename A::Num& abs_m4,
                                 const typename A::Num& scale, const typename A::Num& underflow) {
  return A::gamma(kEntryRoundings) * (abs_ac + abs_m4) + abs_ac * scale +
         A::constant(kEntryRoundings) * underflow;
}

// The rasterizer (raster/, oblique::raster) evaluates M' v in float32, for a float32 point v with
// w = 1; the judge (in double, from the same float32 inputs, for a million samples a frame) uses
// these bounds, in doubles:
//  - a row r: M' rounded to float32 (1 rounding an entry) and a 4-term dot product (4, in any
//    order, fused or not): |fl(M'_r . v) - M'_r . v| <= gamma_f(kRasterRowRoundings) sum_i
//    |M'_ri v_i| + kRasterRowRoundings FLT_MIN (llvmpipe flushes subnormals to zero, an absolute
//    error up to FLT_MIN a rounding), plus the judge's own double evaluation of the same sum
//    (gamma_d(kRasterRowRoundings) of it): raster_row_gamma().
//  - a clip test alpha z + beta w >= 0 (alpha, beta in {0, 1, -1}): both rows' bounds, and one
//    rounding more (u (|z| + |w|)) for a renderer that forms the sum before comparing.
//  - a window position or depth, z / w: (dz + |z / w| dw) / (|w| - dw) from the rows' bounds dz,
//    dw, and kRasterDivideRoundings u |z / w| for the divide (a reciprocal and a product); the
//    viewport transform 1 rounding more (u); then the rasterizer snaps the window position to
//    its subpixel grid (OpenGL requires GL_SUBPIXEL_BITS >= 4; llvmpipe has 8), moving it by up
//    to kRasterSubpixel of a pixel: a sample is placed in its pixel only when that far from the
//    pixel's edges too (a point at exactly an edge is drawn into either pixel by the fill rule);
//    the buffer: fixed24 a whole quantum 1 / (2^24 - 1)
//    (rounded or truncated) and the read-back's conversion to float (u), float32 half an ulp (u
//    |d|) and FLT_MIN (flushed).
//  - every band is computed in double from positive terms (a few roundings, relative error below
//    2^-40): it is widened by kRasterBandSlack.
constexpr int kRasterRowRoundings = 5;
constexpr int kRasterDivideRoundings = 2;
constexpr double kRasterUnit = 0x1p-24;    ///< float32's u
constexpr double kRasterFlush = 0x1p-126;  ///< FLT_MIN: what a flushed subnormal loses
constexpr double kRasterBandSlack = 1 + 0x1p-40;
constexpr double kRasterFixed24Quantum = 1.0 / 16777215.0;
constexpr double kRasterSubpixel = 0x1p-4;  ///< a pixel's part: the coarsest grid OpenGL allows

/// gamma(kRasterRowRoundings) of float32 plus that of double: a row's relative bound (above).
constexpr double raster_row_gamma() noexcept {
  constexpr double nf = kRasterRowRoundings * kRasterUnit;
  constexpr double nd = kRasterRowRoundings * 0x1p-53;
  return (nf / (1 - nf) + nd / (1 - nd)) * kRasterBandSlack;
}

}  // namespace oblique::oracle::tolerance
