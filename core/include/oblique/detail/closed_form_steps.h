// The steps of the closed form and finish() (closed_form.h) that are not the formula, shared with
// the general and the accurate methods: the answer they fill (Answer), a convention's constants
// (ConventionTable), the clip-space far corner Q' from the signs of C', the test that C . Q
// survived underflow, and accept_row3(), which keeps a row 3 only if the near plane a consumer
// extracts from it still keeps C's side.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>

#include "oblique/depth_convention.h"
#include "oblique/detail/config.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique {

namespace detail {

/// How far a method got with a request: answered (its Answer holds row 3), refused (the Answer
/// holds the status), or handed on: the method cannot settle the request in T, and the accurate
/// method answers it (handed_to_accurate()).
enum class Step : unsigned char { answered, refused, handed_on };

/// What is known of the entries of M and C: nothing yet, or that every one is zero or normal
/// (ordinary_input()). With M of the perspective shape, ordinary entries let the near plane's
/// test be decided by signs (near_plane_proved_kept()).
enum class Entries : bool { unchecked = false, ordinary = true };

/// Whether M has the standard perspective shape (has_perspective_shape()).
enum class Shape : bool { other = false, perspective = true };

/// Whether the near plane's test is still to run on a row 3, or was proved by signs already.
enum class NearPlane : bool { to_test = false, proved_kept = true };

/// The smallest |C . Q| the core's dot product of c_hat (C scaled so that its largest component
/// is about 1) and Q settles whatever its products lost to underflow: min / epsilon =
/// 2^(min_exponent - 2 + digits) (2^-970 in double). A product c_hat_i Q_i below the normal range
/// loses up to half a subnormal ulp; at this size four such losses are below 2^-100 of the sum,
/// but a smaller C . Q may rest on them, or be 0 because of them (fuzz_oblique: C = (-0.25, 3.25,
/// 0, -1.8e308) on an infinite reversed-Z matrix, C . Q = 5.7e-30 of which c_hat . Q kept
/// nothing).
template <class T>
constexpr T min_settled_dot() noexcept {
  return std::numeric_limits<T>::min() / std::numeric_limits<T>::epsilon();
}

/// Whether the rounded c_hat . q = d cannot be trusted for underflow: |d| below
/// min_settled_dot() and a product of nonzero factors below the normal range. The closed form
/// and the general method hand such a C . Q to the accurate method. (A d that small from normal
/// products alone is cancellation, which the rounding bounds cover.)
template <class T>
bool dot_lost_to_underflow(T d, const Vector4<T>& c_hat, const Vector4<T>& q) noexcept {
  if (!(std::abs(d) < min_settled_dot<T>())) return false;
  for (int i = 0; i < 4; ++i) {
    if (c_hat(i) != T(0) && q(i) != T(0) &&
        std::abs(c_hat(i) * q(i)) < std::numeric_limits<T>::min())
      return true;
  }
  return false;
}

/// The accurate method on an input the closed form or the general method cannot settle in T
/// (accurate/accurate.h).
template <class T>
ObliqueResult<T> handed_to_accurate(const Matrix4<T>& m, const Vector4<T>& plane,
                                    Convention convention);

template <class T>
T sign(T x) noexcept {
  return x > T(0) ? T(1) : (x < T(0) ? T(-1) : T(0));
}

template <class T>
ObliqueResult<T> refuse(const Matrix4<T>& m, Method method, Status status,
                        std::string_view why = {}) {
  ObliqueResult<T> r;
  r.status = status;
  r.detail = why;
  r.projection = m;
  r.method = method;
  return r;
}

/// The clip-space corner Q' (paper Eq. 7, every convention): x, y = sgn(C'_x), sgn(C'_y) and z on
/// the depth face C' leans toward (the far face whenever the camera is behind C in a perspective
/// projection). A zero sign gives the middle of the edge, which is an equally far point.
template <class T>
Vector4<T> clip_corner(T sign_x, T sign_y, T sign_z, Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const T z = sign_z > T(0)   ? T(range.z_high)
              : sign_z < T(0) ? T(range.z_low)
                              : T(range.z_low + range.z_high) / T(2);
  return Vector4<T>(sign_x, sign_y, z, T(1));
}

/// accept_row3()'s refusals.
namespace accept_row3_messages {
inline constexpr std::string_view not_finite =
    "the oblique matrix exceeds the range of the scalar type: C passes within rounding "
    "distance of the far corner Q";
inline constexpr std::string_view near_plane_lost =
    "the oblique near plane a C is lost to rounding against M_4 (|a C| is below the precision "
    "of M_4's entries): the plane is too far from the view volume for this scalar type";
}  // namespace accept_row3_messages

/// accept_row3()'s test that the near plane a consumer extracts, near = s M'_3 + t M_4, keeps
/// C's side (near_hat . c_hat > 0, near_hat = near 2^-E with 2^(E-1) <= max |near_i| < 2^E),
/// decided by signs where that is provable; false where it is not (the caller then runs the
/// test). For the perspective shape M_4 = (0, 0, K, 0), so near_i = a C_i in value for
/// i = x, y, w (ac: those products, with a > 0), and each of those terms of the dot product
/// is >= 0; if near_z and C_z do not have opposite signs, the z term is >= 0 too, and a
/// rounded sum of terms >= 0 is > 0 exactly when one term is (terms < 1: no overflow). The w
/// term is: with L(x) the frexp exponent (2^(L - 1) <= |x| < 2^L), |near_hat_w| >=
/// 2^(L(a C_w) - 1 - E) and |c_hat_w| = |C_w| 2^-e >= 2^(L(C_w) - 1 - e), so where
/// L(a C_w) + L(C_w) - E - e - 2 >= min_exponent - 1 both and their product are normal, the
/// scaling is exact, and the product of two negatives rounds to a positive number.
/// Preconditions: M of the perspective shape with every entry of M and C zero or normal (what
/// ordinary_input() finds), a > 0 and ac[i] = a C_i rounded (finish() asks only then; the
/// accurate method's ordinary path meets them too); e the frexp exponent of max |C_i|, near_z the
/// z component of near.
template <class T>
OBLIQUE_ALWAYS_INLINE bool near_plane_kept_by_signs(const Vector4<T>& plane, const T (&ac)[4],
                                                    T near_z, int e) {
  if (sign(near_z) * sign(plane.z()) < T(0)) return false;
  const T largest = std::max(std::max(std::abs(ac[0]), std::abs(ac[1])),
                             std::max(std::abs(ac[3]), std::abs(near_z)));
  constexpr unsigned all_ones = ExponentBits<T>::all_ones;
  constexpr int offset = ExponentBits<T>::bias - 1;  // L(x) = field - offset for normal x
  const unsigned f_largest = biased_exponent(largest), f_ac_w = biased_exponent(ac[3]);
  // Normal (so L is read from the field), finite, nonzero: largest, a C_w, and C_w (ordinary).
  if (f_largest - 1u >= all_ones - 1u || f_ac_w - 1u >= all_ones - 1u) return false;
  const int l_ac_w = static_cast<int>(f_ac_w) - offset;
  const int l_c_w = static_cast<int>(biased_exponent(plane.w())) - offset;
  const int l_largest = static_cast<int>(f_largest) - offset;
  return l_ac_w + l_c_w - l_largest - e - 2 >= std::numeric_limits<T>::min_exponent - 1;
}

/// near_plane_kept_by_signs() where its preconditions are known to hold (`entries` ordinary with
/// M of the perspective shape: every entry of M and C zero or normal; C scaled by 2^-e),
/// NearPlane::to_test elsewhere: the caller then runs the full test. ac as there, near_z =
/// s M'_3z + t M_4z.
template <class T>
OBLIQUE_ALWAYS_INLINE NearPlane near_plane_proved_kept(const Vector4<T>& plane, const T (&ac)[4],
                                                       T near_z, const PlaneScale& scale,
                                                       Entries entries) {
  if constexpr (ExponentBits<T>::known) {
    return NearPlane(entries == Entries::ordinary && scale.shift == -scale.top &&
                     near_plane_kept_by_signs(plane, ac, near_z, scale.top));
  } else {
    return NearPlane::to_test;
  }
}

/// A convention's constants as the closed form reads them, in T: corner_z = {z_low,
/// (z_low + z_high) / 2, z_high} (clip_corner() for sgn C'_z = -1, 0, 1), depth_span =
/// z_high - z_low, and the near plane s M_3 + t M_4 (near_rows()), with first = 0 for s = 1 and
/// 1 for s = -1 (M'_3 = a C - t M_4, or t M_4 - a C).
template <class T>
struct ConventionTable {
  T corner_z[3];
  T depth_span;
  T s, t;
  int first;
};

template <class T>
constexpr ConventionTable<T> make_convention_table(Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const RowCombination near_combination = near_rows(convention);
  return {{T(range.z_low), T(range.z_low + range.z_high) / T(2), T(range.z_high)},
          T(range.z_high - range.z_low),
          T(near_combination.m3),
          T(near_combination.m4),
          near_combination.m3 > 0 ? 0 : 1};
}

/// The table for `convention` (gl, zero_one, reversed_z: the enumerators' order).
template <class T>
const ConventionTable<T>& convention_table(Convention convention) {
  static constexpr ConventionTable<T> tables[] = {make_convention_table<T>(Convention::gl),
                                                  make_convention_table<T>(Convention::zero_one),
                                                  make_convention_table<T>(Convention::reversed_z)};
  return tables[static_cast<int>(convention)];
}

/// accept_row3()'s test that the near plane a consumer extracts from the rounded matrix,
/// s row3 + t M_4 (m4: row 4 of M; s and t from the convention's table), still keeps C's side
/// (c_hat: C scaled by 2^k): when a C is below the precision of M_4's entries, a C - M_4 rounds
/// to -M_4 and it vanishes.
template <class T, class Row>
bool near_plane_kept(const Vector4<T>& row3, const Row& m4, const Vector4<T>& c_hat,
                     const ConventionTable<T>& table) {
  const Vector4<T> t_m4 = table.t * m4.transpose();
  const Vector4<T> near_extracted = table.s * row3 + t_m4;
  const Vector4<T> near_hat =
      scaled_by_power_of_two(near_extracted, -magnitude_exponent(near_extracted));
  return near_hat.dot(c_hat) > T(0);
}

/// A method's answer without the matrix it modifies: the status (and message), row 3 of M' when
/// ok, and Q when the computation got that far.
template <class T>
struct Answer {
  Status status = Status::ok;
  std::string_view detail;
  Vector4<T> row3 = Vector4<T>::Zero();
  Vector4<T> far_corner = Vector4<T>::Zero();

  /// Records a refusal.
  Step refuse(Status why_not, std::string_view why = {}) noexcept {
    status = why_not;
    detail = why;
    return Step::refused;
  }

  /// The ObliqueResult for projection m, answered by `method`.
  ObliqueResult<T> result(const Matrix4<T>& m, Method method) const {
    ObliqueResult<T> r;
    r.status = status;
    r.detail = detail;
    std::memcpy(r.projection.data(), m.data(), sizeof(T) * 16);
    if (status == Status::ok) {
      for (int j = 0; j < 4; ++j) r.projection(2, j) = row3(j);
    }
    r.far_corner = far_corner;
    r.method = method;
    return r;
  }
};

/// Keeps row3 as M'_3 in `out` (status ok), or refuses it as out_of_range where it is not finite
/// or the near plane a consumer extracts from it, s row3 + t M_4, no longer keeps C's side
/// (near_plane_kept(); `near_plane`: proved_kept where near_plane_kept_by_signs() proved it).
/// c_hat: C scaled by 2^k.
template <class T>
OBLIQUE_ALWAYS_INLINE Step accept_row3(const Vector4<T>& row3, const Matrix4<T>& m,
                                       const Vector4<T>& c_hat, const ConventionTable<T>& table,
                                       NearPlane near_plane, Answer<T>& out) {
  if (!all_finite(row3)) return out.refuse(Status::out_of_range, accept_row3_messages::not_finite);
  if (near_plane == NearPlane::to_test && !near_plane_kept(row3, m.row(3), c_hat, table))
    return out.refuse(Status::out_of_range, accept_row3_messages::near_plane_lost);
  out.status = Status::ok;
  out.row3 = row3;
  return Step::answered;
}

/// accept_row3() for a result r under construction (the accurate method's form): r with row 3
/// of its projection set to row3, or refused.
template <class T>
ObliqueResult<T> accept_row3(ObliqueResult<T> r, const Vector4<T>& row3, const Vector4<T>& c_hat,
                             Convention convention) {
  Answer<T> answer;
  accept_row3(row3, r.projection, c_hat, convention_table<T>(convention), NearPlane::to_test,
              answer);
  if (answer.status == Status::ok) {
    r.projection.row(2) = row3.transpose();
  } else {
    r.status = answer.status;
    r.detail = answer.detail;
  }
  return r;
}
}  // namespace detail
}  // namespace oblique
