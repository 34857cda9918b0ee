// Exact rational arithmetic (GMP) on 4-vectors and 4x4 matrices: every float, double and
// long double is a rational, so the properties are evaluated with no rounding at all.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <optional>

#include "oblique/plane.h"

namespace oblique::exact {

using Rational = mpq_class;
using Vec = std::array<Rational, 4>;
using Mat = std::array<Vec, 4>;  // rows

/// The exact value of a finite float, double or long double.
inline Rational to_rational(double x) {
  return Rational(x);
}
inline Rational to_rational(float x) {
  return Rational(static_cast<double>(x));
}
inline Rational to_rational(long double x) {
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

}  // namespace oblique::exact
