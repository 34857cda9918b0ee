// The accurate method's refining path: the far corner Q refined to several words from exact
// residuals (RefinedCorner), C . Q from exact products (dot_terms), and row 3 of M' from them with
// each entry rounded once (accurate_row3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "oblique/depth_convention.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/error_free.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"

namespace oblique::detail {

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
    for (int i = 0; i < 4; ++i) residual(i) = residual_terms(i).sum(count_ + 1);
    const Vector4<W> next = solve_(residual);
    if (!all_finite(next)) return false;
    words_[count_++] = next;
    return true;
  }

  /// An estimate of |w| . |Q - (x_0 + ... + x_{n-1})|, the error left in the words weighted by
  /// w: the larger of two.
  ///  - From the refinement's progress: the last word's weighted size times the contraction per
  ///    step, measured from the last two words but never below `contraction_floor` (a bound the
  ///    solve's conditioning gives); the floor times the weighted size of Q while there is one
  ///    word; 0 when the last correction is exactly zero (Q is then exact).
  ///  - From the residual: the error is e = M^-1 r, r = rhs - M (x_0 + ... + x_{n-1}) summed
  ///    exactly, so |w| . |e| <= |w| . |M^-1| |r|, taken twice for the computed inverse.
  /// The first alone misjudges a component of Q far smaller than the others it is coupled with
  /// through M: each solve is accurate relative to |M^-1| |M| |x|, so such a component converges
  /// at the pace of the largest (its error after a step is eps times the largest one's, not its
  /// own), while the weighted progress measured is the largest one's. Where C weighs that
  /// component heavily, C . Q (or a row-3 entry cancelling beyond it) was taken as resolved with
  /// thousands of ulps of error (fuzz_oblique's find, accurate_test's
  /// smallComponentsOfTheFarCornerAreResolved).
  W remaining_error(const Vector4<W>& weights, W contraction_floor) const {
    const Vector4<W> w = weights.cwiseAbs();
    return std::max(progress_error(w, contraction_floor), residual_error(w));
  }

  /// The sum of the words, rounded.
  Vector4<W> value() const {
    Vector4<W> sum = words_[count_ - 1];
    for (int k = count_ - 2; k >= 0; --k) sum += words_[k];
    return sum;
  }

 private:
  /// The terms of rhs_i - M_i (x_0 + ... + x_{n-1}), each exact.
  eft::Terms<W, 1 + 2 * 4 * kMaxWords> residual_terms(int i) const {
    eft::Terms<W, 1 + 2 * 4 * kMaxWords> terms;
    terms.add(rhs_(i));
    for (int k = 0; k < count_; ++k) {
      for (int j = 0; j < nonzero_[i]; ++j) {
        terms.add_product(negated_[i][j], words_[k](columns_[i][j]));
      }
    }
    return terms;
  }

  W progress_error(const Vector4<W>& w, W contraction_floor) const {
    const W last = w.dot(words_[count_ - 1].cwiseAbs());
    if (!(last > W(0))) return W(0);
    if (count_ < 2) return last * contraction_floor;  // the first solve's own error
    const W before = w.dot(words_[count_ - 2].cwiseAbs());
    const W measured = before > W(0) ? last / before : W(1);
    return last * std::min(W(1), std::max(measured, contraction_floor));
  }

  /// 2 |w| . |M^-1| |r|, |r| bounded from its distilled terms (eps |lo| beyond hi + lo; SumK's
  /// bound for eight passes where they do not settle). M^-1 from the solve of each unit vector,
  /// once; not finite where M^-1 overflows (nothing is then resolved from the words).
  W residual_error(const Vector4<W>& w) const {
    constexpr W eps = std::numeric_limits<W>::epsilon();
    if (!inverse_known_) {
      for (int j = 0; j < 4; ++j) abs_inverse_.col(j) = solve_(Vector4<W>::Unit(j)).cwiseAbs();
      inverse_known_ = true;
    }
    Vector4<W> r;
    for (int i = 0; i < 4; ++i) {
      eft::Terms<W, 1 + 2 * 4 * kMaxWords> terms = residual_terms(i);
      const std::size_t size = terms.size();
      const W magnitude = terms.magnitude();
      bool exact = false;
      const eft::Pair<W> sum = terms.distil(exact);
      const W slack = exact ? W(0) : magnitude * std::pow(W(size) * eps, 8);
      r(i) = std::abs(sum.hi) + (W(1) + eps) * std::abs(sum.lo) + slack;
    }
    return W(2) * w.dot(abs_inverse_ * r);
  }

  Vector4<W> rhs_;
  Solve solve_;
  mutable Matrix4<W> abs_inverse_;  ///< |M^-1|, once residual_error() has needed it
  mutable bool inverse_known_ = false;
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

/// Row 3 of M', s (a C_i - t M4_i) with a = range / (C . Q), each entry rounded once to T.
///  - Where t M4_i = 0 it is s range C_i / (C . Q), from a double-word quotient.
///  - Elsewhere it is s N_i / (C . Q) with N_i = range C_i - t M4_i (C . Q) summed from exact
///    products, which removes the cancellation of a C_i against t M4_i (the a C_z + 1 of the GL
///    formula) instead of rounding into it: from C . Q's double-word value where that resolves
///    N_i, else from M4_i times each term of C . Q.
/// Every sum is distilled to its exact value; what is left is Q's own error, `q_part` (an
/// estimate of |C| . |Q error|), which must stay below eps / 8 of C . Q and of each N_i; a
/// C . Q <= 0 is resolved when that error cannot lift it above zero.
/// Precondition: scaling C lost nothing (not scaled.lossy).
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

}  // namespace oblique::detail
