// Built twice: as shipped (ENGINE_FIXED=0), with the deliberate bug, and fixed (ENGINE_FIXED=1).
//
// The bug: the far corner's x and y signs taken from the camera-space plane, sgn(C_x) and
// sgn(C_y), as Listing 5.1 prints them. They are the signs of the clip-space plane C' only when
// m[0] and m[5] are positive: a y-flipped projection (m[5] < 0, as Vulkan-style engines build
// theirs) puts the far plane through the wrong corner and clips visible geometry.
#include "engine.h"

#ifndef ENGINE_FIXED
#define ENGINE_FIXED 0
#endif

namespace engine {
namespace {

float sgn(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}

}  // namespace

void make_oblique(float m[16], const float plane[4]) {
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
  const float scale = 2.0f / dot;
  m[2] = scale * plane[0] - m[3];
  m[6] = scale * plane[1] - m[7];
  m[10] = scale * plane[2] - m[11];
  m[14] = scale * plane[3] - m[15];
}

}  // namespace engine
