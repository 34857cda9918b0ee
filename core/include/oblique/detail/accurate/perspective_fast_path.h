// The accurate method's fast path for the standard perspective shape: row 3 of M' in one pass of
// double-word arithmetic (plain double first for float; pairs of doubles for x87 long double),
// each entry accepted only where its rounding is certified; otherwise the refining path answers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

#include "oblique/depth_convention.h"
#include "oblique/detail/closed_form_steps.h"
#include "oblique/detail/config.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/error_free.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"

namespace oblique::detail {

/// Row 3 of M' and Q from the fast path for the standard perspective shape.
template <class T, class W>
struct PerspectiveAnswer {
  Vector4<T> row3;
  Vector4<W> far_corner;
};

/// What the perspective fast path reads: M11, M13, M22, M23, M33, M34, M43 as A, B, D, E, G, H,
/// K; C; the corner Q'; and the reciprocals it multiplies by instead of dividing.
template <class W>
struct PerspectiveInput {
  W K;
  std::array<W, 3> a, b, q_clip, c;  ///< A_i, B_i, Q'_i, C_i for i = x, y, w
  W c_z;
  std::array<W, 3> reciprocal;  ///< fl(1 / A_i)
  W k, s, t;                    ///< z_high - z_low, and near = s M_3 + t M_4
};

/// The fast paths' range condition, checked once on their input instead of on every value they
/// form: K and A_i nonzero, and every nonzero input (K, A_i, B_i, C) within 2^+-E of 1, with
/// E = max_exponent / 8 of W (p its precision). Then the products and quotients of up to three
/// inputs lie within 2^+-3E; N and V, once resolved (their bound, at least 2^-2p S, within
/// target / 32 of their size, with S at least one such term), above 2^-(3E + 2p); the entries,
/// k K C_i / N and K V / N, within 2^+-(5E + 2p); their exact rounding errors, 2p binades lower,
/// stay inside W's normal range (5E + 4p = 852 binades for double, of 1022), so every error-free
/// transformation is exact and every rounding relative. Inputs outside (subnormal
/// values, huge scales) take the refining path.
template <class W>
OBLIQUE_EFT_INLINE bool in_fast_range(const PerspectiveInput<W>& in) {
  constexpr int e = std::numeric_limits<W>::max_exponent / 8;
  bool ok = true;
  // zero_ok: whether x may be 0 (B_i and C_i may; K and A_i may not).
  const auto within = [&ok](W x, bool zero_ok) {
    if constexpr (std::is_same_v<W, double> && std::numeric_limits<double>::is_iec559) {
      // From the bits: the biased exponent within 1023 +- e, or x = +-0 where allowed.
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      bits &= ~(std::uint64_t(1) << 63);
      const std::uint64_t offset = (bits >> 52) - std::uint64_t(1023 - e);
      ok &= (zero_ok & (bits == 0)) | (offset <= std::uint64_t(2 * e));
    } else {
      constexpr W low = constant_power_of_two<W>(-e), high = constant_power_of_two<W>(e);
      const W size = std::abs(x);
      ok &= (zero_ok & (x == W(0))) | ((size >= low) & (size <= high));
    }
  };
  within(in.K, false);
  within(in.c_z, true);
  for (int i = 0; i < 3; ++i) {
    within(in.a[i], false);
    within(in.b[i], true);
    within(in.c[i], true);
  }
  return ok;
}

/// The fast path in plain arithmetic of a type W wider than T (double for float): the formulas of
/// perspective_row3 with one rounding per operation. With u = eps / 2 of W, each u_i = n_i (1 /
/// A_i) C_i is within 4u |u_i| (n_i rounded, the reciprocal, two products), the sums add 3u S, so N
/// and V are within 8u S; the entries then take up to three more roundings. Each entry is accepted
/// only when its whole error interval rounds to one T value (so the answer is the correctly rounded
/// one); std::nullopt otherwise, and the double-word path runs. The caller checks in_fast_range.
/// Written without a branch on the convention (t, and so V's use, changes from one request to
/// the next): V and both forms of the z entry are formed and one is chosen, and a single test
/// rejects; the same values as a branch per case. Its callers (accurate() and the accurate
/// method's ordinary path) are compiled for the build's target: not in perspective_row3()'s FMA
/// clone, where the compiler may contract a b + c into one FMA, so both run the same arithmetic
/// and certify the same requests.
template <class T, class W>
OBLIQUE_EFT_INLINE std::optional<Vector4<T>> perspective_row3_single(
    const PerspectiveInput<W>& in) {
  constexpr W u = std::numeric_limits<W>::epsilon() / W(2);
  W u_i[3];
  W magnitude = std::abs(in.c_z);
  for (int i = 0; i < 3; ++i) {
    u_i[i] = (in.q_clip[i] * in.K - in.b[i]) * in.reciprocal[i] * in.c[i];
    magnitude += std::abs(u_i[i]);
  }
  const W sum = (u_i[0] + u_i[1]) + u_i[2];
  const W big_n = sum + in.c_z;
  const W v = (in.k - in.t) * in.c_z - in.t * sum;
  const W error = W(8) * u * magnitude;
  const bool has_v = in.t != W(0);
  // C . Q = N / K must be positive; N's doubt below 1 settles its sign. N and V within 1/64.
  const bool unresolved = ((big_n > W(0)) != (in.K > W(0))) | !(W(64) * error <= std::abs(big_n)) |
                          (has_v & !(W(64) * error <= std::abs(v)));
  if (unresolved) return std::nullopt;
  const W reciprocal_n = W(1) / big_n;
  const W g = in.k * in.K * reciprocal_n;  // a 2^-shift
  const W z_entries[2] = {g * in.c_z, in.K * v * reciprocal_n};
  const Vector4<W> entries(g * in.c[0], g * in.c[1], z_entries[has_v], g * in.c[2]);
  // Relative doubt per entry: N's (error / |N|, first order, doubled for its own second order
  // and for the rounding of 1 / N), three roundings, and room for the roundings of x -+ spread
  // below. The z entry K V / N also carries V's: error / |V| of |K V / N|, error |K / N|.
  const W doubt = W(2) * error * std::abs(reciprocal_n) + W(6) * u;
  const W v_part = W(has_v) * (W(2) * error * std::abs(in.K * reciprocal_n));
  Vector4<T> row3;
  bool certified = true;
  for (int i = 0; i < 4; ++i) {
    const W x = in.s * entries(i);
    const W spread = doubt * std::abs(x) + (i == 2 ? v_part : W(0));
    const T below = static_cast<T>(x - spread), above = static_cast<T>(x + spread);
    certified &= below == above;
    row3(i) = below + T(0);  // +0 for a zero (as the plain methods give), below otherwise
  }
  if (!certified) return std::nullopt;
  return row3;
}

/// x87's long double (64-bit significand, 15-bit exponent), whose values split exactly into two
/// doubles: the perspective fast path computes in pairs of doubles (106 bits) there, in SSE
/// registers, instead of in double-word long double on the x87 stack (several times slower).
inline constexpr bool kX87LongDouble = std::numeric_limits<long double>::digits == 64 &&
                                       std::numeric_limits<long double>::max_exponent == 16384;

/// Half the spacing of T at y (finite, nonzero), towards zero where y is a power of two (the
/// spacing below is half that above), in W. From the bits for IEEE double in its normal range
/// and for x87 long double whose half spacing is a normal double (the fast paths' entries); from
/// the neighbours elsewhere.
template <class W, class T>
OBLIQUE_EFT_INLINE W half_spacing(T y) {
  if constexpr (std::is_same_v<T, double> && std::numeric_limits<double>::is_iec559) {
    std::uint64_t bits;
    std::memcpy(&bits, &y, sizeof bits);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    const bool power_of_two = (bits & ((std::uint64_t(1) << 52) - 1)) == 0;
    const int half = biased - 53 - (power_of_two ? 1 : 0);  // y in [2^e, 2^(e + 1)), e + 1023
    if (biased > 2 && half > 0) {
      const std::uint64_t half_bits = std::uint64_t(half) << 52;
      double out;
      std::memcpy(&out, &half_bits, sizeof out);
      return W(out);
    }
  } else if constexpr (std::is_same_v<T, long double> && kX87LongDouble) {
    // y = +-m 2^(e - 63), m in [2^63, 2^64): bytes 0-7 hold m, bytes 8-9 the sign and exponent.
    unsigned char bytes[sizeof(long double)];
    std::memcpy(bytes, &y, sizeof bytes);
    std::uint64_t significand;
    std::uint16_t sign_exponent;
    std::memcpy(&significand, bytes, 8);
    std::memcpy(&sign_exponent, bytes + 8, 2);
    const int e = (sign_exponent & 0x7fff) - 16383;  // y in [2^e, 2^(e + 1))
    const int half = e - 64 - (significand == (std::uint64_t(1) << 63) ? 1 : 0);
    if (half > -1022 && half < 1024) {
      const std::uint64_t half_bits = std::uint64_t(half + 1023) << 52;
      double out;
      std::memcpy(&out, &half_bits, sizeof out);
      return W(out);
    }
  }
  const T toward = std::nextafter(y, T(0));
  const T away = std::nextafter(
      y, y > T(0) ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
  return std::min(std::abs(W(y) - W(toward)), std::abs(W(away) - W(y))) / W(2);
}

/// The rounding y of x = hi + lo to T, when it is certified: the exact value lies within
/// `spread` of x, and |x - y| + spread stays below half the spacing of T at y (with room for the
/// roundings of this test), so the exact value rounds to y as well. +0 for x = 0 (as the plain
/// methods give); std::nullopt when not certified (or y is not finite).
template <class T, class W>
OBLIQUE_EFT_INLINE std::optional<T> certified_rounding(eft::Pair<W> x, W spread) {
  if (x.hi == W(0)) return T(0);
  const T y = eft::round_pair<T>(x);
  // x - y exactly enough: y as y_hi + y_lo in W (y_lo only where T is wider than W).
  const W y_hi = W(y);
  W y_lo = W(0);
  if constexpr (std::numeric_limits<T>::digits > std::numeric_limits<W>::digits)
    y_lo = W(y - T(y_hi));
  const W distance = std::abs((x.hi - y_hi) + (x.lo - y_lo));
  const W margin = W(1) - W(1) / W(1 << 20);
  if (!(distance + spread < margin * half_spacing<W>(y))) return std::nullopt;
  return y;
}

/// Row 3 from the double-word fast paths' entries x_i (before the sign s): each s x_i rounded to
/// T where certified_rounding() certifies it, the exact entry being within doubt |x_i| of x_i
/// (the z entry, i = 2, within doubt |x_2| + v_part); std::nullopt when any entry is not.
template <class T, class W>
OBLIQUE_EFT_INLINE std::optional<Vector4<T>> certified_row3(const eft::Pair<W> (&entries)[4], W s,
                                                            W doubt, W v_part) {
  Vector4<T> row3;
  for (int i = 0; i < 4; ++i) {
    const W spread = doubt * std::abs(entries[i].hi) + (i == 2 ? v_part : W(0));
    const auto y =
        certified_rounding<T>(eft::Pair<W>{s * entries[i].hi, s * entries[i].lo}, spread);
    if (!y) return std::nullopt;
    row3(i) = *y;
  }
  return row3;
}

/// x as hi + lo in doubles, exactly (hi the rounding of x, lo the at most 11 bits left), when
/// x is 0 or 2^+-E of 1, E = 128 (in_fast_range's for double); ok is cleared otherwise.
inline eft::Pair<double> long_double_pair(long double x, bool& ok) {
  constexpr double low = constant_power_of_two<double>(-128),
                   high = constant_power_of_two<double>(128);
  const double hi = static_cast<double>(x);
  const double size = std::abs(hi);
  if (hi != 0.0) {
    ok &= (size >= low) & (size <= high);
  } else {
    ok &= x == 0.0L;  // not a nonzero x below double's range
  }
  return {hi, static_cast<double>(x - static_cast<long double>(hi))};
}

/// The perspective fast path for x87 long double, in pairs of doubles: the formulas of
/// perspective_row3 with double-word operations on exact double pairs of the inputs. Error,
/// u = 2^-53: each u_i = (Q'_i K - B_i) / A_i C_i is within 3u^2 (the sum) + 28u^2 (quotient) +
/// 7u^2 (product) = 38u^2 of itself, and N and V's three additions add 3u^2 S each, so both are
/// within 48u^2 S, taken as 72u^2 S; each must be within 1/64 of its size. The entries take a
/// quotient and a product more (35u^2), plus N's and V's relative error (first order, doubled),
/// taken as 48u^2. An entry x is accepted when its rounding y to long double is certified: the
/// distance |x - y| plus that doubt stays below half the spacing at y, so the exact entry rounds
/// to y. std::nullopt otherwise (and for inputs outside long_double_pair's range).
template <class T, eft::Fma F>
OBLIQUE_EFT_INLINE std::optional<PerspectiveAnswer<T, T>> perspective_row3_in_doubles(
    const Vector4<T>& c, const Matrix4<T>& m, const Vector4<T>& corner, Convention convention) {
  static_assert(std::is_same_v<T, long double> && kX87LongDouble);
  using D = double;
  using P = eft::Pair<D>;
  constexpr D u = std::numeric_limits<D>::epsilon() / 2;
  bool ok = true;
  const P big_k = long_double_pair(m(3, 2), ok);
  const P a[3] = {long_double_pair(m(0, 0), ok), long_double_pair(m(1, 1), ok),
                  long_double_pair(m(2, 3), ok)};
  const P b[3] = {long_double_pair(m(0, 2), ok), long_double_pair(m(1, 2), ok),
                  long_double_pair(m(2, 2), ok)};
  const P cp[4] = {long_double_pair(c.x(), ok), long_double_pair(c.y(), ok),
                   long_double_pair(c.z(), ok), long_double_pair(c.w(), ok)};
  const D q_clip[3] = {D(corner.x()), D(corner.y()), D(corner.z())};
  const DepthRange range = clip_depth_range(convention);
  const RowCombination near_combination = near_rows(convention);
  const D k = D(range.z_high - range.z_low), s = D(near_combination.m3), t = D(near_combination.m4);
  if (!ok || big_k.hi == D(0) || a[0].hi == D(0) || a[1].hi == D(0) || a[2].hi == D(0) ||
      (t != D(0) && t != D(1)))
    return std::nullopt;
  const int c_index[3] = {0, 1, 3};
  P r[3], u_i[3];
  D magnitude = std::abs(cp[2].hi);
  for (int i = 0; i < 3; ++i) {
    const P n = eft::add(P{q_clip[i] * big_k.hi, q_clip[i] * big_k.lo}, P{-b[i].hi, -b[i].lo});
    r[i] = eft::divide<F>(n, a[i], D(1) / a[i].hi);
    u_i[i] = eft::multiply<F>(r[i], cp[c_index[i]]);
    magnitude += std::abs(u_i[i].hi);
  }
  const P sum = eft::add(eft::add(u_i[0], u_i[1]), u_i[2]);
  const P big_n = eft::add(sum, cp[2]);
  const D error = D(72) * u * u * magnitude;
  P v{D(0), D(0)};
  if (t != D(0)) v = eft::add(P{(k - t) * cp[2].hi, (k - t) * cp[2].lo}, P{-sum.hi, -sum.lo});
  if ((big_n.hi > D(0)) != (big_k.hi > D(0)) || !(D(64) * error <= std::abs(big_n.hi)) ||
      (t != D(0) && !(D(64) * error <= std::abs(v.hi))))
    return std::nullopt;
  const D reciprocal_n = D(1) / big_n.hi;
  const P g = eft::divide<F>(P{k * big_k.hi, k * big_k.lo}, big_n, reciprocal_n);
  P entries[4] = {eft::multiply<F>(g, cp[0]), eft::multiply<F>(g, cp[1]),
                  eft::multiply<F>(g, cp[2]), eft::multiply<F>(g, cp[3])};
  if (t != D(0)) entries[2] = eft::divide<F>(eft::multiply<F>(big_k, v), big_n, reciprocal_n);
  // As in perspective_row3_single: N's relative doubt on every entry, V's on the z entry.
  const D doubt = D(2) * error * std::abs(reciprocal_n) + D(48) * u * u;
  const D v_part = t != D(0) ? D(2) * error * std::abs(big_k.hi * reciprocal_n) : D(0);
  const std::optional<Vector4<T>> row3 = certified_row3<T>(entries, s, doubt, v_part);
  if (!row3) return std::nullopt;
  PerspectiveAnswer<T, T> out;
  out.row3 = *row3;
  const T reciprocal_k = T(1) / m(3, 2);
  for (int i = 0; i < 3; ++i) {
    out.far_corner(i == 2 ? 3 : i) = (T(r[i].hi) + T(r[i].lo)) * reciprocal_k;
  }
  out.far_corner(2) = reciprocal_k;
  return out;
}

/// The fast path's input in V: A_i, B_i, K and C converted exactly (V holds W's values), and
/// the reciprocals of the A_i.
template <class V, class W, class M>
OBLIQUE_EFT_INLINE PerspectiveInput<V> perspective_input(const Vector4<W>& c, const Matrix4<M>& m,
                                                         const Vector4<W>& corner,
                                                         Convention convention) {
  const ConventionTable<V>& constants = convention_table<V>(convention);  // closed_form.h's
  const V a_x = V(m(0, 0)), a_y = V(m(1, 1)), a_w = V(m(2, 3));
  return {V(m(3, 2)),
          {a_x, a_y, a_w},
          {V(m(0, 2)), V(m(1, 2)), V(m(2, 2))},
          {V(corner.x()), V(corner.y()), V(corner.z())},
          {V(c.x()), V(c.y()), V(c.w())},
          V(c.z()),
          {V(1) / a_x, V(1) / a_y, V(1) / a_w},
          constants.depth_span,
          constants.s,
          constants.t};
}

/// The fast path's first step where W is wider than T (float in double): perspective_row3_single()
/// and the far corner Q = (r_x, r_y, 1, r_w) / K from the same plain r_i = n_i (1 / A_i);
/// std::nullopt where an entry is not certified (perspective_row3() then runs its double-word
/// pass). The input must pass in_fast_range, with t = 0 or 1.
template <class T, class W>
OBLIQUE_EFT_INLINE std::optional<PerspectiveAnswer<T, W>> perspective_row3_plain(
    const PerspectiveInput<W>& in) {
  static_assert(std::numeric_limits<W>::digits > std::numeric_limits<T>::digits);
  const std::optional<Vector4<T>> row3 = perspective_row3_single<T>(in);
  if (!row3) return std::nullopt;
  W r[3];
  for (int i = 0; i < 3; ++i) r[i] = (in.q_clip[i] * in.K - in.b[i]) * in.reciprocal[i];
  const W reciprocal_k = W(1) / in.K;
  return PerspectiveAnswer<T, W>{*row3, Vector4<W>(r[0] * reciprocal_k, r[1] * reciprocal_k,
                                                   reciprocal_k, r[2] * reciprocal_k)};
}

/// The accurate method for the standard perspective shape without refining Q, where one pass of
/// double-word arithmetic resolves the answer. With Q' the clip-space corner, n_i = Q'_i K - B_i
/// (exact: Q'_i is 0, +-1/2 or +-1), r_i = n_i / A_i and u_i = C_i r_i for i = x, y, w
/// (B_i = B, E, G; A_i = A, D, H):
///   Q = (r_x, r_y, 1, r_w) / K,   N = K (C . Q) = u_x + u_y + C_z + u_w,
///   a C_i = k K C_i / N  where M4_i = 0 (i = x, y, w),
///   a C_z - t K = K ((k - t) C_z - t (u_x + u_y + u_w)) / N,
/// so the a C_z + 1 cancellation of the GL formula is removed algebraically. Divisions are
/// multiplications by reciprocals with a remainder correction (eft::divide with a reciprocal).
/// Error, u = eps / 2 of W: each u_i is within 20u^2 |u_i| (17u^2 from the quotient, 3u^2 from
/// the product) and the sums add under 18u^2 of S = |u_x| + |u_y| + |u_w| + |C_z|, so N and
/// the z numerator V are within 38u^2 S, taken as 64u^2 S; both must be within target / 32 of
/// their own size (target = eps of T), and the divisions and products after them add under
/// 32u^2, so each entry is within target / 8 of its value before its one rounding (faithful).
/// The input must pass in_fast_range. std::nullopt when any condition fails: a component lost to
/// the scaling, an input outside that range, an unresolved N or V, C . Q <= 0; the refining path
/// then answers.
template <class T, class W, eft::Fma F = eft::Fma::portable>
OBLIQUE_EFT_INLINE std::optional<PerspectiveAnswer<T, W>> perspective_row3(
    const ScaledPlane<W>& scaled, const Matrix4<T>& m, const Vector4<W>& corner,
    Convention convention) {
  if (scaled.lossy) return std::nullopt;
  constexpr W u = std::numeric_limits<W>::epsilon() / W(2);
  constexpr W target = W(std::numeric_limits<T>::epsilon());
  const Vector4<W>& c = scaled.c_hat;
  if constexpr (std::is_same_v<T, long double> && kX87LongDouble) {
    if (auto fast = perspective_row3_in_doubles<T, F>(c, m, corner, convention)) return fast;
  }
  const PerspectiveInput<W> in = perspective_input<W>(c, m, corner, convention);
  // V = (k - t) C_z - t U is formed for t = 1 (gl, reversed_z), where (k - t) C_z is exact.
  if ((in.t != W(0) && in.t != W(1)) || !in_fast_range(in)) return std::nullopt;
  const auto far_corner = [&in](const W(&r)[3]) {
    const W reciprocal_k = W(1) / in.K;
    return Vector4<W>(r[0] * reciprocal_k, r[1] * reciprocal_k, reciprocal_k, r[2] * reciprocal_k);
  };
  // float computes in double: the caller runs plain double arithmetic first
  // (perspective_row3_plain()), and this pass where that is not certified. (x87's long double
  // for double was tried the same way: its 11 extra bits left a quarter of the benchmark's cases
  // unresolved, and its arithmetic cost more than the double-word path.)
  eft::Pair<W> r[3], u_i[3];
  W magnitude = std::abs(in.c_z);
  for (int i = 0; i < 3; ++i) {
    const eft::Pair<W> n = eft::two_sum(in.q_clip[i] * in.K, -in.b[i]);
    r[i] = eft::divide<F>(n, in.a[i], in.reciprocal[i]);
    u_i[i] = eft::multiply<F>(r[i], in.c[i]);
    magnitude += std::abs(u_i[i].hi);
  }
  PerspectiveAnswer<T, W> out;
  const W r_hi[3] = {r[0].hi, r[1].hi, r[2].hi};
  out.far_corner = far_corner(r_hi);
  // U = u_x + u_y + u_w: TwoSum on the leading words, the rest summed plainly (Sum2).
  const eft::Pair<W> s1 = eft::two_sum(u_i[0].hi, u_i[1].hi);
  const eft::Pair<W> s2 = eft::two_sum(s1.hi, u_i[2].hi);
  const W u_rest = ((s1.lo + s2.lo) + (u_i[0].lo + u_i[1].lo)) + u_i[2].lo;
  const auto plus = [](W hi, W lo, W y) {  // hi + lo + y, as a pair
    const eft::Pair<W> sum = eft::two_sum(hi, y);
    return eft::two_sum(sum.hi, sum.lo + lo);
  };
  const eft::Pair<W> n = plus(s2.hi, u_rest, in.c_z);
  const W bound = W(64) * u * u * magnitude;
  const W resolution = target / W(32);
  // C . Q = N / K must be positive and resolved.
  if (n.hi == W(0) || (n.hi > W(0)) != (in.K > W(0)) || !(bound <= resolution * std::abs(n.hi)) ||
      !std::isfinite(magnitude))
    return std::nullopt;
  const W reciprocal_n = W(1) / n.hi;
  const eft::Pair<W> g = eft::divide<F>(eft::Pair<W>{in.k * in.K, W(0)}, n, reciprocal_n);
  eft::Pair<W> entries[4];
  for (int i = 0; i < 4; ++i) entries[i] = eft::multiply<F>(g, c(i));
  if (in.t != W(0)) {
    const eft::Pair<W> v = plus(-s2.hi, -u_rest, (in.k - in.t) * in.c_z);
    if (!(bound <= resolution * std::abs(v.hi))) return std::nullopt;
    const eft::Pair<W> kv = eft::multiply<F>(v, in.K);
    entries[2] = eft::divide<F>(kv, n, reciprocal_n);
  }
  // Each entry is within doubt of itself: N's relative error (first order, doubled for its own
  // second order and the rounding of 1 / N) and the quotient and product after it (31u^2,
  // taken as 48u^2); the z entry K V / N also V's, bound / |V| of it: bound |K / N|. Its
  // rounding y is certified when |x - y| plus that doubt stays below half the spacing of T at
  // y: the exact entry then rounds to y too (correct rounding, not only faithful).
  const W doubt = W(2) * bound * std::abs(reciprocal_n) + W(48) * u * u;
  const W v_part = in.t != W(0) ? W(2) * bound * std::abs(in.K * reciprocal_n) : W(0);
  const std::optional<Vector4<T>> row3 = certified_row3<T>(entries, in.s, doubt, v_part);
  if (!row3) return std::nullopt;
  out.row3 = *row3;
  return out;
}

/// perspective_row3 where the processor has an FMA that the build does not target: x86-64
/// builds for the baseline ISA, where two_prod would otherwise take Dekker's seventeen flops
/// (the FMA is two). Same exact products, so the same answer; chosen at run time.
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(__FMA__)
#define OBLIQUE_FMA_DISPATCH 1
template <class T, class W>
__attribute__((target("fma"))) std::optional<PerspectiveAnswer<T, W>> perspective_row3_fma(
    const ScaledPlane<W>& scaled, const Matrix4<T>& m, const Vector4<W>& corner,
    Convention convention) {
  return perspective_row3<T, W, eft::Fma::hardware>(scaled, m, corner, convention);
}

inline bool processor_has_fma() noexcept {
  return __builtin_cpu_supports("fma");
}
#endif

/// perspective_row3 with the processor's FMA when the build does not use it and it exists.
template <class T, class W>
std::optional<PerspectiveAnswer<T, W>> perspective_row3_dispatched(const ScaledPlane<W>& scaled,
                                                                   const Matrix4<T>& m,
                                                                   const Vector4<W>& corner,
                                                                   Convention convention) {
#if defined(OBLIQUE_FMA_DISPATCH)
  if constexpr (std::is_same_v<W, double> || (std::is_same_v<W, long double> && kX87LongDouble)) {
    if (processor_has_fma()) return perspective_row3_fma<T>(scaled, m, corner, convention);
  }
#endif
  return perspective_row3<T>(scaled, m, corner, convention);
}

}  // namespace oblique::detail
