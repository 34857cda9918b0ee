// Bit-for-bit comparison of scalars and Eigen matrices, for the tests that promise the same bits
// as a reference (closed_form_bits_test, apply_batch_test, accurate_ordinary_test).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstring>
#include <limits>

namespace oblique::test {

/// The value bits of x (x87 long double: the 10 bytes that hold it, not the padding).
template <class T>
bool same_bits(T x, T y) {
  constexpr std::size_t size = std::numeric_limits<T>::digits == 64 ? std::size_t(10) : sizeof(T);
  return std::memcmp(&x, &y, size) == 0;
}

template <class T, int R, int C>
bool same_bits(const Eigen::Matrix<T, R, C>& x, const Eigen::Matrix<T, R, C>& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!same_bits(x.data()[i], y.data()[i])) return false;
  }
  return true;
}

}  // namespace oblique::test
