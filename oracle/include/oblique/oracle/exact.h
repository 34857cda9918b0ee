// Exact rational arithmetic (GMP) on 4-vectors and 4x4 matrices: every float, double and
// long double is a rational, so the properties are evaluated with no rounding at all.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "oblique/plane.h"

namespace oblique::oracle::exact {

using Rational = mpq_class;
using Vec = std::array<Rational, 4>;
using Mat = std::array<Vec, 4>;  // rows

/// Thrown for a NaN or an infinity: a rational has neither, and GMP given one ends the process
/// (SIGFPE). Callers check a user's numbers first and judge them; reaching this is our bug.
inline void require_finite(bool finite) {
  if (!finite)
    throw std::domain_error(
        "a NaN or an infinity reached exact arithmetic (a number that should have been judged "
        "not finite first)");
}

/// The exact value of a finite float, double or long double.
inline Rational to_rational(double x) {
  require_finite(std::isfinite(x));
  return Rational(x);
}
inline Rational to_rational(float x) {
  require_finite(std::isfinite(x));
  return Rational(static_cast<double>(x));
}
inline Rational to_rational(long double x) {
  require_finite(std::isfinite(x));
  int exponent = 0;
  const long double mantissa = std::frexp(std::fabs(x), &exponent);  // |x| = mantissa * 2^exponent
  // The 64-bit significand times 2^64 is an integer below 2^64.
  const auto integral = static_cast<unsigned long>(std::ldexp(mantissa, 64));
  static_assert(sizeof(unsigned long) * 8 >= 64, "needs a 64-bit unsigned long");
  Rational r{mpz_class(integral)};
  const int shift = exponent - 64;
  if (shift >= 0) {
    mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
  } else {
    mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(-shift));
  }
  return std::signbit(x) ? Rational(-r) : r;
}

template <class T>
Vec to_rational(const Vector4<T>& v) {
  return {to_rational(v(0)), to_rational(v(1)), to_rational(v(2)), to_rational(v(3))};
}

template <class T>
Mat to_rational(const Matrix4<T>& m) {
  Mat out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out[i][j] = to_rational(m(i, j));
  }
  return out;
}

/// 2^k exactly.
inline Rational power_of_two(long k) {
  Rational r(1);
  if (k >= 0) {
    mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(k));
  } else {
    mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
  }
  return r;
}

inline Rational abs(const Rational& x) {
  return x < 0 ? Rational(-x) : x;
}

/// x rounded to the nearest T, ties to even, with T's subnormals and overflow to infinity: the
/// correctly rounded value every error figure in ulps is measured against.
template <class T>
T round_to(const Rational& x) {
  static_assert(std::numeric_limits<T>::radix == 2, "binary types only");
  constexpr int p = std::numeric_limits<T>::digits;
  constexpr int min_exponent = std::numeric_limits<T>::min_exponent;  // normals are >= 2^(min-1)
  if (x == 0) return T(0);
  const bool negative = x < 0;
  const Rational magnitude = negative ? Rational(-x) : x;
  // e with 2^e <= |x| < 2^(e+1), from the bit lengths, corrected by one comparison.
  long e = static_cast<long>(mpz_sizeinbase(magnitude.get_num_mpz_t(), 2)) -
           static_cast<long>(mpz_sizeinbase(magnitude.get_den_mpz_t(), 2));
  if (magnitude < power_of_two(e)) --e;
  if (e >= std::numeric_limits<T>::max_exponent) {
    return negative ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::infinity();
  }
  // The last kept bit has weight 2^(e - p + 1), or the subnormal quantum 2^(min_exponent - p).
  const long quantum = std::max(e - p + 1, static_cast<long>(min_exponent - p));
  const Rational scaled = magnitude / power_of_two(quantum);  // >= 1 unless subnormal
  mpz_class integral, remainder;
  mpz_fdiv_qr(integral.get_mpz_t(), remainder.get_mpz_t(), scaled.get_num_mpz_t(),
              scaled.get_den_mpz_t());
  const int half = cmp(2 * remainder, mpz_class(scaled.get_den_mpz_t()));
  if (half > 0 || (half == 0 && mpz_odd_p(integral.get_mpz_t()))) ++integral;
  // integral <= 2^p <= 2^64, exact in T; so is the scaling by 2^quantum (overflow gives inf).
  const T significand =
      mpz_fits_ulong_p(integral.get_mpz_t())
          ? static_cast<T>(mpz_get_ui(integral.get_mpz_t()))
          : std::ldexp(T(1), static_cast<int>(mpz_sizeinbase(integral.get_mpz_t(), 2)) - 1);
  const T out = std::ldexp(significand, static_cast<int>(quantum));
  return negative ? -out : out;
}

/// How far `computed` is from the correctly rounded value of `exact`, in units in the last place
/// of that rounded value (the subnormal quantum at zero and below the normal range): 0 for the
/// correctly rounded answer, infinity for a non-finite one.
template <class T>
double ulp_distance(T computed, const Rational& exact) {
  if (!std::isfinite(computed)) return std::numeric_limits<double>::infinity();
  const T rounded = round_to<T>(exact);
  if (!std::isfinite(rounded)) return std::numeric_limits<double>::infinity();
  constexpr int p = std::numeric_limits<T>::digits;
  const long lowest = std::numeric_limits<T>::min_exponent - p;
  const long quantum =
      rounded == T(0) ? lowest : std::max(static_cast<long>(std::ilogb(rounded)) - p + 1, lowest);
  const Rational gap = abs(Rational(to_rational(computed) - to_rational(rounded)));
  return Rational(gap / power_of_two(quantum)).get_d();
}

inline int sign(const Rational& x) {
  return sgn(x);
}

inline Rational dot(const Vec& a, const Vec& b) {
  Rational s = 0;
  for (int i = 0; i < 4; ++i) s += a[i] * b[i];
  return s;
}

/// m v.
inline Vec mul(const Mat& m, const Vec& v) {
  Vec out;
  for (int i = 0; i < 4; ++i) out[i] = dot(m[i], v);
  return out;
}

inline Mat transpose(const Mat& m) {
  Mat t;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) t[i][j] = m[j][i];
  }
  return t;
}

inline Mat abs(const Mat& m) {
  Mat out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out[i][j] = abs(m[i][j]);
  }
  return out;
}

inline Vec abs(const Vec& v) {
  return {abs(v[0]), abs(v[1]), abs(v[2]), abs(v[3])};
}

inline Vec combine(const Rational& a, const Vec& x, const Rational& b, const Vec& y) {
  Vec out;
  for (int i = 0; i < 4; ++i) out[i] = a * x[i] + b * y[i];
  return out;
}

/// The exact inverse by Gauss-Jordan elimination; empty when m is singular.
inline std::optional<Mat> inverse(Mat m) {
  Mat inv{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) inv[i][j] = (i == j) ? 1 : 0;
  }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    while (pivot < 4 && m[pivot][col] == 0) ++pivot;
    if (pivot == 4) return std::nullopt;
    std::swap(m[pivot], m[col]);
    std::swap(inv[pivot], inv[col]);
    const Rational p = m[col][col];
    for (int j = 0; j < 4; ++j) {
      m[col][j] /= p;
      inv[col][j] /= p;
    }
    for (int row = 0; row < 4; ++row) {
      if (row == col || m[row][col] == 0) continue;
      const Rational f = m[row][col];
      for (int j = 0; j < 4; ++j) {
        m[row][j] -= f * m[col][j];
        inv[row][j] -= f * inv[col][j];
      }
    }
  }
  return inv;
}

/// Integers (GMP) for exact signs where rationals would cost a gcd per operation: a float, double
/// or long double is an integer times a power of two, and a vector or matrix of them is integers
/// in units of the lowest power of two any of its nonzero entries needs.
using Integer = mpz_class;
using IntegerMat = std::array<std::array<Integer, 4>, 4>;  // rows

/// The entries of v as integers in units of 2^exponent (the lowest such exponent of a nonzero
/// entry; 0 when all are zero). Precondition: every entry finite.
template <class T, std::size_t N>
std::array<Integer, N> to_integers(const std::array<T, N>& v, int& exponent) {
  static_assert(std::numeric_limits<T>::digits <= 64, "the significand must fit in 64 bits");
  static_assert(sizeof(unsigned long) * 8 >= 64, "needs a 64-bit unsigned long");
  std::array<unsigned long, N> significand{};
  std::array<int, N> own{};
  exponent = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < N; ++i) {
    if (v[i] == T(0)) continue;
    int e = 0;
    const T fraction = std::frexp(std::fabs(v[i]), &e);  // [1/2, 1)
    significand[i] =
        static_cast<unsigned long>(std::ldexp(fraction, std::numeric_limits<T>::digits));
    own[i] = e - std::numeric_limits<T>::digits;
    for (; (significand[i] & 1u) == 0; significand[i] >>= 1) ++own[i];  // trailing zeros
    exponent = std::min(exponent, own[i]);
  }
  if (exponent == std::numeric_limits<int>::max()) exponent = 0;
  std::array<Integer, N> out;
  for (std::size_t i = 0; i < N; ++i) {
    if (significand[i] == 0) continue;
    out[i] = significand[i];
    mpz_mul_2exp(out[i].get_mpz_t(), out[i].get_mpz_t(),
                 static_cast<mp_bitcnt_t>(own[i] - exponent));
    if (v[i] < T(0)) out[i] = -out[i];
  }
  return out;
}

/// det a by the Laplace expansion along the first two rows (six 2 x 2 minors each side).
inline Integer determinant(const IntegerMat& a) {
  const auto minor = [](int r, int i, int j, const IntegerMat& m) {
    return Integer(m[r][i] * m[r + 1][j] - m[r][j] * m[r + 1][i]);
  };
  Integer det;
  // Pairs of columns (i, j) for rows 1-2 and their complements (k, l) for rows 3-4, each with
  // the sign of the permutation (i, j, k, l).
  constexpr int pairs[6][5] = {{0, 1, 2, 3, 1}, {0, 2, 1, 3, -1}, {0, 3, 1, 2, 1},
                               {1, 2, 0, 3, 1}, {1, 3, 0, 2, -1}, {2, 3, 0, 1, 1}};
  for (const auto& p : pairs) {
    const Integer term = minor(0, p[0], p[1], a) * minor(2, p[2], p[3], a);
    if (p[4] > 0)
      det += term;
    else
      det -= term;
  }
  return det;
}

}  // namespace oblique::oracle::exact
