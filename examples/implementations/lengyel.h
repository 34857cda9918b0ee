// A small, self-contained oblique-clipping implementation of the kind an engine ships, written
// from the formulas (no Eigen, no oblique core), wrapped in the JSON Lines adapter that
// `oblique verify` drives. The example programs beside it are this implementation, correct or
// with one mistake that real engines make.
//
//   request: {"projection": [16 numbers, row-major], "plane": [4 numbers], "convention": "gl"}
//   answer:  {"status": "ok", "projection": [16 numbers]}  or  {"status": "<code>"}
//
// Usage: PROGRAM [--float]   (--float computes in float instead of double)
#pragma once

namespace lengyel {

enum class Mistake {
  none,
  camera_space_signs,     ///< sgn(C_x), sgn(C_y) instead of sgn(C'_x), sgn(C'_y), C' = M^-T C
  zero_one_factor_on_gl,  ///< a = 1 / (C . Q), M'_3 = a C (the [0, 1] formula) on every matrix
  no_camera_guard,        ///< no check that the camera is behind the plane (C_w < 0)
  sign_by_division,       ///< sgn(x) = x / |x|, which is NaN at 0
  two_bugs,               ///< no_camera_guard and sign_by_division together
  ignores_shift,          ///< C' and Q from M without its stereo / lens shift (M14 = M24 = 0)
  no_statuses,            ///< no guards, no refusals: every input gets a matrix, as in engines
  /// on the perspective shape, the far corner's x sign from C_x (C'_x = C_x / M11: the sign of
  /// M11 ignored), wrong for a mirror camera made by negating M11
  ignores_m11_sign,
  /// numerical, the formula right: reversed Z computed on the [0, 1] matrix (row 3 M_4 - M_3,
  /// formed in T) and flipped back
  reversed_z_through_zero_one,
  /// numerical, the formula right: the far corner as a point Q / Q_w, a = k (M_4 . Q) / (C . Q)
  far_corner_as_point,
};

/// The adapter loop: one answer line per request line (standard input to standard output),
/// flushed so the caller never waits; computed with `mistake`. Compiled once (lengyel.cpp).
int serve(int argc, char** argv, Mistake mistake);

}  // namespace lengyel
