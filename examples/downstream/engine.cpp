// Built twice: as shipped (ENGINE_FIXED=0), with the deliberate bug, and fixed (ENGINE_FIXED=1).
//
// The bug: the far corner's x and y signs taken from the camera-space plane, sgn(C_x) and
// sgn(C_y), as Listing 5.1 prints them. They are the signs of the clip-space plane C' only when
// m[0] and m[5] are positive: a y-flipped projection (m[5] < 0, as Vulkan-style engines build
// theirs) puts the far plane through the wrong corner and clips visible geometry.
#include "engine.h"

#include <Eigen/LU>
#include <cmath>

#ifndef ENGINE_FIXED
#define ENGINE_FIXED 0
#endif

namespace engine {
namespace {

float sgn(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}

}  // namespace

bool make_oblique(float m[16], const float plane[4]) {
  for (int i = 0; i < 16; ++i) {
    if (!std::isfinite(m[i])) return false;
  }
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(plane[i])) return false;
  }
  if (!(plane[3] < 0.0f)) return false;  // the camera (the origin) must be behind the plane
  // The answer does not change when C is scaled by a positive number: scale it by a power of two
  // (exact) so that its largest component is in [0.5, 1), or C . Q and 2 / (C . Q) under- or
  // overflow for planes at the ends of float's range.
  float largest = 0.0f;
  for (int i = 0; i < 4; ++i) largest = std::fmax(largest, std::fabs(plane[i]));
  int exponent = 0;
  std::frexp(largest, &exponent);
  float c[4];
  for (int i = 0; i < 4; ++i) c[i] = std::ldexp(plane[i], -exponent);
  plane = c;
  if (m[0] == 0.0f || m[5] == 0.0f || m[11] == 0.0f || m[14] == 0.0f) return false;
    // C' = M^-T C: for the perspective shape, C'_x = C_x / m[0] and C'_y = C_y / m[5].
#if ENGINE_FIXED
  const float sx = sgn(plane[0]) * sgn(m[0]);
  const float sy = sgn(plane[1]) * sgn(m[5]);
#else
  const float sx = sgn(plane[0]);
  const float sy = sgn(plane[1]);
#endif
  // Q = M^-1 (sx, sy, 1, 1): the far corner opposite the plane, in camera space.
  const float qz = 1.0f / m[11];
  const float q[4] = {(sx - m[8] * qz) / m[0], (sy - m[9] * qz) / m[5], qz,
                      (1.0f - m[10] * qz) / m[14]};
  // M'_3 = (2 M_4 . Q / C . Q) C - M_4, with M_4 . Q = 1.
  const float dot = plane[0] * q[0] + plane[1] * q[1] + plane[2] * q[2] + plane[3] * q[3];
  if (!(dot > 0.0f)) return false;        // the plane misses the view volume
  if (!std::isfinite(dot)) return false;  // C . Q beyond float's range
  const float scale = 2.0f / dot;
  const float row3[4] = {scale * plane[0] - m[3], scale * plane[1] - m[7], scale * plane[2] - m[11],
                         scale * plane[3] - m[15]};
  for (float x : row3) {
    if (!std::isfinite(x)) return false;  // beyond float's range
  }
  m[2] = row3[0];
  m[6] = row3[1];
  m[10] = row3[2];
  m[14] = row3[3];
  return true;
}

void view_position(const float projection[16], float ndc_x, float ndc_y, float depth,
                   float out[3]) {
  const Eigen::Matrix4f m = Eigen::Map<const Eigen::Matrix4f>(projection);  // column-major
  const Eigen::Vector4f v = m.inverse() * Eigen::Vector4f(ndc_x, ndc_y, 2 * depth - 1, 1);
  for (int i = 0; i < 3; ++i) out[i] = v(i) / v(3);
}

}  // namespace engine
