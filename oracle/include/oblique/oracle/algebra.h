// 4-vector and 4x4 algebra written once over the checker's number types: exact rationals
// (exact.h), certified intervals (certified::Num) and ranges of magnitudes (certified::Range).
// A term with an exact zero is left out of a sum, so an interval sum keeps only the errors of the
// terms that are there (for rationals the value is the same either way).
#pragma once

#include <array>

#include "oblique/oracle/certified.h"
#include "oblique/oracle/exact.h"

namespace oblique::oracle::algebra {

inline bool is_zero(const exact::Rational& x) {
  return sgn(x) == 0;
}
inline bool is_zero(const certified::Num& x) {
  return certified::is_exact_zero(x);
}
inline bool is_zero(const certified::Range& x) {
  return x.hi == 0;
}

template <class N>
using Vec = std::array<N, 4>;
template <class N>
using Mat = std::array<Vec<N>, 4>;  // rows

/// a . b.
template <class N>
N dot(const Vec<N>& a, const Vec<N>& b) {
  N s{};
  bool first = true;
  for (int i = 0; i < 4; ++i) {
    if (is_zero(a[i]) || is_zero(b[i])) continue;
    s = first ? N(a[i] * b[i]) : N(s + a[i] * b[i]);
    first = false;
  }
  return s;
}

/// m v.
template <class N>
Vec<N> mul(const Mat<N>& m, const Vec<N>& v) {
  return {dot(m[0], v), dot(m[1], v), dot(m[2], v), dot(m[3], v)};
}

/// a x + b y.
template <class N>
Vec<N> combine(const N& a, const Vec<N>& x, const N& b, const Vec<N>& y) {
  Vec<N> out;
  for (int i = 0; i < 4; ++i) out[i] = a * x[i] + b * y[i];
  return out;
}

/// v . p' for p' with entries -1, 0 or 1: a signed sum, no products.
template <class N>
N signed_sum(const Vec<N>& v, const std::array<int, 4>& p) {
  N s{};
  bool first = true;
  for (int j = 0; j < 4; ++j) {
    if (p[j] == 0 || is_zero(v[j])) continue;
    const N term = p[j] > 0 ? N(v[j]) : N(-v[j]);
    s = first ? term : N(s + term);
    first = false;
  }
  return s;
}

/// m p' for p' with entries -1, 0 or 1: sums of columns, no products.
template <class N>
Vec<N> signed_column_sum(const Mat<N>& m, const std::array<int, 4>& p) {
  return {signed_sum(m[0], p), signed_sum(m[1], p), signed_sum(m[2], p), signed_sum(m[3], p)};
}

}  // namespace oblique::oracle::algebra
