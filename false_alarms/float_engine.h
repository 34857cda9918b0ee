// An engine-style oblique function in float, as engines ship it: the closed form for the
// perspective shape (oblique::perspective_shape_only), column-major matrices, one
// function per depth convention, no statuses (every call writes a matrix; callers never pass an
// input without an answer). It is correct: the false-alarm campaign (README.md here) runs it for a
// long time through oblique::testing and the fuzz driver, and a finding is a false alarm of the
// harness.
#pragma once

namespace oblique::false_alarms {

/// M' in place of `m` (column-major, m[4 * column + row]) for the plane C = `plane`, camera space.
void make_oblique_gl(float m[16], const float plane[4]);
void make_oblique_zero_one(float m[16], const float plane[4]);
void make_oblique_reversed_z(float m[16], const float plane[4]);
/// [0, 1] through the GL function: to GL's range, the GL row, and back ((M'_3 + M_4) / 2).
void make_oblique_zero_one_from_gl(float m[16], const float plane[4]);

}  // namespace oblique::false_alarms
