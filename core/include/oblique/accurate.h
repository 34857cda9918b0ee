// The accurate method: the same answer as closed_form / general, with every entry of M'_3 close
// to the exactly rounded value of the exact answer (aim: correct rounding; measured by
// `oblique report accuracy` against the GMP oracle, checked by the property suite at 2 ulp).
//
// Where the plain methods lose accuracy, and what this one does instead:
//  - Q = M^-1 Q' rounds in every component: here Q is refined to two words (one for float's
//    closed form, up to five where needed), each correction solved from a residual
//    Q' - M (q_0 + ...) summed as in K-fold precision;
//  - C . Q cancels when C passes close to the far corner: distilled to its exact value from
//    exact products;
//  - a = range / (C . Q) rounds: kept as a double-word quotient;
//  - a C_i - t M4_i cancels when C is close to the standard near plane (the a C_z + 1 of the
//    paper's GL formula): formed as (k C_i - t M4_i (C . Q)) / (C . Q) from exact products,
//    rounded once;
//  - stiff planes (components spanning more binades than the type holds, or pushed below the
//    range by the power-of-two scaling), signs of C' within their error bound of zero, and what
//    five words of Q do not resolve: the exact answer (exact_cramer.h).
// float runs in double (float products are exact there and nothing under- or overflows); double
// and long double run in their own type with double-word arithmetic.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "oblique/depth_convention.h"
#include "oblique/equilibrated_solver.h"
#include "oblique/error_free.h"
#include "oblique/plane.h"

namespace oblique::detail {

/// The type the accurate method computes in for a given scalar type.
template <class T>
struct AccurateWorkingType {
  using type = T;
};
template <>
struct AccurateWorkingType<float> {
  using type = double;
};

/// Q = x_0 + x_1 + ... + x_{n-1} with M Q = rhs, refined from exact residuals:
/// x_0 = solve(rhs), x_j = solve(rhs - M (x_0 + ... + x_{j-1})), the residual summed as in
/// (j + 1)-fold precision. Each word is about eps times the last (the closed form's solve has a
/// few roundings; the equilibrated LU is refined to a small componentwise backward error).
/// The most words the far corner is refined to.
inline constexpr int kMaxCornerWords = 5;

template <class W, class Solve>
class RefinedCorner {
 public:
  static constexpr int kMaxWords = kMaxCornerWords;

  /// Keeps M's nonzero entries only: the residuals skip its zeros.
  RefinedCorner(const Matrix4<W>& m, const Vector4<W>& rhs, Solve solve)
      : rhs_(rhs), solve_(std::move(solve)) {
    for (int i = 0; i < 4; ++i) {
      nonzero_[i] = 0;
      for (int col = 0; col < 4; ++col) {
        if (m(i, col) != W(0)) {
          columns_[i][nonzero_[i]] = col;
          negated_[i][nonzero_[i]++] = -m(i, col);
        }
      }
    }
    words_[0] = solve_(rhs_);
    count_ = 1;
  }

  int count() const { return count_; }
  const Vector4<W>& word(int k) const { return words_[k]; }
  bool finite() const { return all_finite(words_[0]); }

  /// Adds the next correction; false when there is no room or it would not be finite.
  bool add_word() {
    if (count_ == kMaxWords) return false;
    Vector4<W> residual;
    for (int i = 0; i < 4; ++i) {
      eft::Terms<W, 1 + 2 * 4 * kMaxWords> terms;
      terms.add(rhs_(i));
      for (int k = 0; k < count_; ++k) {
        for (int j = 0; j < nonzero_[i]; ++j) {
          terms.add_product(negated_[i][j], words_[k](columns_[i][j]));
        }
      }
      residual(i) = terms.sum(count_ + 1);
    }
    const Vector4<W> next = solve_(residual);
    if (!all_finite(next)) return false;
    words_[count_++] = next;
    return true;
  }

  /// An estimate of |w| . |Q - (x_0 + ... + x_{n-1})|, the error left in the words weighted by
  /// w: the last word's weighted size times the contraction per refinement step, measured from
  /// the last two words but never below `contraction_floor` (a bound the solve's conditioning
  /// gives); the floor times the weighted size of Q while there is one word; 0 when the last
  /// correction is exactly zero (Q is then exact).
  W remaining_error(const Vector4<W>& weights, W contraction_floor) const {
    const W last = weights.cwiseAbs().dot(words_[count_ - 1].cwiseAbs());
    if (!(last > W(0))) return W(0);
    if (count_ < 2) return last * contraction_floor;  // the first solve's own error
    const W before = weights.cwiseAbs().dot(words_[count_ - 2].cwiseAbs());
    const W measured = before > W(0) ? last / before : W(1);
    return last * std::min(W(1), std::max(measured, contraction_floor));
  }

  /// The sum of the words, rounded.
  Vector4<W> value() const {
    Vector4<W> sum = words_[count_ - 1];
    for (int k = count_ - 2; k >= 0; --k) sum += words_[k];
    return sum;
  }

 private:
  Vector4<W> rhs_;
  Solve solve_;
  std::array<std::array<W, 4>, 4> negated_{};  ///< -M_i,col for the nonzero entries of row i
  std::array<std::array<int, 4>, 4> columns_{};
  std::array<int, 4> nonzero_{};
  std::array<Vector4<W>, kMaxWords> words_{};
  int count_ = 0;
};

/// The products C_i x_k,i of C with every word of Q, exact (two terms each) but for the last
/// word's, whose rounding errors are below eps times its own small contribution.
template <class W>
using DotTerms = eft::Terms<W, 2 * 4 * kMaxCornerWords>;

template <class W, class Corner>
DotTerms<W> dot_terms(const Vector4<W>& plane, const Corner& q) {
  // Smallest first (the last word's products, then each word's product errors, then the first
  // word's products): the error-free passes then settle in fewer rounds.
  DotTerms<W> terms;
  const int last = q.count() - 1;
  for (int i = 0; i < 4; ++i) terms.add(plane(i) * q.word(last)(i));
  eft::Pair<W> products[DotTerms<W>::capacity() / 2];
  for (int k = last - 1; k >= 0; --k) {
    for (int i = 0; i < 4; ++i) products[4 * k + i] = eft::two_prod(plane(i), q.word(k)(i));
  }
  for (int k = last - 1; k >= 0; --k) {
    for (int i = 0; i < 4; ++i) terms.add(products[4 * k + i].lo);
  }
  for (int k = last - 1; k >= 0; --k) {
    for (int i = 0; i < 4; ++i) terms.add(products[4 * k + i].hi);
  }
  return terms;
}

/// Row 3 of M' and whether every entry is resolved (within an ulp of the exact answer): when
/// not, Q needs another word.
template <class T, class W>
struct AccurateRow3 {
  Vector4<T> row3;
  bool resolved = true;
  W corner_dot = W(0);  ///< C . Q, distilled: its sign is exact for the words of Q
};

/// What scaling C by 2^shift cost: `lost` holds C_i (unscaled) where C_i 2^shift is not exact
/// (it fell below the normal range), 0 elsewhere.
template <class W>
struct ScaledPlane {
  Vector4<W> c_hat;
  Vector4<W> lost = Vector4<W>::Zero();
  int shift = 0;
  bool lossy() const { return (lost.array() != W(0)).any(); }
};

template <class W>
ScaledPlane<W> scale_plane(const Vector4<W>& c, int shift) {
  ScaledPlane<W> out;
  out.shift = shift;
  out.c_hat = scaled_by_power_of_two(c, shift);
  for (int i = 0; i < 4; ++i) {
    // A normal result is exact; below the normal range it may be.
    if (c(i) != W(0) && !(std::abs(out.c_hat(i)) >= std::numeric_limits<W>::min()) &&
        std::ldexp(out.c_hat(i), -shift) != c(i))
      out.lost(i) = c(i);
  }
  return out;
}

/// Row 3 of M', s (a C_i - t M4_i) with a = range / (C . Q), each entry rounded once to T.
///  - Where t M4_i = 0 it is s range C_i / (C . Q), from a double-word quotient.
///  - Elsewhere it is s N_i / (C . Q) with N_i = range C_i - t M4_i (C . Q) summed from exact
///    products, which removes the cancellation of a C_i against t M4_i (the a C_z + 1 of the GL
///    formula) instead of rounding into it: from C . Q's double-word value where that resolves
///    N_i, else from M4_i times each term of C . Q.
/// Every sum is distilled to its exact value; what is left is Q's own error, `q_part` (an
/// estimate of |C| . |Q error|), which must stay below eps / 8 of C . Q and of each N_i; a
/// C . Q <= 0 is resolved when that error cannot lift it above zero.
/// Precondition: scaling C lost nothing (not scaled.lossy()).
template <class T, class W>
AccurateRow3<T, W> accurate_row3(const ScaledPlane<W>& scaled, const DotTerms<W>& terms, W q_part,
                                 const Vector4<W>& m4, Convention convention) {
  const Vector4<W>& plane = scaled.c_hat;
  constexpr W eps = std::numeric_limits<W>::epsilon();
  // What the answer in T needs resolved: eps of T (float computes in double and needs less).
  constexpr W target = W(std::numeric_limits<T>::epsilon());
  const DepthRange range = clip_depth_range(convention);
  const W k = W(range.z_high - range.z_low);
  const RowCombination near_combination = near_rows(convention);
  const W s = W(near_combination.m3), t = W(near_combination.m4);
  AccurateRow3<T, W> out;
  DotTerms<W> d_terms = terms;
  bool exact = false;
  const eft::Pair<W> d = d_terms.distil(exact);
  out.corner_dot = d.hi;
  // Not distilled: fall back on SumK's bound for 8 passes, (n eps)^8 of the magnitude.
  const W sum_part = exact ? W(0) : terms.magnitude() * std::pow(W(terms.size()) * eps, 8);
  const W d_error = q_part + sum_part + eps * std::abs(d.lo);
  if (!(d.hi > W(0)) || !std::isfinite(d.hi)) {
    out.resolved = !std::isfinite(d.hi) || d_error < std::abs(d.hi) || d_error == W(0);
    return out;
  }
  out.resolved = d_error <= target / W(8) * d.hi;
  const eft::Pair<W> a = eft::divide(eft::Pair<W>{k, W(0)}, d.hi);
  const W lo_ratio = d.lo / d.hi;
  const W a_lo = a.lo - a.hi * lo_ratio;  // k / (hi + lo) to first order in lo / hi
  for (int i = 0; i < 4; ++i) {
    const W tm4 = t * m4(i);
    eft::Pair<W> entry;
    if (tm4 == W(0)) {
      const eft::Pair<W> ac = eft::two_prod(a.hi, plane(i));
      entry = eft::fast_two_sum(s * ac.hi, s * (ac.lo + a_lo * plane(i)));
    } else {
      eft::Terms<W, 5> fast;
      fast.add(k * plane(i));  // k = 1 or 2: exact
      fast.add_product(-tm4, d.hi);
      fast.add_product(-tm4, d.lo);
      eft::Pair<W> numerator = fast.distil(exact);
      if (!exact || std::abs(tm4) * d_error > target / W(8) * std::abs(numerator.hi)) {
        eft::Terms<W, 1 + 2 * DotTerms<W>::capacity()> slow;
        slow.add(k * plane(i));
        for (std::size_t j = 0; j < terms.size(); ++j) slow.add_product(-tm4, terms[j]);
        // As added: distil rewrites the terms and drops zero ones.
        const std::size_t slow_size = slow.size();
        const W slow_magnitude = slow.magnitude();
        numerator = slow.distil(exact);
        const W slow_sum_part = exact ? W(0) : slow_magnitude * std::pow(W(slow_size) * eps, 8);
        const W bound = std::abs(tm4) * q_part + slow_sum_part;
        if (bound > target / W(8) * std::abs(numerator.hi)) out.resolved = false;
      }
      const eft::Pair<W> quotient = eft::divide(numerator, d.hi);
      entry = eft::fast_two_sum(s * quotient.hi, s * (quotient.lo - quotient.hi * lo_ratio));
    }
    out.row3(i) = eft::round_pair<T>(entry);
    if (out.row3(i) == T(0)) out.row3(i) = T(0);  // +0, as the plain methods give
  }
  return out;
}

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

/// Values the fast path can vouch for: 0, or finite and 2p binades above the underflow threshold,
/// where the error-free transformations are exact and every rounding is relative.
template <class W>
struct RangeCheck {
  static constexpr W low = eft::power_of_two<W>(std::numeric_limits<W>::min_exponent +
                                                2 * std::numeric_limits<W>::digits + 2);
  bool ok = true;
  void operator()(W x) {
    const W size = std::abs(x);
    ok &= (x == W(0)) | ((size >= low) & (size <= std::numeric_limits<W>::max()));
  }
};

/// The fast path in W's own precision, for T = float in W = double (53 bits against 24): the
/// formulas of perspective_row3 with one rounding per operation. With u = eps / 2 of W, each
/// u_i = n_i (1 / A_i) C_i is within 4u |u_i| (n_i rounded, the reciprocal, two products), the
/// sums add 3u S, so N and V are within 8u S; the entries then take up to three more roundings.
/// Each entry is accepted only when its whole error interval rounds to one T value (so the
/// answer is the correctly rounded one); std::nullopt otherwise, and the double-word path runs.
template <class T, class W>
std::optional<Vector4<T>> perspective_row3_single(const PerspectiveInput<W>& in,
                                                  const std::array<W, 3>& n) {
  constexpr W u = std::numeric_limits<W>::epsilon() / W(2);
  RangeCheck<W> check;
  W u_i[3];
  W magnitude = std::abs(in.c_z);
  for (int i = 0; i < 3; ++i) {
    u_i[i] = n[i] * in.reciprocal[i] * in.c[i];
    check(u_i[i]);
    magnitude += std::abs(u_i[i]);
  }
  const W sum = (u_i[0] + u_i[1]) + u_i[2];
  const W big_n = sum + in.c_z;
  const W v = (in.k - in.t) * in.c_z - in.t * sum;
  check(big_n);
  check(v);
  const W error = W(8) * u * magnitude;
  const W n_doubt = error / std::abs(big_n);
  const W v_doubt = in.t != W(0) ? error / std::abs(v) : W(0);
  // C . Q = N / K must be positive; N's doubt below 1 settles its sign.
  if (!check.ok || (big_n > W(0)) != (in.K > W(0)) || !(n_doubt <= W(1) / W(64)) ||
      !(v_doubt <= W(1) / W(64)))
    return std::nullopt;
  const W reciprocal_n = W(1) / big_n;
  const W g = in.k * in.K * reciprocal_n;  // a 2^-shift
  Vector4<W> entries(g * in.c[0], g * in.c[1], g * in.c_z, g * in.c[2]);
  if (in.t != W(0)) entries(2) = in.K * v * reciprocal_n;
  // Relative doubt per entry: N's and V's (first order, doubled for their own second order),
  // three roundings, and room for the roundings of x -+ doubt |x| below.
  const W doubt = W(2) * (n_doubt + v_doubt) + W(6) * u;
  Vector4<T> row3;
  for (int i = 0; i < 4; ++i) {
    const W x = in.s * entries(i);
    check(x);
    const W spread = doubt * std::abs(x);
    const T below = static_cast<T>(x - spread), above = static_cast<T>(x + spread);
    if (below != above) return std::nullopt;
    row3(i) = below == T(0) ? T(0) : below;  // +0, as the plain methods give
  }
  if (!check.ok) return std::nullopt;
  return row3;
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
/// Every product's and quotient's operands and results must pass RangeCheck. std::nullopt when
/// any condition fails: a component lost to the scaling, an unresolved N or V, C . Q <= 0, a
/// value outside that range; the refining path then answers.
template <class T, class W>
std::optional<PerspectiveAnswer<T, W>> perspective_row3(const ScaledPlane<W>& scaled,
                                                        const Matrix4<W>& m,
                                                        const Vector4<W>& corner,
                                                        Convention convention) {
  if (scaled.lossy()) return std::nullopt;
  constexpr W u = std::numeric_limits<W>::epsilon() / W(2);
  constexpr W target = W(std::numeric_limits<T>::epsilon());
  const Vector4<W>& c = scaled.c_hat;
  const DepthRange range = clip_depth_range(convention);
  const RowCombination near_combination = near_rows(convention);
  const PerspectiveInput<W> in{m(3, 2),
                               {m(0, 0), m(1, 1), m(2, 3)},
                               {m(0, 2), m(1, 2), m(2, 2)},
                               {corner.x(), corner.y(), corner.z()},
                               {c.x(), c.y(), c.w()},
                               c.z(),
                               {W(1) / m(0, 0), W(1) / m(1, 1), W(1) / m(2, 3)},
                               W(range.z_high - range.z_low),
                               W(near_combination.m3),
                               W(near_combination.m4)};
  // V = (k - t) C_z - t U is formed for t = 1 (gl, reversed_z), where (k - t) C_z is exact.
  if (in.t != W(0) && in.t != W(1)) return std::nullopt;
  RangeCheck<W> check;
  check(in.K);
  eft::Pair<W> r[3], u_i[3];
  std::array<W, 3> n_hi;
  W magnitude = std::abs(in.c_z);
  for (int i = 0; i < 3; ++i) {
    check(in.a[i]);
    const eft::Pair<W> n = eft::two_sum(in.q_clip[i] * in.K, -in.b[i]);
    n_hi[i] = n.hi;
    check(n.hi);
    r[i] = eft::divide(n, in.a[i], in.reciprocal[i]);
    check(r[i].hi);
    u_i[i] = eft::multiply(r[i], in.c[i]);
    check(u_i[i].hi);
    magnitude += std::abs(u_i[i].hi);
  }
  if (!check.ok || !(in.K > W(0) || in.K < W(0))) return std::nullopt;
  const W reciprocal_k = W(1) / in.K;
  PerspectiveAnswer<T, W> out;
  out.far_corner = Vector4<W>(r[0].hi * reciprocal_k, r[1].hi * reciprocal_k, reciprocal_k,
                              r[2].hi * reciprocal_k);
  if constexpr (std::numeric_limits<W>::digits >= 2 * std::numeric_limits<T>::digits + 5) {
    if (const auto row3 = perspective_row3_single<T>(in, n_hi)) {
      out.row3 = *row3;
      return out;
    }
  }
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
  const eft::Pair<W> g = eft::divide(eft::Pair<W>{in.k * in.K, W(0)}, n, reciprocal_n);
  check(g.hi);
  eft::Pair<W> entries[4];
  for (int i = 0; i < 4; ++i) {
    entries[i] = eft::multiply(g, c(i));
    check(entries[i].hi);
  }
  if (in.t != W(0)) {
    const eft::Pair<W> v = plus(-s2.hi, -u_rest, (in.k - in.t) * in.c_z);
    check(v.hi);
    if (!(bound <= resolution * std::abs(v.hi))) return std::nullopt;
    const eft::Pair<W> kv = eft::multiply(v, in.K);
    check(kv.hi);
    entries[2] = eft::divide(kv, n, reciprocal_n);
    check(entries[2].hi);
  }
  if (!check.ok) return std::nullopt;
  for (int i = 0; i < 4; ++i) {
    const T entry = eft::round_pair<T>(eft::Pair<W>{in.s * entries[i].hi, in.s * entries[i].lo});
    out.row3(i) = entry == T(0) ? T(0) : entry;  // +0, as the plain methods give
  }
  return out;
}

}  // namespace oblique::detail
