// Decodes fuzzer bytes into an oblique problem: scalar type, convention, method, a projection
// (a family built from decoded parameters, or 16 raw numbers) and a plane. Every number is either
// a special value picked by index (libFuzzer's comparison tracing does not see double compares, so
// 0, -0, subnormals, DBL_MIN, DBL_MAX, powers of two and ties are reached this way) or 8 raw bytes.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>

#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/protocol/numbers.h"

namespace oblique::fuzz {

/// Reads bytes front to back; past the end it yields zeros.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  double raw_double() {
    std::uint8_t bytes[8] = {};
    for (auto& b : bytes) b = byte();
    double d;
    std::memcpy(&d, bytes, sizeof d);
    return d;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// The special values, by index. A selector byte below kSpecialCount picks one; 255 reads 8 raw
/// bytes; anything else gives a small dyadic (selector - kSpecialCount - 64) / 8.
inline double special_value(int index) {
  constexpr double dmax = std::numeric_limits<double>::max();
  constexpr double dmin = std::numeric_limits<double>::min();
  constexpr double denorm = std::numeric_limits<double>::denorm_min();
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double table[] = {0.0,
                          -0.0,
                          1.0,
                          -1.0,
                          2.0,
                          0.5,
                          -2.0,
                          -0.5,
                          dmin,
                          -dmin,
                          denorm,
                          -denorm,
                          dmax,
                          -dmax,
                          eps,
                          1.0 + eps,
                          1.0 - eps / 2,
                          1e-6,
                          1e12,
                          1e-12,
                          1e6,
                          0.1,
                          3.0,
                          0.25,
                          -0.25,
                          1e-300,
                          1e300,
                          std::ldexp(1.0, -1074 + 52),
                          0.75,
                          1.5,
                          4.0,
                          -4.0,
                          1.0 / 3,
                          std::ldexp(1.0, 1023),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::quiet_NaN()};
  constexpr int count = sizeof(table) / sizeof(table[0]);
  return table[index % count];
}
constexpr int kSpecialCount = 37;

inline double number(ByteReader& in) {
  const int selector = in.byte();
  if (selector < kSpecialCount) return special_value(selector);
  if (selector == 255) return in.raw_double();
  return (selector - kSpecialCount - 64) / 8.0;
}

struct FuzzCase {
  protocol::Precision scalar = protocol::Precision::float64;
  Convention convention = Convention::gl;
  Method method = Method::automatic;
  /// 0..4 built (frustum, infinite, orthographic, y-flipped frustum, rotated), 5 raw, 6 a
  /// frustum or infinite frustum times a camera shift T(tx, ty, 0): M14, M24 != 0 (stereo, lens
  /// shift; generators::Family::stereo_shift).
  int family = 0;
  Matrix4<double> matrix = Matrix4<double>::Identity();
  Vector4<double> plane = Vector4<double>::Zero();
};

inline const char* family_label(int family) {
  const char* names[] = {"frustum", "infinite", "orthographic", "y_flipped",
                         "rotated", "raw",      "stereo_shift"};
  return names[family % 7];
}

inline constexpr std::uint8_t kShiftMarker = 0x53;  // 'S'

/// Builds the case; builder parameters that break a builder's preconditions fall back to raw.
inline FuzzCase decode(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  FuzzCase c;
  c.scalar = protocol::all_precisions[in.byte() % 3];
  c.convention = all_conventions[in.byte() % 3];
  c.method = all_methods[in.byte() % std::size(all_methods)];
  c.family = in.byte() % 6;
  if (c.family == 5) {
    for (int i = 0; i < 16; ++i) c.matrix(i / 4, i % 4) = number(in);
  } else {
    const double l = number(in), r = number(in), b = number(in), t = number(in);
    const double n = number(in), f = number(in);
    const bool finite = std::isfinite(l) && std::isfinite(r) && std::isfinite(b) &&
                        std::isfinite(t) && std::isfinite(n) && std::isfinite(f);
    const bool sides = finite && l != r && b != t;
    if (c.family == 2 && sides && n != f) {
      c.matrix = orthographic(l, r, b, t, n, f, c.convention);
    } else if (c.family == 1 && sides && n > 0) {
      c.matrix = infinite_frustum(l, r, b, t, n, c.convention);
    } else if (sides && n > 0 && f > n) {
      c.matrix = frustum(l, r, b, t, n, f, c.convention);
      if (c.family == 3) c.matrix.row(1) *= -1;
      if (c.family == 4) {
        const double angle = number(in);
        const double ca = std::cos(angle), sa = std::sin(angle);
        Matrix4<double> rot = Matrix4<double>::Identity();
        rot(0, 0) = ca, rot(0, 2) = sa, rot(2, 0) = -sa, rot(2, 2) = ca;
        if (std::isfinite(ca) && std::isfinite(sa)) c.matrix = c.matrix * rot;
      }
    } else {
      c.family = 5;
      for (int i = 0; i < 16; ++i) c.matrix(i / 4, i % 4) = number(in);
    }
  }
  for (int i = 0; i < 4; ++i) c.plane(i) = number(in);
  // After the plane, the byte kShiftMarker shifts a frustum or infinite frustum by (tx, ty, 0)
  // (two more numbers). Inputs that end earlier, or go on with another byte, decode as before.
  if ((c.family == 0 || c.family == 1) && in.byte() == kShiftMarker) {
    Matrix4<double> shift = Matrix4<double>::Identity();
    shift(0, 3) = number(in);
    shift(1, 3) = number(in);
    if (std::isfinite(shift(0, 3)) && std::isfinite(shift(1, 3))) {
      c.matrix = c.matrix * shift;
      c.family = 6;
    }
  }
  return c;
}

}  // namespace oblique::fuzz
