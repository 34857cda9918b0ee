// The campaign's float engine: Lengyel's method in closed form for the perspective shape
//   M = [m11 0 m13 0; 0 m22 m23 0; 0 0 m33 m34; 0 0 m43 0]
// (symmetric, off-axis, infinite, flipped and jittered frusta; oblique::perspective_shape_only),
// in float throughout, the way engines write it: no guards and no statuses.
//   C' = M^-T C:  C'_x = C_x / m11, C'_y = C_y / m22, C'_z = C_w / m34
//   Q' = (sgn C'_x, sgn C'_y, z, 1): the corner of the clip volume that maximises C' . Q'
//   Q  = M^-1 Q': Q_z = 1 / m43, Q_w = (Q'_z - m33 Q_z) / m34, Q_x = (Q'_x - m13 Q_z) / m11,
//                 Q_y = (Q'_y - m23 Q_z) / m22
//   a  = (z_high - z_low) / (C . Q), and the near plane a C:
//        gl M'_3 = a C - M_4; zero_one M'_3 = a C; reversed_z M'_3 = M_4 - a C.
// make_oblique_zero_one_from_gl is the [0, 1] engine that keeps one GL code path, as engines
// ported from OpenGL do: the matrix taken to GL's depth range, the GL row formed, and the row
// converted back (M'_3 = (M'_3(gl) + M_4) / 2), in float.
// C is first scaled by a power of two so that its largest component is in [0.5, 1) (the answer
// does not change): C . Q and a then neither overflow nor underflow for planes at the ends of
// float's range; a component far below the largest may be lost, which no rasterizer sees.
#include "float_engine.h"

#include <cmath>

namespace oblique::false_alarms {
namespace {

enum class Depth { gl, zero_one, reversed_z };

float sgn(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}

void make_oblique(float m[16], const float plane[4], Depth depth) {
  // Column-major: m[4 * column + row].
  const float m11 = m[0], m22 = m[5], m13 = m[8], m23 = m[9], m33 = m[10], m43 = m[11], m34 = m[14];
  float largest = 0.0f;
  for (int i = 0; i < 4; ++i) largest = std::fmax(largest, std::fabs(plane[i]));
  int exponent = 0;
  std::frexp(largest, &exponent);
  float c[4];
  for (int i = 0; i < 4; ++i) c[i] = std::ldexp(plane[i], -exponent);
  const float z_low = depth == Depth::gl ? -1.0f : 0.0f, z_high = 1.0f;
  // The corner of the clip volume farthest on C's side (the signs of C', as products: a quotient
  // could underflow to 0); on an edge of equally far corners (a zero component), its middle.
  const float sx = sgn(c[0]) * sgn(m11), sy = sgn(c[1]) * sgn(m22), sz = sgn(c[3]) * sgn(m34);
  const float corner_z = sz > 0 ? z_high : (sz < 0 ? z_low : (z_low + z_high) / 2);
  const float qz = 1.0f / m43;
  const float q[4] = {(sx - m13 * qz) / m11, (sy - m23 * qz) / m22, qz,
                      (corner_z - m33 * qz) / m34};
  const float dot = c[0] * q[0] + c[1] * q[1] + c[2] * q[2] + c[3] * q[3];
  const float a = (z_high - z_low) / dot;
  for (int j = 0; j < 4; ++j) {
    const float ac = a * c[j], m4 = m[4 * j + 3];
    m[4 * j + 2] = depth == Depth::gl ? ac - m4 : (depth == Depth::zero_one ? ac : m4 - ac);
  }
}

}  // namespace

void make_oblique_gl(float m[16], const float plane[4]) {
  make_oblique(m, plane, Depth::gl);
}
void make_oblique_zero_one(float m[16], const float plane[4]) {
  make_oblique(m, plane, Depth::zero_one);
}
void make_oblique_reversed_z(float m[16], const float plane[4]) {
  make_oblique(m, plane, Depth::reversed_z);
}
void make_oblique_zero_one_from_gl(float m[16], const float plane[4]) {
  // The row for GL's [-1, 1] from M built for [0, 1]: that M's GL form has row 3 2 M_3 - M_4
  // (z_gl = 2 z - w), the GL row is made from it, and z = (z_gl + w) / 2 takes it back.
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = 2.0f * m[4 * j + 2] - m[4 * j + 3];
  make_oblique(m, plane, Depth::gl);
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = (m[4 * j + 2] + m[4 * j + 3]) / 2.0f;
}

}  // namespace oblique::false_alarms
