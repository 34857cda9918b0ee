// Error-free transformations and compensated sums (Knuth, Dekker, Ogita-Rump-Oishi): the
// arithmetic behind the accurate method. Each function says what it computes exactly.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "oblique/detail/config.h"
#include "oblique/numeric/magnitudes.h"

namespace oblique::eft {

/// An unevaluated sum hi + lo.
template <class T>
struct Pair {
  T hi;
  T lo;
};

/// x, as a value the compiler cannot see into: a product passed through it is rounded on its own
/// and never contracted with a later addition or subtraction into an FMA (-ffp-contract=fast,
/// GCC's default in gnu++ modes, wherever the target has one: -march=native, -mfma, AArch64, a
/// target("fma") function). No instruction on x86-64 and AArch64 (the value stays in its
/// register); x87's long double has no FMA to contract into; other targets go through memory.
template <class T>
OBLIQUE_EFT_INLINE T rounded(T x) noexcept {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__aarch64__))
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) {
#if defined(__x86_64__)
    __asm__("" : "+x"(x));
#else
    __asm__("" : "+w"(x));
#endif
  }
#elif defined(__GNUC__)
  __asm__("" : "+m"(x));
#endif
  return x;
}

/// s + e = a + b exactly, s = fl(a + b) (Knuth's TwoSum; no condition on a and b).
/// a and b are taken through rounded(): the sum is exact only for the values the caller names,
/// and a product the caller passes (or one its argument was computed from) must not be fused
/// into s = a + b while e is formed from its rounded value (see fast_two_sum).
template <class T>
OBLIQUE_EFT_INLINE Pair<T> two_sum(T a, T b) noexcept {
  a = rounded(a);
  b = rounded(b);
  const T s = a + b;
  const T z = s - a;
  return {s, (a - (s - z)) + (b - z)};
}

/// s + e = a + b exactly when |a| >= |b| or a = 0 (Dekker's FastTwoSum).
/// a and b are taken through rounded(), as in two_sum: divide() passes q1 = a.hi r and the
/// correction rem r, both products, and GCC 12's SLP vectoriser (-O3 with -march=znver3's cost
/// model) packed s = q1 + c and e = c - (s - q1) into one vector multiply and add-subtract,
/// which it then fused into vfmsubadd132pd even under -ffp-contract=off: s came from the exact
/// a.hi r, e from the rounded q1, and the pair was off by up to an ulp of s (design.md,
/// "Contraction").
template <class T>
OBLIQUE_EFT_INLINE Pair<T> fast_two_sum(T a, T b) noexcept {
  a = rounded(a);
  b = rounded(b);
  const T s = a + b;
  return {s, b - (s - a)};
}

/// hi + lo = a with hi holding the upper half of a's significand (Veltkamp's split), for
/// |a| < 2^(max_exponent - p/2 - 1) (beyond, (2^(p/2) + 1) a overflows). The product c must be
/// rounded by itself: contracted into c - a and c - (c - a), as GCC does with -ffp-contract=fast
/// and an FMA, the split returns {a, 0}, and Dekker's product is then exact only by the accident
/// of its own first product being fused too; hence rounded().
template <class T>
OBLIQUE_EFT_INLINE Pair<T> split(T a) noexcept {
  constexpr int half = (std::numeric_limits<T>::digits + 1) / 2;
  constexpr T factor = constant_power_of_two<T>(half) + T(1);
  const T c = rounded(factor * a);
  const T hi = c - (c - a);
  return {hi, a - hi};
}

/// How two_prod finds a product's rounding error: `hardware` uses the FMA instruction, and is
/// for code compiled for a target that has one (a function with __attribute__((target("fma"))),
/// chosen at run time; see accurate.h); `portable` uses it only where the whole build targets it.
enum class Fma { portable, hardware };

/// p + e = a b exactly, p = fl(a b), barring underflow (TwoProduct). With a hardware FMA where
/// the compiler inlines one (FP_FAST_FMA, or F = Fma::hardware for float and double); otherwise
/// Dekker's product, which is twice as fast as glibc's fma() call for double and a hundred times
/// faster than its fmal() for long double, and exact unless |a| or |b| is within 2^(p/2 + 2) of
/// overflow or |a b| within a factor 2 of it (then std::fma: the split halves' product
/// x.hi y.hi exceeds |a b| by up to 2^(1 - p/2)). Both give the same, exact, pair.
template <class T, Fma F = Fma::portable>
OBLIQUE_EFT_INLINE Pair<T> two_prod(T a, T b) noexcept {
  // p through rounded(): the callers' a - p (divide's remainder) must see the rounded product,
  // not a * b fused into it.
  const T p = rounded(a * b);
  if constexpr (F == Fma::hardware && (std::is_same_v<T, double> || std::is_same_v<T, float>)) {
    return {p, std::fma(a, b, -p)};
  }
#if defined(FP_FAST_FMA)
  if constexpr (std::is_same_v<T, double>) return {p, std::fma(a, b, -p)};
#endif
#if defined(FP_FAST_FMAF)
  if constexpr (std::is_same_v<T, float>) return {p, std::fma(a, b, -p)};
#endif
  constexpr T large = constant_power_of_two<T>(std::numeric_limits<T>::max_exponent -
                                               (std::numeric_limits<T>::digits + 1) / 2 - 2);
  constexpr T large_product = constant_power_of_two<T>(std::numeric_limits<T>::max_exponent - 1);
  if (std::fabs(a) < large && std::fabs(b) < large && std::fabs(p) < large_product) {
    const Pair<T> x = split(a), y = split(b);
    return {p, ((x.hi * y.hi - p) + x.hi * y.lo + x.lo * y.hi) + x.lo * y.lo};
  }
  return {p, std::fma(a, b, -p)};
}

/// Terms of a sum, in a fixed-size buffer (no allocation on the core's path).
template <class T, std::size_t Capacity>
class Terms {
 public:
  Terms() noexcept = default;
  /// Copies only the terms that are set (the buffer is large; a sum usually has a few terms).
  Terms(const Terms& other) noexcept : size_(other.size_) {
    for (std::size_t i = 0; i < size_; ++i) values_[i] = other.values_[i];
  }
  Terms& operator=(const Terms& other) noexcept {
    size_ = other.size_;
    for (std::size_t i = 0; i < size_; ++i) values_[i] = other.values_[i];
    return *this;
  }

  /// Adds x; Capacity must allow every term the caller adds (a term beyond it is dropped).
  void add(T x) noexcept {
    if (x != T(0) && size_ < Capacity) values_[size_++] = x;
  }
  /// The sum of the magnitudes of the terms (SumK's error bounds scale with it): of the terms as
  /// added until sum() or distil() rewrites them.
  T magnitude() const noexcept {
    T total = T(0);
    for (std::size_t i = 0; i < size_; ++i) total += std::fabs(values_[i]);
    return total;
  }
  void add(Pair<T> x) noexcept {
    add(x.hi);
    add(x.lo);
  }
  /// a b, exactly, as two terms.
  void add_product(T a, T b) noexcept { add(two_prod(a, b)); }

  /// The sum as if computed in K-fold working precision and rounded once: K - 1 error-free
  /// passes, then a plain sum (Ogita, Rump and Oishi's SumK). The terms keep their exact sum.
  T sum(int k) noexcept {
    for (int pass = 1; pass < k; ++pass) vec_sum();
    T total = T(0);
    for (std::size_t i = 0; i + 1 < size_; ++i) total += values_[i];
    return size_ == 0 ? T(0) : total + values_[size_ - 1];
  }

  /// The exact sum as hi + lo, hi its rounding and lo that of the rest (so the pair is within
  /// eps |lo| of the sum; a zero sum gives 0 + 0): error-free passes until one changes nothing,
  /// when the terms no longer overlap. Returns false in `exact` if `max_passes` did not suffice;
  /// hi + lo is then the top term plus the plain sum of the others.
  Pair<T> distil(bool& exact, int max_passes = 8) noexcept {
    // The pass that would change nothing is replaced by a check of the same condition: a pass
    // changes nothing iff fl(x_i + x_{i-1}) = x_i for every i (its running sums are then the
    // terms themselves), and those sums, unlike the pass's, do not wait on each other.
    exact = max_passes > 0 && !vec_sum();
    for (int pass = 1; pass < max_passes && !exact; ++pass) {
      exact = settled();
      if (!exact) vec_sum();
    }
    if (size_ == 0) return {T(0), T(0)};
    if (!exact) {
      T rest = T(0);
      for (std::size_t i = 0; i + 1 < size_; ++i) rest += values_[i];
      return fast_two_sum(values_[size_ - 1], rest);
    }
    // Settled: the top term is the sum rounded, bar a tie that a lower term breaks.
    const T hi = settled_rounding(values_.data(), size_);
    if (hi == values_[size_ - 1]) return {hi, settled_rounding(values_.data(), size_ - 1)};
    // hi = top + 2 x (x the next term, half the spacing at top), so the rest is -x plus the terms
    // below x: not settled, as -x and the next lower term may now overlap.
    Terms rest;
    for (std::size_t i = 0; i + 2 < size_; ++i) rest.add(values_[i]);
    rest.add(-values_[size_ - 2]);
    // Iterated passes settle any finite terms (Priest); a few suffice for these.
    for (int pass = 0; pass < 64 && rest.vec_sum(); ++pass) {
    }
    return {hi, settled_rounding(rest.values_.data(), rest.size_)};
  }

  std::size_t size() const noexcept { return size_; }
  static constexpr std::size_t capacity() noexcept { return Capacity; }
  T operator[](std::size_t i) const noexcept { return values_[i]; }

  bool all_finite() const noexcept {
    for (std::size_t i = 0; i < size_; ++i) {
      if (!std::isfinite(values_[i])) return false;
    }
    return true;
  }

 private:
  /// Whether a VecSum pass would leave the terms as they are (false, as the pass would report,
  /// when a term is not finite: TwoSum's error is then NaN).
  bool settled() const noexcept {
    bool same = true;
    for (std::size_t i = 1; i < size_; ++i) {
      const bool absorbed = values_[i] + values_[i - 1] == values_[i];
      const bool finite = values_[i] - values_[i] == T(0);
      same = same && absorbed && finite;
    }
    return same;
  }

  /// The sum of x[0, n) rounded to nearest (ties to even), for settled terms: nonzero ones
  /// increase in magnitude, each at most half the spacing of T next to the one above it, and
  /// the terms below any x_i add up to less than x_i in magnitude, with the sign of the first
  /// nonzero one. So the top term is the rounding unless the next, x, lies exactly halfway to
  /// the top's neighbour (top + 2x is then that neighbour) and a third term beyond it has the
  /// same sign (the tie is broken away from the top).
  static T settled_rounding(const T* x, std::size_t n) noexcept {
    if (n == 0) return T(0);
    const T top = x[n - 1];
    if (n < 3 || x[n - 3] == T(0) || (x[n - 3] > T(0)) != (x[n - 2] > T(0))) return top;
    const Pair<T> neighbour = two_sum(top, T(2) * x[n - 2]);
    return neighbour.lo == T(0) && neighbour.hi != top ? neighbour.hi : top;
  }

  /// One error-free pass (Ogita-Rump-Oishi's VecSum): the running sum moves to the last term and
  /// the rounding errors stay behind. Returns whether any term changed.
  bool vec_sum() noexcept {
    if (size_ < 2) return false;
    bool changed = false;
    T carry = values_[0];
    for (std::size_t i = 1; i < size_; ++i) {
      const T x = values_[i];
      const Pair<T> s = two_sum(x, carry);
      changed |= (s.hi != x) | (s.lo != carry);
      values_[i - 1] = s.lo;
      carry = s.hi;
    }
    values_[size_ - 1] = carry;
    return changed;
  }

  std::array<T, Capacity> values_;  // the first size_ are set
  std::size_t size_ = 0;
};

/// (hi + lo) / b to about twice the working precision: q1 = fl(hi / b), and the exact remainder
/// hi - q1 b (TwoProduct) plus lo, divided by b.
template <class T>
OBLIQUE_EFT_INLINE Pair<T> divide(Pair<T> a, T b) noexcept {
  const T q1 = a.hi / b;
  const Pair<T> p = two_prod(q1, b);
  const T remainder = ((a.hi - p.hi) - p.lo) + a.lo;
  return fast_two_sum(q1, remainder / b);
}

/// (hi + lo) b to about twice the working precision: within 3u^2 |a b| (u = eps / 2) barring
/// underflow (Joldes, Muller and Popescu's DWTimesFP).
template <Fma F = Fma::portable, class T>
OBLIQUE_EFT_INLINE Pair<T> multiply(Pair<T> a, T b) noexcept {
  const Pair<T> p = two_prod<T, F>(a.hi, b);
  return fast_two_sum(p.hi, p.lo + a.lo * b);
}

/// (a.hi + a.lo) + (b.hi + b.lo) within 3u^2 / (1 - 4u) of the exact sum, relative to the sum
/// itself however much it cancels, barring overflow (Joldes, Muller and Popescu's
/// AccurateDWPlusDW; both operands normalised, |lo| <= ulp(hi) / 2).
template <class T>
OBLIQUE_EFT_INLINE Pair<T> add(Pair<T> a, Pair<T> b) noexcept {
  const Pair<T> s = two_sum(a.hi, b.hi);
  const Pair<T> t = two_sum(a.lo, b.lo);
  const Pair<T> v = fast_two_sum(s.hi, s.lo + t.hi);
  return fast_two_sum(v.hi, t.lo + v.lo);
}

/// (a.hi + a.lo) (b.hi + b.lo) within 7u^2 of the product barring underflow (Joldes, Muller and
/// Popescu's DWTimesDW1: the exact a.hi b.hi, the cross terms rounded, a.lo b.lo left out).
template <Fma F = Fma::portable, class T>
OBLIQUE_EFT_INLINE Pair<T> multiply(Pair<T> a, Pair<T> b) noexcept {
  const Pair<T> c = two_prod<T, F>(a.hi, b.hi);
  const T cross = a.lo * b.hi + a.hi * b.lo;
  return fast_two_sum(c.hi, c.lo + cross);
}

/// (a.hi + a.lo) / (b.hi + b.lo) to about twice the working precision: q1 = fl(a.hi / b.hi) and
/// the remainder a - q1 b (a.hi - q1 b.hi exact by TwoProduct) divided by b.hi; within 18u^2 of
/// the quotient barring underflow (each of the remainder's five roundings is below u times a few
/// u |a|, and dividing by b.hi instead of b costs u |b.lo / b.hi| of the small second word).
template <class T>
OBLIQUE_EFT_INLINE Pair<T> divide(Pair<T> a, Pair<T> b) noexcept {
  const T q1 = a.hi / b.hi;
  const Pair<T> p = two_prod(q1, b.hi);
  const T remainder = (((a.hi - p.hi) - p.lo) + a.lo) - q1 * b.lo;
  return fast_two_sum(q1, remainder / b.hi);
}

/// (a.hi + a.lo) / b from b and an approximate reciprocal r = fl(1 / b), with no division:
/// q1 = fl(a.hi r) is within 2u of the quotient, so a.hi - q1 b is exact by TwoProduct and
/// Sterbenz, and the remainder's correction rem r adds errors of order u^2 only; within 17u^2
/// of the quotient barring underflow (the remainder's two roundings, below 7u^2 |a|, and 2u of
/// a correction below 5u |a / b|).
template <Fma F = Fma::portable, class T>
OBLIQUE_EFT_INLINE Pair<T> divide(Pair<T> a, T b, T reciprocal) noexcept {
  const T q1 = a.hi * reciprocal;
  const Pair<T> p = two_prod<T, F>(q1, b);
  const T remainder = ((a.hi - p.hi) - p.lo) + a.lo;
  return fast_two_sum(q1, remainder * reciprocal);
}

/// (a.hi + a.lo) / (b.hi + b.lo) from b and r = fl(1 / b.hi), as above; within 28u^2 (the
/// remainder also subtracts q1 b.lo, and the correction divides by b.hi instead of b).
template <Fma F = Fma::portable, class T>
OBLIQUE_EFT_INLINE Pair<T> divide(Pair<T> a, Pair<T> b, T reciprocal) noexcept {
  const T q1 = a.hi * reciprocal;
  const Pair<T> p = two_prod<T, F>(q1, b.hi);
  const T remainder = (((a.hi - p.hi) - p.lo) + a.lo) - q1 * b.lo;
  return fast_two_sum(q1, remainder * reciprocal);
}

/// The value of hi + lo rounded to nearest (ties to even) in N. In a narrower N: hi is the
/// working-precision sum, so its rounding to N differs from the exact one only when hi lies
/// exactly halfway between two N values; then lo's sign decides. In T itself: hi. In a wider N
/// (with T's exponent range): N(hi) + N(lo), one rounding of the exact sum.
template <class N, class T>
N round_pair(Pair<T> x) noexcept {
  const N nearest = static_cast<N>(x.hi);
  if constexpr (std::numeric_limits<T>::digits < std::numeric_limits<N>::digits) {
    // N wider (a pair of doubles into x87's long double): one addition of the exact operands.
    return nearest + static_cast<N>(x.lo);
  } else if constexpr (std::numeric_limits<T>::digits == std::numeric_limits<N>::digits) {
    return nearest;
  } else {
    // r = hi - nearest is exact (T holds N's values with room to spare) and at most half the
    // spacing of N on its side; hi is a tie iff nearest + 2r, the reflection of nearest through
    // hi, is itself an N value (the neighbour on that side).
    if (!std::isfinite(nearest)) {
      // hi at the midpoint between N's largest value and 2^max_exponent rounds to infinity as
      // a tie (to even); hi + lo with lo towards zero lies below it and rounds to the largest.
      constexpr T largest = static_cast<T>(std::numeric_limits<N>::max());
      constexpr T midpoint =
          largest + constant_power_of_two<T>(std::numeric_limits<N>::max_exponent -
                                             std::numeric_limits<N>::digits - 1);
      const bool below = x.lo != T(0) && (x.lo > T(0)) != (x.hi > T(0));
      if (std::fabs(x.hi) == midpoint && below) {
        return static_cast<N>(x.hi > T(0) ? largest : -largest);
      }
      return nearest;
    }
    const T r = x.hi - static_cast<T>(nearest);
    if (x.lo == T(0) || r == T(0)) return nearest;
    const T reflected = static_cast<T>(nearest) + T(2) * r;
    const N other = static_cast<N>(reflected);
    if (static_cast<T>(other) != reflected) return nearest;
    // A tie in N: the exact value lies on lo's side of it.
    return (x.lo > T(0)) == (r > T(0)) ? other : nearest;
  }
}

}  // namespace oblique::eft
