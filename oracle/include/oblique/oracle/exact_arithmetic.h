// The exact oracle's arithmetic for ViewVolume (view_volume.h): rationals, every predicate
// decided exactly, nothing scaled.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "oblique/oracle/algebra.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/plane.h"

namespace oblique::oracle {

template <class T>
class ExactArithmetic {
 public:
  using Num = exact::Rational;
  using Magnitude = exact::Rational;
  using Mat = algebra::Mat<Num>;

  ExactArithmetic(const Matrix4<T>&, const Vector4<T>&) {}

  /// The exponents M and C are held scaled by (2^-row_scale(), 2^-plane_scale()): none here.
  int row_scale() const { return 0; }
  int plane_scale() const { return 0; }
  Num matrix_entry(T x) const { return exact::to_rational(x); }
  Num plane_entry(T x) const { return exact::to_rational(x); }
  /// The underflow unit of T (tolerance::underflow_unit) in the units of a row entry and of C . Q.
  Num underflow_row() const { return tolerance::underflow_unit<T>(); }
  Num underflow_dot() const { return tolerance::underflow_unit<T>(); }

  static Num constant(double x) { return Num(x); }
  static Num gamma(int n) { return tolerance::gamma(n, tolerance::precision_bits<T>()); }
  static Num unit_roundoff() { return tolerance::unit_roundoff(tolerance::precision_bits<T>()); }
  static Num abs(const Num& x) { return exact::abs(x); }
  static bool less_equal(const Num& x, const Num& y) { return x <= y; }
  static bool less(const Num& x, const Num& y) { return x < y; }

  static Magnitude magnitude(const Num& x) { return exact::abs(x); }
  static Magnitude magnitude_constant(double x) { return Magnitude(x); }
  static Num as_num(const Magnitude& x) { return x; }
  /// Whether some entry of v is at least t (a power of two).
  static bool some_at_least(const algebra::Vec<Magnitude>& v, double t) {
    for (const Magnitude& x : v) {
      if (x >= t) return true;
    }
    return false;
  }

  /// Whether x 2^k is at least the largest finite T, or (overflow_threshold) the overflow
  /// threshold: the largest finite T plus half an ulp of it, where rounding to nearest overflows.
  static bool at_least_largest(const Num& x, bool overflow_threshold, int k) {
    Num limit = exact::to_rational(std::numeric_limits<T>::max());
    if (overflow_threshold)
      limit += exact::to_rational(std::ldexp(
          T(1), std::numeric_limits<T>::max_exponent - std::numeric_limits<T>::digits - 1));
    return (k == 0 ? x : Num(x * exact::power_of_two(k))) >= limit;
  }

  std::optional<Mat> inverse(const Mat& m) const { return exact::inverse(m); }
  /// The signs of C'_k, of C' . p' (a corner's C . p, and C . Q) and of (M^-1 p')_w.
  int plane_sign(const Num& x, int) const { return sgn(x); }
  int clip_dot_sign(const Num& x, const std::array<int, 4>&) const { return sgn(x); }
  int w_sign(const Num& x, const std::array<int, 4>&) const { return sgn(x); }
  /// A tighter C . Q where the arithmetic's is too wide to divide by: exact already.
  void refine_corner_dot(Num&, const std::array<int, 4>&) const {}
};

}  // namespace oblique::oracle
