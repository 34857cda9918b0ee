// oblique: Lengyel's oblique near plane. apply() makes the near plane of a projection matrix M a
// camera-space clip plane C (the camera behind it, C_w < 0), keeps the four side planes, and
// tilts the far plane as little as it can by passing it through Q, the corner of the view volume
// farthest on C's positive side; in the GL [-1, 1], [0, 1] and reversed-Z depth conventions
// (depth_convention.h), or a status that says why there is no answer (status.h).
//
// This header declares apply(); link oblique::core, which compiles it for float, double and long
// double (a header-only build includes oblique/definitions.h instead). apply_batch(): batch.h.
// The references for the code around the matrix (depth, culling planes, the pass camera):
// oblique/references/. The methods' internals: oblique/detail/.
//
// The closed form, which answers the common request (the standard perspective shape: A = M11,
// B = M13, D = M22, E = M23, G = M33, H = M34, K = M43, zeros elsewhere; paper Eqs. 15, 20):
//   C'   = M^-T C has the signs of (C_x / A, C_y / D, C_w / H); Q' the clip-space corner by them,
//   Q    = M^-1 Q' = ((Q'_x - B/K) / A, (Q'_y - E/K) / D, 1/K, (Q'_z - G/K) / H),
//   a    = (z_high - z_low) / (C . Q),
//   M'_3 = a C - t M_4      (near = s M_3 + t M_4, per convention: depth_convention.h).
// Its code, with the care for scaling and underflow: detail/closed_form.h. Any other invertible
// M goes through one equilibrated LU solve (Method::general); Method::accurate rounds each entry
// of M'_3 once (near-correct rounding); Method::automatic picks the closed form where it applies.
#pragma once

#include "oblique/depth_convention.h"  // Convention, clip_depth_range(), near_rows()
#include "oblique/plane.h"             // Matrix4, Vector4 (Eigen/Core)
#include "oblique/projection.h"        // perspective(), frustum(), has_perspective_shape()
#include "oblique/result.h"            // Method, ObliqueResult
#include "oblique/status.h"            // Status

namespace oblique {

/// M' for `projection` M and the camera-space clip plane `plane` C (kept side positive):
///   M'_1 = M_1, M'_2 = M_2, M'_4 = M_4, near(M') = a C with a > 0, far(M') . Q = 0,
/// Q = M^-1 Q' the corner of the original view volume farthest on C's positive side.
/// Preconditions are checked, in this order, and reported as statuses: finite input
/// (invalid_input), nonzero entries within max_magnitude_spread<T>() binades (out_of_range), an
/// invertible matrix (singular_projection), C_w < 0 (camera_not_behind_plane), C . Q > 0
/// (plane_misses_view_volume), a representable answer (out_of_range).
template <class T>
ObliqueResult<T> apply(const Matrix4<T>& projection, const Vector4<T>& plane, Convention convention,
                       Method method = Method::automatic);

}  // namespace oblique
