// Certified double-double numbers for the filtered checker (filtered.h): a value hi + lo and a
// rigorous bound on its distance from the exact value it stands for. Every operation widens the
// bound by what its inputs carried and what its own rounding may add; a decision (a sign, a
// comparison) is made only when the whole interval lies on one side, and otherwise throws
// Undecided, which sends the caller to exact arithmetic.
//
// Bounds used (eft = core/include/oblique/numeric/error_free.h, Joldes, Muller and Popescu):
// eft::add within 3u^2 / (1 - 4u), eft::multiply within 7u^2, eft::divide within 18u^2 of the
// exact result of their operands, u = 2^-53, relative to that result, barring underflow and
// overflow. Each bound below takes 2^-100 (above 2^6 u^2) for those; any rounding in the subnormal
// range loses at most a few 2^-1074 absolutely, covered by 2^-1060 wherever an operation may have
// rounded; the bound's own arithmetic (a handful of roundings, each below 2^-53 relative) is
// covered by the factor 1 + 2^-45. A value or bound that overflows throws Undecided.
// An exact zero (from exact inputs, or a sum that cancels exactly) keeps the bound 0.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

#include "oblique/numeric/error_free.h"

namespace oblique::oracle::certified {

/// Thrown when the floating-point filter cannot decide: the caller asks exact arithmetic. `line`
/// is where (for the statistics of what the filter leaves to exact arithmetic).
struct Undecided {
  int line = 0;
};

/// hi + lo (normalised: |lo| <= ulp(hi) / 2) within `err` of the exact value it stands for.
struct Num {
  double hi = 0, lo = 0, err = 0;
};

namespace detail {

constexpr double kRelative = 0x1p-100;        // one double-double operation's relative error
constexpr double kBoundGrowth = 1 + 0x1p-45;  // the bound's own roundings
constexpr double kUnderflow = 0x1p-1060;      // roundings in the subnormal range

inline double magnitude(const Num& x) {
  return std::fabs(x.hi) + std::fabs(x.lo);
}

inline Num finish(eft::Pair<double> value, double err, bool may_round) {
  err = err * kBoundGrowth + (may_round ? kUnderflow : 0.0);
  if (!std::isfinite(value.hi) || !std::isfinite(err)) throw Undecided{__LINE__};
  return Num{value.hi, value.lo, err};
}

}  // namespace detail

/// A float, double or long double, exactly (a long double outside double's normal range, or
/// with bits below it, throws Undecided).
template <class T>
Num exactly(T x) {
  if constexpr (std::is_same_v<T, long double>) {
    const double hi = static_cast<double>(x);
    if (!std::isfinite(hi)) throw Undecided{__LINE__};
    const double lo = static_cast<double>(x - static_cast<long double>(hi));
    if (static_cast<long double>(hi) + static_cast<long double>(lo) != x ||
        (lo != 0 && std::fabs(lo) < std::numeric_limits<double>::min()))
      throw Undecided{__LINE__};
    return Num{hi, lo, 0};
  } else {
    return Num{static_cast<double>(x), 0, 0};
  }
}

/// An exactly representable double (a constant).
inline Num constant(double x) {
  return Num{x, 0, 0};
}

/// A value known only to lie in [0, upper] (upper a double; the interval kept is [0, 2 upper]):
/// e.g. half the smallest subnormal of double or long double, which double cannot hold.
inline Num between_zero_and(double upper) {
  return Num{upper, 0, upper};
}

/// 2^e: exact within double's range; below it (e < -1074) the interval [0, 2^-1073], which holds
/// it; above it Undecided.
inline Num power_of_two(int e) {
  if (e > std::numeric_limits<double>::max_exponent - 1) throw Undecided{__LINE__};
  if (e < std::numeric_limits<double>::min_exponent - std::numeric_limits<double>::digits)
    return between_zero_and(std::numeric_limits<double>::denorm_min());
  return constant(std::ldexp(1.0, e));
}

/// x 2^e for any e, in steps within double's exponent range (an overflow is Undecided, as in
/// operator*; below the range the product is an interval holding it).
inline Num times_power_of_two(Num x, int e);

/// x 2^e: the filter works on inputs scaled by powers of two, so that magnitudes at the ends of
/// each type's range, and long doubles beyond double's, stay within double's. Exact (err 0) where
/// x 2^e is a double, or for long double a double-double hi + lo with lo 0 or normal (as
/// exactly()); otherwise (a value scaled into double's subnormal range, or a long double whose
/// rest below hi is that small) an interval around the nearest double hi that holds it (rounding
/// to the subnormal grid loses at most 2^-1075). Undecided when x 2^e overflows double, or (long
/// double) leaves long double's range, where scaling back by 2^-e no longer gives x.
template <class T>
Num scaled(T x, int e) {
  constexpr double tiny = std::numeric_limits<double>::denorm_min();
  if constexpr (std::is_same_v<T, long double>) {
    const long double y = std::ldexp(x, e);
    if (std::ldexp(y, -e) != x) throw Undecided{__LINE__};
    const double hi = static_cast<double>(y);
    if (!std::isfinite(hi)) throw Undecided{__LINE__};
    const double lo = static_cast<double>(y - static_cast<long double>(hi));
    const bool exact = static_cast<long double>(hi) + static_cast<long double>(lo) == y &&
                       (lo == 0 || std::fabs(lo) >= std::numeric_limits<double>::min());
    if (exact) return Num{hi, lo, 0};
    // lo is the rest y - hi rounded (to the subnormal grid when it is that small): |y - hi| <=
    // |lo| + 2^-1075.
    return Num{hi, 0, std::fabs(lo) + tiny};
  } else {
    const double y = std::ldexp(static_cast<double>(x), e);
    if (!std::isfinite(y)) throw Undecided{__LINE__};
    return Num{y, 0, std::ldexp(y, -e) == static_cast<double>(x) ? 0.0 : tiny};
  }
}

inline Num operator-(const Num& x) {
  return Num{-x.hi, -x.lo, x.err};
}

inline Num operator+(const Num& x, const Num& y) {
  const eft::Pair<double> s =
      eft::add(eft::Pair<double>{x.hi, x.lo}, eft::Pair<double>{y.hi, y.lo});
  const double rounding = detail::kRelative * (std::fabs(s.hi) + std::fabs(s.lo));
  return detail::finish(s, x.err + y.err + rounding, s.hi != 0 || s.lo != 0);
}

inline Num operator-(const Num& x, const Num& y) {
  return x + (-y);
}

inline Num operator*(const Num& x, const Num& y) {
  const double mx = detail::magnitude(x), my = detail::magnitude(y);
  const bool exact_zero = (mx == 0 && x.err == 0) || (my == 0 && y.err == 0);
  if (exact_zero) return Num{};
  const eft::Pair<double> p =
      eft::multiply(eft::Pair<double>{x.hi, x.lo}, eft::Pair<double>{y.hi, y.lo});
  const double propagated = mx * y.err + my * x.err + x.err * y.err;
  const double rounding = detail::kRelative * (std::fabs(p.hi) + std::fabs(p.lo));
  return detail::finish(p, propagated + rounding, true);
}

inline Num times_power_of_two(Num x, int e) {
  constexpr int step = 1000;
  for (; e > step; e -= step) x = x * power_of_two(step);
  for (; e < -step; e += step) x = x * power_of_two(-step);
  return e == 0 ? x : x * power_of_two(e);
}

/// x / y; throws Undecided unless y is certainly nonzero.
inline Num operator/(const Num& x, const Num& y) {
  const double my = detail::magnitude(y);
  // |y| >= |y.hi| (1 - 2^-52) - err: certainly away from zero by at least half of |y.hi|.
  if (!(y.hi != 0 && y.err * 4 <= std::fabs(y.hi))) throw Undecided{__LINE__};
  if (detail::magnitude(x) == 0 && x.err == 0) return Num{};
  const eft::Pair<double> q =
      eft::divide(eft::Pair<double>{x.hi, x.lo}, eft::Pair<double>{y.hi, y.lo});
  const double mq = std::fabs(q.hi) + std::fabs(q.lo);
  // |X / Y - x / y| <= (e_x + |x / y| e_y) / (|y| - e_y), |y| - e_y >= |y.hi| / 2 here; |x / y| is
  // within 2^-100 of |q|.
  const double low_y = std::fabs(y.hi) * 0.5;
  const double propagated = (x.err + mq * (1 + 0x1p-90) * y.err) / low_y;
  (void)my;
  return detail::finish(q, propagated + detail::kRelative * mq, true);
}

/// The lowest and highest value x may stand for, rounded outward: hi + (lo -+ err), each of the
/// two roundings below u of its result, covered by 2u of both (and the last subtraction by the
/// other u; 2^-1074 for the subnormal range).
inline double lower(const Num& x) {
  const double t = x.lo - x.err;
  const double l = x.hi + t;
  return l - (std::fabs(l) + std::fabs(t)) * 0x1p-52 - 0x1p-1074;
}
inline double upper(const Num& x) {
  const double t = x.lo + x.err;
  const double u = x.hi + t;
  return u + (std::fabs(u) + std::fabs(t)) * 0x1p-52 + 0x1p-1074;
}

inline bool is_exact_zero(const Num& x) {
  return x.hi == 0 && x.lo == 0 && x.err == 0;
}

/// The sign of the exact value; throws Undecided when the interval holds zero and is not {0}.
/// Decided in double-double where it can be (|lo| <= ulp(hi) / 2, so hi + lo - err keeps hi's
/// sign while err <= |hi| / 4), else by the interval's ends.
/// sign_known() sets s and returns true where sign() returns, false where it throws.
inline bool sign_known(const Num& x, int& s) {
  if (is_exact_zero(x)) {
    s = 0;
  } else if (x.err * 4 <= std::fabs(x.hi)) {
    s = x.hi > 0 ? 1 : -1;
  } else if (lower(x) > 0) {
    s = 1;
  } else if (upper(x) < 0) {
    s = -1;
  } else {
    return false;
  }
  return true;
}
inline int sign(const Num& x) {
  int s = 0;
  if (!sign_known(x, s)) throw Undecided{__LINE__};
  return s;
}

/// Whether the exact value is >= 0 (> 0), decided or Undecided.
inline bool non_negative(const Num& x) {
  if (is_exact_zero(x) || lower(x) >= 0) return true;
  return sign(x) >= 0;
}
inline bool positive(const Num& x) {
  if (is_exact_zero(x) || upper(x) <= 0) return false;
  return sign(x) > 0;
}

inline bool less_equal(const Num& x, const Num& y) {
  return non_negative(y - x);
}
inline bool less(const Num& x, const Num& y) {
  return positive(y - x);
}

/// x <= bound for a bound that is >= 0 by construction (a sum of magnitudes): an exact zero x
/// holds whatever the bound's interval.
inline bool within(const Num& x, const Num& bound) {
  return is_exact_zero(x) || less_equal(x, bound);
}

/// |x|, without deciding its sign: where the interval holds zero, the interval [0, max].
inline Num abs(const Num& x) {
  if (x.hi == 0 && x.lo == 0 && x.err == 0) return x;
  if (lower(x) >= 0) return x;
  if (upper(x) <= 0) return -x;
  const double top = std::fmax(-lower(x), upper(x));
  return between_zero_and(top * detail::kBoundGrowth);
}

/// An interval holding max(x, y) (larger_of) or min(x, y) (smaller_of), without deciding which
/// is larger.
inline Num hull(double low, double high) {
  const double mid = low * 0.5 + high * 0.5;
  const double half = std::fmax(mid - low, high - mid) * detail::kBoundGrowth + 0x1p-1074;
  if (!std::isfinite(mid) || !std::isfinite(half)) throw Undecided{__LINE__};
  return Num{mid, 0, half};
}
inline Num larger_of(const Num& x, const Num& y) {
  if (x.err == 0 && y.err == 0 && x.hi == y.hi && x.lo == y.lo) return x;
  if (lower(x) >= upper(y)) return x;
  if (lower(y) >= upper(x)) return y;
  return hull(std::fmax(lower(x), lower(y)), std::fmax(upper(x), upper(y)));
}
inline Num smaller_of(const Num& x, const Num& y) {
  return -larger_of(-x, -y);
}

/// A nonnegative quantity known to lie in [lo, hi]: sums and products of magnitudes (condition
/// numbers, bounds), computed in plain double with each result widened outward by 2^-50 relative
/// (above the 2^-53 of its rounding) and 2^-1074 absolute (the subnormal range).
struct Range {
  double lo = 0, hi = 0;
};

inline Range widened(double lo, double hi) {
  const double l = lo * (1 - 0x1p-50) - 0x1p-1074;
  return Range{l > 0 ? l : 0.0, hi * (1 + 0x1p-50) + (hi > 0 ? 0x1p-1074 : 0.0)};
}
inline Range operator+(const Range& x, const Range& y) {
  if (x.hi == 0) return y;
  if (y.hi == 0) return x;
  return widened(x.lo + y.lo, x.hi + y.hi);
}
inline Range operator*(const Range& x, const Range& y) {
  if (x.hi == 0 || y.hi == 0) return Range{};
  return widened(x.lo * y.lo, x.hi * y.hi);
}
/// |x| as a range.
inline Range magnitude_of(const Num& x) {
  if (is_exact_zero(x)) return Range{};
  const double l = lower(x), u = upper(x);
  if (l >= 0) return Range{l, u};
  if (u <= 0) return Range{-u, -l};
  return Range{0, std::fmax(-l, u)};
}
/// A range as a certified number (Undecided beyond double's range).
inline Num as_num(const Range& r) {
  if (!std::isfinite(r.hi)) throw Undecided{__LINE__};
  if (r.hi == 0) return Num{};
  const double mid = r.lo * 0.5 + r.hi * 0.5;
  const double half = std::fmax(mid - r.lo, r.hi - mid) * detail::kBoundGrowth + 0x1p-1074;
  return Num{mid, 0, half};
}

/// An approximation of the value, for reports (ratios).
inline double approx(const Num& x) {
  return x.hi + x.lo;
}

}  // namespace oblique::oracle::certified
