// Writes the closed form's expected answers (closed_form_bits.h) to standard output: apply()'s
// answer, by the closed form, to requests drawn from the generators' valid and invalid cases of
// every family and convention, to perspective cases with special values put in their entries
// (zeros of both signs, subnormals, the ends of the range, infinities, NaN) or their planes
// scaled to the edges of the exponent range or made stiff, and to far planes up to the top of
// the range. Run once, on a version whose answers were checked; the file it wrote is the data
// closed_form_bits_test compares apply() against:
//   make_closed_form_bits > tests/data/closed_form_bits.txt
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "closed_form_bits.h"
#include "oblique/cases/generators.h"
#include "oblique/oblique.h"
#include "special_values.h"

namespace oblique {
namespace {

using test::bits_token;

template <class T>
void write(const Matrix4<T>& m, const Vector4<T>& c, Convention convention, Method method) {
  // The closed form's requests only (apply()'s automatic choice of the general method is not).
  if (method == Method::automatic && all_finite(m) && all_finite(c) &&
      !magnitude_spread_exceeds<max_magnitude_spread<T>()>(m) && !has_perspective_shape(m))
    return;
  const ObliqueResult<T> r = apply<T>(m, c, convention, method);
  std::string line = std::string(test::scalar_token<T>()) + " " +
                     std::string(convention_name(convention)) + " " +
                     std::string(method_name(method));
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) line += " " + bits_token(m(i, j));
  for (int i = 0; i < 4; ++i) line += " " + bits_token(c(i));
  line += " " + std::string(status_code(r.status)) + " " + std::string(method_name(r.method));
  for (int j = 0; j < 4; ++j) line += " " + bits_token(r.projection(2, j));
  for (int j = 0; j < 4; ++j) line += " " + bits_token(r.far_corner(j));
  line += " " + (r.detail.empty() ? std::string("-") : std::string(r.detail));
  std::cout << line << '\n';
}

template <class T>
Method method_for(int i) {
  return i % 2 == 0 ? Method::closed_form : Method::automatic;
}

template <class T>
void write_scalar(int per_source) {
  using limits = std::numeric_limits<T>;
  {
    const auto gen = cases::valid_case<T>();
    rc::Random random(17001);
    for (int i = 0; i < per_source; ++i) {
      const cases::Case<T> c = gen(random.split(), i % 101).value();
      write(c.matrix, c.plane, c.convention, method_for<T>(i));
    }
  }
  {
    const auto gen = cases::invalid_case<T>();
    rc::Random random(17002);
    for (int i = 0; i < per_source / 2; ++i) {
      const cases::Case<T> c = gen(random.split(), i % 101).value();
      write(c.matrix, c.plane, c.convention, method_for<T>(i));
    }
  }
  {
    const auto gen = cases::valid_case_in<T>({std::begin(cases::perspective_shape_families),
                                              std::end(cases::perspective_shape_families)},
                                             cases::every_convention());
    const std::vector<T> specials = test::special_values<T>();
    const int exponent_edges[] = {limits::max_exponent - 1,
                                  limits::max_exponent - 2,
                                  limits::min_exponent - 1,
                                  limits::min_exponent - 2,
                                  limits::min_exponent - limits::digits,
                                  limits::max_exponent / 2,
                                  -limits::max_exponent / 2};
    rc::Random random(17003);
    for (int i = 0; i < per_source; ++i) {
      cases::Case<T> c = gen(random.split(), i % 101).value();
      const int pick = i % 4;
      const T special = specials[std::size_t(i / 4) % specials.size()];
      const int entry = (i / 7) % 20;  // 16 matrix entries, then 4 plane components
      if (pick == 0 || pick == 1) {
        if (entry < 16) {
          c.matrix(entry / 4, entry % 4) = special;
        } else {
          c.plane(entry - 16) = special;
        }
      }
      if (pick == 1 || pick == 2) {
        // The whole plane scaled to an edge of the exponent range (its largest component 2^k).
        const int k = exponent_edges[std::size_t(i / 3) % std::size(exponent_edges)];
        const int e = magnitude_exponent(c.plane);
        for (int j = 0; j < 4; ++j) c.plane(j) = std::ldexp(c.plane(j), k - e);
      }
      if (pick == 3) {
        // One plane component pushed far below the others (a stiff plane).
        const int j = (i / 5) % 4;
        c.plane(j) = std::ldexp(c.plane(j), -(i % 3 + 1) * limits::digits * 8);
      }
      write(c.matrix, c.plane, c.convention, method_for<T>(i));
    }
  }
  {
    // Far planes up to 2^(max_exponent - 1), so that a C nears the bottom of the range, and
    // planes whose components span the exponent range (accept_row3's near-plane test).
    int i = 0;
    for (Convention convention : all_conventions) {
      for (int far_exponent : {limits::max_exponent - 1, limits::max_exponent - 4,
                               limits::max_exponent - limits::digits, limits::max_exponent / 2}) {
        const T far = std::ldexp(T(1), far_exponent);
        const Matrix4<T> m = frustum<T>(T(-1), T(1), T(-1), T(1), T(1), far, convention);
        for (int j = 0; j < 2 * limits::digits + 8; j += (2 * limits::digits + 8) / 4) {
          for (int k = 0; k < 4 * limits::digits; k += limits::digits) {
            for (const T z : {T(1)}) {
              const Vector4<T> plane(std::ldexp(T(0.5), -k), std::ldexp(T(-0.25), -k / 2), z,
                                     -std::ldexp(T(1), -j));
              write(m, plane, convention, method_for<T>(i++));
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace oblique

int main() {
  oblique::write_scalar<float>(200);
  oblique::write_scalar<double>(400);
  oblique::write_scalar<long double>(200);
  std::cout.flush();
  if (!std::cout) {
    std::fprintf(stderr, "make_closed_form_bits: could not write the answers\n");
    return 1;
  }
  return 0;
}
