// Values to put in a request's entries where the closed form's checks and scalings are at their
// edges: zeros of both signs, subnormals, the smallest normal, the top of the range, powers of two
// near both ends, epsilon, one, infinities and NaN.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

namespace oblique::test {

template <class T>
std::vector<T> special_values() {
  using limits = std::numeric_limits<T>;
  return {T(0),
          T(-0.0),
          limits::denorm_min(),
          -limits::denorm_min(),
          limits::min(),
          -limits::min() / T(2),
          limits::min() * T(3) / T(4),
          limits::max(),
          -limits::max(),
          std::ldexp(T(1), limits::max_exponent - 2),
          std::ldexp(T(1), limits::max_exponent - 3),
          std::ldexp(T(-1), limits::min_exponent + limits::digits),
          limits::epsilon(),
          T(1),
          T(-1),
          limits::infinity(),
          -limits::infinity(),
          limits::quiet_NaN()};
}

}  // namespace oblique::test
