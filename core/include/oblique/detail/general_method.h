// The general method, for any invertible M: C' = M^-T C and Q = M^-1 Q' through one equilibrated
// LU factorisation (equilibrated_solver.h), then detail/closed_form.h's finish(); and what it
// shares with the accurate method: the refusal of a solver that cannot be trusted, and the signs of
// C' kept only outside their error bounds.
#pragma once

#include <cmath>
#include <limits>

#include "oblique/depth_convention.h"
#include "oblique/detail/closed_form.h"  // finish()
#include "oblique/detail/closed_form_steps.h"
#include "oblique/detail/equilibrated_solver.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique {

/// The general method refuses a matrix whose equilibrated reciprocal condition number is at or
/// below this: its solve for Q could not be trusted to even two significant digits.
template <class T>
constexpr T singular_rcond_threshold() noexcept {
  return T(16) * std::numeric_limits<T>::epsilon();
}

namespace detail {

/// The signs of C' for the far corner, with 0 for a component within its error bound of zero:
/// a rounded zero's sign would send Q' to a face whose corner may lie arbitrarily far out (a
/// matrix entry of 2^-52 puts it at 2^52), and C . Q, computed there, cancels to nothing. Where
/// the component is really that small, every point of the edge is within rounding as far, and
/// the middle of the edge is the safe choice.
template <class T>
Vector4<T> trusted_signs(const Vector4<T>& c_clip, const Vector4<T>& error_bound) {
  Vector4<T> signs;
  for (int i = 0; i < 4; ++i)
    signs(i) = std::abs(c_clip(i)) <= error_bound(i) ? T(0) : sign(c_clip(i));
  return signs;
}

/// Refuses (in `out`) a matrix the equilibrated solver cannot be trusted with, and says whether
/// it did.
template <class T, class W>
bool solver_refused(const EquilibratedSolver<W>& solver, Answer<T>& out) {
  switch (solver.failure()) {
    case EquilibratedSolver<W>::Failure::zero_row:
      out.refuse(Status::singular_projection, "the projection is singular: a row is zero");
      return true;
    case EquilibratedSolver<W>::Failure::zero_column:
      out.refuse(Status::singular_projection, "the projection is singular: a column is zero");
      return true;
    case EquilibratedSolver<W>::Failure::none: break;
  }
  if (!(solver.rcond() > singular_rcond_threshold<W>())) {
    out.refuse(Status::singular_projection,
               "the projection is singular or numerically singular (reciprocal condition "
               "number after equilibration at most 16 epsilon)");
    return true;
  }
  return false;
}

/// General method for any invertible M, through EquilibratedSolver (equilibration by powers of
/// two, one LU factorisation for both solves):
///   C' = M^-T C   has the signs of   R^-1 C',
///   Q  = M^-1 Q',
/// with the signs of Q' those of C' (each one outside C'_k's error bound, or C'_k exactly 0).
/// Fills `out` (answered or refused), or hands on where the accurate method must answer (a stiff
/// plane, a sign of C' within its error bound, a stalled refinement, C . Q lost to underflow).
template <class T>
Step general(const Matrix4<T>& m, const Vector4<T>& plane, Convention convention, Answer<T>& out) {
  const EquilibratedSolver<T> solver(m);
  if (solver_refused(solver, out)) return Step::refused;
  if (!(plane.w() < T(0))) return out.refuse(Status::camera_not_behind_plane);
  const PlaneScale scale = plane_scale(plane);
  const ScaledPlane<T> scaled = scale_plane(plane, scale);
  // Stiff planes: C' and C . Q may rest on components below the others' rounding.
  if (stiff_plane(scale, scaled)) return Step::handed_on;
  T transposed_error = T(0);
  const Vector4<T> c_clip = solver.solve_transposed_unscaled(scaled.c_hat, &transposed_error);
  if (!all_finite(c_clip)) {
    return out.refuse(Status::out_of_range, "C' = M^-T C is beyond the range of the scalar type");
  }
  // A nonzero C'_k within its error bound goes to the accurate method, which settles its sign
  // exactly. The bound comes from a computed inverse and can be far above the error on matrices
  // whose entries differ greatly in size: fuzz_oblique found C'_z = 12.5 (first-order error
  // 1.4e-4) under a bound of 147 in float, and the middle corner the trusted signs take there
  // moved C . Q by 3.6%. A C'_k that came out 0 is within its first-order error of 0 (the solve
  // is componentwise backward stable, checked below), so the middle is as good as either corner
  // (the checker allows that much), and it avoids a corner that may be far out.
  const Vector4<T> bound = solver.transposed_error_bound(c_clip);
  for (int i = 0; i < 3; ++i) {
    if (c_clip(i) != T(0) && std::abs(c_clip(i)) <= bound(i)) return Step::handed_on;
  }
  const Vector4<T> corner =
      clip_corner(sign(c_clip.x()), sign(c_clip.y()), sign(c_clip.z()), convention);
  T corner_error = T(0);
  const Vector4<T> q = solver.solve(corner, &corner_error);
  // A refinement that stalled short of a small componentwise backward error: the error bounds
  // (the signs' and the checker's) assume one.
  if (all_finite(q) &&
      (transposed_error > backward_error_limit<T>() || corner_error > backward_error_limit<T>()))
    return Step::handed_on;
  return finish(m, plane, q, convention_table<T>(convention), scale, scaled, Entries::unchecked,
                out);
}

}  // namespace detail
}  // namespace oblique
