// An engine's oblique near-plane clipping, as engines write it (Lengyel's Listing 5.1 style):
// OpenGL conventions, a column-major perspective matrix m (m[4 * column + row]), modified in
// place so that its near plane becomes `plane` (a, b, c, d in camera space, the kept side
// positive, the camera behind it: d < 0). Returns false, leaving m as it was, when there is no
// such matrix in float (the camera not behind the plane, a plane that misses the view volume, a
// degenerate matrix, numbers that are not finite, an answer beyond float's range).
#pragma once

namespace engine {

bool make_oblique(float m[16], const float plane[4]);

/// The camera-space point of a pixel from its depth-buffer value (OpenGL: NDC z = 2 depth - 1)
/// under the projection it was rendered with (column-major, the oblique one in a mirror pass):
/// out = (x, y, z). What the engine's SSAO and fog reconstruct positions with.
void view_position(const float projection[16], float ndc_x, float ndc_y, float depth, float out[3]);

}  // namespace engine
