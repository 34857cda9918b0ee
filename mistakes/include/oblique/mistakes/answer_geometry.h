// What a wrong answer does, in geometry, for a finding that no known mistake reproduces: which of
// the near plane, the side rows and the far plane are right; row 3 written as alpha C + beta M_4 +
// rest beside the correct alpha* C + beta* M_4; where the far corner Q lands; what of the original
// view volume is clipped. Computed exactly (the checker's Problem); the numbers are rounded only
// for print. Compiled in oblique::mistakes (float, double, long double).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"

namespace oblique::mistakes {

struct AnswerGeometry {
  bool described =
      false;  ///< false where the input has no oblique answer or the answer is not finite
  /// Rows 1, 2 and 4 as M's (the side planes and w kept); else the first changed entry (1-based).
  bool side_rows_kept = true;
  int changed_row = 0, changed_column = 0;
  /// Row 3 = alpha C + beta M_4 + rest, alpha and beta the least-squares fit; the correct row is
  /// right_alpha C + right_beta M_4. rest_share = max|rest_i| / max|row 3_i|; in_span where each
  /// |rest_i| is within row 3's rounding in T (tolerance.h).
  double alpha = 0, beta = 0, rest_share = 0;
  bool in_span = false;
  double right_alpha = 0, right_beta = 0;
  double alpha_ratio = 0;   ///< alpha / right_alpha (exact, rounded)
  bool beta_right = false;  ///< row 3 is alpha C + right_beta M_4 within its rounding
  /// Property 1: the near plane is C (up to rounding), and whether it keeps C's kept side.
  bool near_is_c = false, near_wrong_side = false;
  /// far' . Q (Q normalised so that M_4 . Q = 1, or the edge direction where Q is at infinity)
  /// and its bound: within it, the far plane passes through Q (property 3).
  double far_at_q = 0, far_at_q_bound = 0;
  bool far_through_q = false;
  bool q_at_infinity = false;
  /// Where Q lands in the answer's clip space: its depth z' / w' (NaN at infinity), and the far
  /// face's depth.
  double q_depth = 0, far_face = 0;
  /// Property 4: a point of the original volume on C's kept side that the far plane cuts away
  /// (eye space, w = 1), at a corner or where C crosses an edge.
  bool clips = false, clipped_at_corner = false;
  std::array<double, 4> clipped_point{};
};

/// The geometry of `answer` (status ok) on (M, C) in `convention`.
template <class T>
AnswerGeometry answer_geometry(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                               const Matrix4<T>& answer);

extern template AnswerGeometry answer_geometry<float>(const Matrix4<float>&, const Vector4<float>&,
                                                      Convention, const Matrix4<float>&);
extern template AnswerGeometry answer_geometry<double>(const Matrix4<double>&,
                                                       const Vector4<double>&, Convention,
                                                       const Matrix4<double>&);
extern template AnswerGeometry answer_geometry<long double>(const Matrix4<long double>&,
                                                            const Vector4<long double>&, Convention,
                                                            const Matrix4<long double>&);

/// The description in Markdown (a list, and a sentence on what the numbers say).
std::string answer_geometry_markdown(const AnswerGeometry& geometry);

}  // namespace oblique::mistakes
