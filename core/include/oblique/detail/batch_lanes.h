// apply_batch()'s closed form over a block of requests at once: the requests' entries gathered
// into one array per entry (structure of arrays), every step of the closed form
// (detail::closed_form(), detail/closed_form.h) for the common request written as one loop over the
// block with no branch, so that the compiler runs it on packed registers (two doubles or four
// floats to an SSE2 instruction at the x86-64 baseline, the divisions included) and several
// requests' chains of divisions are in flight at once. A request that passes every test of that
// loop is answered from it; every other one by the one-request path, as before.
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "oblique/detail/closed_form_steps.h"
#include "oblique/detail/config.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"

namespace oblique::detail {

/// Whether apply_batch() answers blocks of closed-form requests with closed_form_lanes(): for
/// IEEE float and double where Eigen vectorises Vector4<T> with SSE (x86), whose C . Q adds the
/// four products as (c_0 q_0 + c_2 q_2) + (c_1 q_1 + c_3 q_3) (a packet sum, then the sum of its
/// halves: Eigen's redux and predux for Packet2d, Packet4d and Packet4f), the order the lanes
/// use; and not where the compiler may contract a product and a sum into a fused multiply-add
/// (FMA enabled), which it might do differently in the lanes and in the closed form
/// (detail::closed_form(), detail/closed_form.h). Elsewhere apply_batch() answers request by
/// request.
template <class T>
constexpr bool closed_form_lanes_available() noexcept {
#if defined(EIGEN_VECTORIZE_SSE2) && !defined(EIGEN_DONT_VECTORIZE) && !defined(__FMA__)
  constexpr bool ieee_float_or_double = std::is_same_v<T, float> || std::is_same_v<T, double>;
  return ieee_float_or_double && ExponentBits<T>::known;
#else
  return false;
#endif
}

/// Requests per block: four SSE2 registers' worth.
template <class T>
inline constexpr int closed_form_lane_count = 64 / int(sizeof(T));

/// sign(x) (detail/closed_form_steps.h), the same value (+0 for zeros and NaN), from two
/// comparisons both made, so that the compiler can run it on packed registers (it does not make a
/// comparison that a branch skips, which may trap, unconditional).
template <class T>
OBLIQUE_ALWAYS_INLINE T lane_sign(T x) noexcept {
  return T(x > T(0)) - T(x < T(0));
}

/// closed_form_lanes()'s answers for a block: fast[k] != 0 where request k is answered here
/// (status ok, row 3 of M' row3[.][k], far corner q[.][k] if asked for); nothing else is
/// meaningful. (fast is a T, 1 or 0: a select between two integers under a mask from comparing
/// doubles has no SSE2 instruction, and would keep the loop from being packed.)
template <class T, int W>
struct ClosedFormLanes {
  T row3[4][W];
  T q[4][W];
  T fast[W];
};

/// A block's entries, one array each (closed_form_lanes() reads them): A..K the perspective
/// shape's entries M11, M13, M22, M23, M33, M34, M43, m3j = M4j, outside the bits of the nine
/// entries outside the shape or-ed together, sign cleared, as a T; cx..cw the plane.
template <class T, int W>
struct LaneInputs {
  T A[W], B[W], D[W], E[W], G[W], H[W], K[W], m30[W], m31[W], m33[W], outside[W];
  T cx[W], cy[W], cz[W], cw[W];
};

/// the closed form (detail::closed_form(), detail/closed_form.h) for the W requests of `in` in the
/// convention of `table` (a ConventionTable<T>, with AcFirst = table.first == 0: M'_3 = a C - t
/// M_4, else t M_4 - a C; a template parameter, as a subtraction in each arm of a branch, which may
/// trap, would keep the compiler from packing the loop), without a branch: every lane computes
/// every step, and fast[k] is set only where request k passes tests that imply each of apply()'s
/// and the closed form (detail::closed_form(), detail/closed_form.h)'s tests on its way to status
/// ok, so that the lane's row3 and q (q only with FarCorner) are that path's, bit for bit (the same
/// operations, in the same order, on the same operands). The tests, which may refuse more than that
/// path does (those requests go to it) but never less:
///
/// - ordinary_input(): the nine entries outside the perspective shape are zeros (their bits,
///   sign cleared, or-ed together, are those of +0); the sum of the magnitudes of A, B, D, E, G,
///   H, K (M11, M13, M22, M23, M33, M34, M43) and of C's components is at most the largest
///   finite T (no NaN, no infinity); lo, the smallest of |A|, |D|, |H|, |K|, |C_w| and of the
///   nonzero |B|, |E|, |G|, |C_x|, |C_y|, |C_z|, is normal (so A, D, H, K, C_w are nonzero: also
///   closed_form's singularity test, and every nonzero entry is normal); hi < lo_m 2^S, hi and
///   lo_m the largest and the smallest nonzero magnitude of the seven entries, S =
///   max_magnitude_spread<T>(), implies (floor log2 hi) - (floor log2 lo_m) <= S (a product
///   overflowing to infinity only where lo_m >= 2^(max_exponent - S), where the fields differ by
///   less than S anyway); C_w < 0 (the camera test).
/// - the plane's scaling by 2^-e (e = frexp exponent of max |C_i|, built from its bits):
///   max |C_i| < 2^(1 - min_exponent) gives a normal 2^-e, and max |C_i| < min nonzero |C_i|
///   2^-min_exponent the exponents' difference that keeps every scaled component normal.
/// - Q finite, C . Q finite and positive, a = a_hat 2^-e finite and normal (so a C is
///   the operand), row 3 finite (each as a sum of magnitudes at most the largest finite T).
/// - near_plane_kept_by_signs(): near_z and C_z not of opposite signs; with
///   K = (1 - min_exponent) / 3, |a C_w| >= 2^-K, |c_hat_w| >= 2^-K and the largest of the
///   near plane's |a C_x|, |a C_y|, |a C_w|, |near_z| below 2^K: all normal, and
///   L(a C_w) + L(C_w) - L(largest) - e - 2 = L(a C_w) + L(c_hat_w) - L(largest) - 2
///   >= (1 - K) + (1 - K) - K - 2 = -3K >= min_exponent - 1.
///
/// On those lanes A and C_w are nonzero and C_w < 0, so sgn A = copysign(1, A), and
/// sgn C'_z = sgn C_w sgn H > 0 exactly when H < 0 (the corner's z is z_high, else z_low).
/// KPowerOfTwo: every K of the block is +-2^n with 2^-n normal (gather_lanes()).
template <class T, int W, bool AcFirst, bool KPowerOfTwo, bool FarCorner, class Table>
OBLIQUE_ALWAYS_INLINE void closed_form_lanes(const LaneInputs<T, W>& in, const Table& table,
                                             ClosedFormLanes<T, W>& out) {
  using Bits = typename ExponentBits<T>::Bits;
  using limits = std::numeric_limits<T>;
  constexpr int fraction_bits = ExponentBits<T>::fraction_bits;
  constexpr Bits exponent_mask = Bits(ExponentBits<T>::all_ones) << fraction_bits;
  constexpr Bits magnitude_mask = ~Bits(0) >> 1;
  constexpr Bits sign_mask = ~magnitude_mask;
  // The bits of 2^-n are (2 bias - f) << fraction_bits for the field f of 2^n.
  constexpr Bits inverse_base = Bits(2 * ExponentBits<T>::bias) << fraction_bits;
  // The bits of 2^-e are (2 bias - 1 - f) << fraction_bits for the field f of max |C_i|.
  constexpr Bits factor_base = Bits(2 * ExponentBits<T>::bias - 1) << fraction_bits;
  constexpr T lowest = limits::min(), highest = limits::max(), infinity = limits::infinity();
  constexpr T spread_factor = constant_power_of_two<T>(max_magnitude_spread<T>());
  constexpr T plane_high_limit = constant_power_of_two<T>(1 - limits::min_exponent);
  constexpr T plane_spread_factor = constant_power_of_two<T>(-limits::min_exponent);
  constexpr int sign_test_exponent = (1 - limits::min_exponent) / 3;
  constexpr T sign_test_high = constant_power_of_two<T>(sign_test_exponent);
  constexpr T sign_test_low = constant_power_of_two<T>(-sign_test_exponent);

  const T *const A = in.A, *const B = in.B, *const D = in.D, *const E = in.E, *const G = in.G,
                 *const H = in.H, *const K = in.K, *const m30 = in.m30, *const m31 = in.m31,
                 *const m33 = in.m33, *const outside = in.outside, *const cx = in.cx,
                 *const cy = in.cy, *const cz = in.cz, *const cw = in.cw;
  const T z_low = table.corner_z[0], z_high = table.corner_z[2];
  const T depth_span = table.depth_span, s = table.s, t = table.t;
  // Two loops over the block, each packed by the compiler: the tests on the input and Q; then
  // C . Q, a, row 3 and the tests on them. (In one loop, a lane's chain of divisions, Q's and
  // then a's, would hold back the lanes after it.)
  T qs[4][W], c_hats[4][W], factors[W], oks[W];
  for (int k = 0; k < W; ++k) {
    const T a_abs = std::abs(A[k]), b_abs = std::abs(B[k]), d_abs = std::abs(D[k]),
            e_abs = std::abs(E[k]), g_abs = std::abs(G[k]), h_abs = std::abs(H[k]),
            k_abs = std::abs(K[k]);
    const T x_abs = std::abs(cx[k]), y_abs = std::abs(cy[k]), z_abs = std::abs(cz[k]),
            w_abs = std::abs(cw[k]);
    const T total = ((a_abs + b_abs) + (d_abs + e_abs)) + ((g_abs + h_abs) + k_abs) +
                    ((x_abs + y_abs) + (z_abs + w_abs));
    const T b_nonzero = b_abs == T(0) ? infinity : b_abs;
    const T e_nonzero = e_abs == T(0) ? infinity : e_abs;
    const T g_nonzero = g_abs == T(0) ? infinity : g_abs;
    const T x_nonzero = x_abs == T(0) ? infinity : x_abs;
    const T y_nonzero = y_abs == T(0) ? infinity : y_abs;
    const T z_nonzero = z_abs == T(0) ? infinity : z_abs;
    const T hi = std::max(std::max(std::max(a_abs, d_abs), std::max(h_abs, k_abs)),
                          std::max(std::max(b_abs, e_abs), g_abs));
    const T lo = std::min(std::min(std::min(a_abs, d_abs), std::min(h_abs, k_abs)),
                          std::min(std::min(b_nonzero, e_nonzero), g_nonzero));
    const T plane_high = std::max(std::max(x_abs, y_abs), std::max(z_abs, w_abs));
    const T plane_low = std::min(std::min(x_nonzero, y_nonzero), std::min(z_nonzero, w_abs));
    bool ok = (outside[k] == T(0)) & (total <= highest) & (std::min(lo, plane_low) >= lowest) &
              (hi < lo * spread_factor) & (cw[k] < T(0)) & (plane_high < plane_high_limit) &
              (plane_high < plane_low * plane_spread_factor);
    Bits high_bits;
    std::memcpy(&high_bits, &plane_high, sizeof high_bits);
    const Bits factor_bits = factor_base - (high_bits & exponent_mask);
    T factor;
    std::memcpy(&factor, &factor_bits, sizeof factor);
    // the closed form (detail::closed_form(), detail/closed_form.h) from here, step for step.
    const T c_hat[4] = {cx[k] * factor, cy[k] * factor, cz[k] * factor, cw[k] * factor};
    const T corner_z = H[k] < T(0) ? z_high : z_low;
    // B / K, E / K, G / K and 1 / K; for K = +-2^n (with 2^-n normal: KPowerOfTwo), 1 / K is
    // +-2^-n exactly, built from K's bits, and x / K and x (1 / K) are the same exact number
    // rounded once, so the same T: three divisions of eight fewer.
    T b_k, e_k, g_k, k_inverse;
    if constexpr (KPowerOfTwo) {
      Bits k_bits;
      std::memcpy(&k_bits, &K[k], sizeof k_bits);
      const Bits inverse_bits = (k_bits & sign_mask) | (inverse_base - (k_bits & exponent_mask));
      std::memcpy(&k_inverse, &inverse_bits, sizeof k_inverse);
      b_k = B[k] * k_inverse, e_k = E[k] * k_inverse, g_k = G[k] * k_inverse;
    } else {
      k_inverse = T(1) / K[k];
      b_k = B[k] / K[k], e_k = E[k] / K[k], g_k = G[k] / K[k];
    }
    const T q[4] = {(lane_sign(cx[k]) * std::copysign(T(1), A[k]) - b_k) / A[k],
                    (lane_sign(cy[k]) * std::copysign(T(1), D[k]) - e_k) / D[k], k_inverse,
                    (corner_z - g_k) / H[k]};
    const T q_total = (std::abs(q[0]) + std::abs(q[1])) + (std::abs(q[2]) + std::abs(q[3]));
    ok &= (q_total <= highest) & (std::abs(c_hat[3]) >= sign_test_low);
    for (int i = 0; i < 4; ++i) {
      qs[i][k] = q[i];
      c_hats[i][k] = c_hat[i];
    }
    factors[k] = factor;
    oks[k] = ok ? T(1) : T(0);
  }
  for (int k = 0; k < W; ++k) {
    const T d = (c_hats[0][k] * qs[0][k] + c_hats[2][k] * qs[2][k]) +
                (c_hats[1][k] * qs[1][k] + c_hats[3][k] * qs[3][k]);
    const T a_hat = depth_span / d;
    const T a = a_hat * factors[k];
    // A C . Q below min_settled_dot() goes apart, to the one-request path, which hands it to the
    // accurate method where underflow took it (dot_lost_to_underflow()).
    bool ok = (oks[k] != T(0)) & (d >= min_settled_dot<T>()) & (d <= highest);
    const T ac[4] = {a * cx[k], a * cy[k], a * cz[k], a * cw[k]};
    const T t_m4[4] = {t * m30[k], t * m31[k], t * K[k], t * m33[k]};
    T row3[4];
    for (int i = 0; i < 4; ++i) {
      if constexpr (AcFirst) {
        row3[i] = ac[i] - t_m4[i];
      } else {
        row3[i] = t_m4[i] - ac[i];
      }
    }
    const T row3_total =
        (std::abs(row3[0]) + std::abs(row3[1])) + (std::abs(row3[2]) + std::abs(row3[3]));
    const T near_z = s * row3[2] + t_m4[2];
    const T largest = std::max(std::max(std::abs(ac[0]), std::abs(ac[1])),
                               std::max(std::abs(ac[3]), std::abs(near_z)));
    ok &= (std::abs(a) >= lowest) & (std::abs(a) <= highest) & (row3_total <= highest) &
          !((std::min(near_z, cz[k]) < T(0)) & (std::max(near_z, cz[k]) > T(0))) &
          (largest < sign_test_high) & (std::abs(ac[3]) >= sign_test_low);
    for (int i = 0; i < 4; ++i) {
      out.row3[i][k] = row3[i];
      if constexpr (FarCorner) out.q[i][k] = qs[i][k];
    }
    out.fast[k] = ok ? T(1) : T(0);
  }
}

/// A block's entries from its requests, and whether every K is +-2^n with 2^-n normal
/// (its fraction bits zero, |K| normal and at most 2^(max_exponent - 2)).
template <class T, int W>
OBLIQUE_ALWAYS_INLINE bool gather_lanes(const Matrix4<T>* m, const Vector4<T>* c,
                                        LaneInputs<T, W>& in) {
  using Bits = typename ExponentBits<T>::Bits;
  constexpr Bits magnitude_mask = ~Bits(0) >> 1;
  constexpr Bits fraction_mask = (Bits(1) << ExponentBits<T>::fraction_bits) - 1;
  constexpr T k_high = constant_power_of_two<T>(std::numeric_limits<T>::max_exponent - 2);
  T *const A = in.A, *const B = in.B, *const D = in.D, *const E = in.E, *const G = in.G,
           *const H = in.H, *const K = in.K, *const m30 = in.m30, *const m31 = in.m31,
           *const m33 = in.m33, *const outside = in.outside, *const cx = in.cx, *const cy = in.cy,
           *const cz = in.cz, *const cw = in.cw;
  for (int k = 0; k < W; ++k) {
    const Matrix4<T>& mk = m[k];
    A[k] = mk(0, 0), B[k] = mk(0, 2), D[k] = mk(1, 1), E[k] = mk(1, 2);
    G[k] = mk(2, 2), H[k] = mk(2, 3), K[k] = mk(3, 2);
    m30[k] = mk(3, 0), m31[k] = mk(3, 1), m33[k] = mk(3, 3);
    const T nine[9] = {mk(0, 1), mk(0, 3), mk(1, 0), mk(1, 3), mk(2, 0),
                       mk(2, 1), m30[k],   m31[k],   m33[k]};
    Bits any = 0;
    for (const T x : nine) {
      Bits bits;
      std::memcpy(&bits, &x, sizeof bits);
      any |= bits;
    }
    any &= magnitude_mask;
    std::memcpy(&outside[k], &any, sizeof any);
    cx[k] = c[k].x(), cy[k] = c[k].y(), cz[k] = c[k].z(), cw[k] = c[k].w();
  }
  Bits k_fraction = 0;
  bool k_in_range = true;
  for (int k = 0; k < W; ++k) {
    Bits bits;
    std::memcpy(&bits, &K[k], sizeof bits);
    k_fraction |= bits & fraction_mask;
    k_in_range &= (std::abs(K[k]) >= std::numeric_limits<T>::min()) & (std::abs(K[k]) <= k_high);
  }
  return k_fraction == 0 && k_in_range;
}

/// closed_form_lanes() for the W requests m[k], c[k] in the convention of `table`.
template <class T, int W, bool FarCorner, class Table>
OBLIQUE_ALWAYS_INLINE void closed_form_block(const Matrix4<T>* m, const Vector4<T>* c,
                                             const Table& table, ClosedFormLanes<T, W>& out) {
  LaneInputs<T, W> in;
  const bool k_power_of_two = gather_lanes<T, W>(m, c, in);
  if (table.first == 0) {
    if (k_power_of_two) {
      closed_form_lanes<T, W, true, true, FarCorner>(in, table, out);
    } else {
      closed_form_lanes<T, W, true, false, FarCorner>(in, table, out);
    }
  } else {
    if (k_power_of_two) {
      closed_form_lanes<T, W, false, true, FarCorner>(in, table, out);
    } else {
      closed_form_lanes<T, W, false, false, FarCorner>(in, table, out);
    }
  }
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__)) && !defined(__AVX2__)
/// closed_form_block() built for AVX2 beside the baseline build (GCC and Clang on x86 without
/// AVX2 at baseline): four doubles or eight floats to an instruction, the same operations and
/// so the same roundings (AVX2 brings no fused multiply-add). apply_batch() runs it where the
/// processor has AVX2 (closed_form_block_avx2_supported()).
#define OBLIQUE_BATCH_AVX2 1
template <class T, int W, bool FarCorner, class Table>
__attribute__((target("avx2"))) void closed_form_block_avx2(const Matrix4<T>* m,
                                                            const Vector4<T>* c, const Table& table,
                                                            ClosedFormLanes<T, W>& out) {
  closed_form_block<T, W, FarCorner>(m, c, table, out);
}

inline bool closed_form_block_avx2_supported() noexcept {
  static const bool supported = __builtin_cpu_supports("avx2");
  return supported;
}
#else
inline bool closed_form_block_avx2_supported() noexcept {
  return false;
}
#endif

/// closed_form_block(), built for AVX2 where `avx2` (closed_form_block_avx2_supported()).
template <class T, int W, bool FarCorner, class Table>
OBLIQUE_ALWAYS_INLINE void closed_form_block_on(bool avx2, const Matrix4<T>* m, const Vector4<T>* c,
                                                const Table& table, ClosedFormLanes<T, W>& out) {
#ifdef OBLIQUE_BATCH_AVX2
  if (avx2) {
    closed_form_block_avx2<T, W, FarCorner>(m, c, table, out);
    return;
  }
#else
  (void)avx2;
#endif
  closed_form_block<T, W, FarCorner>(m, c, table, out);
}

}  // namespace oblique::detail
