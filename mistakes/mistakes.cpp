// The catalogue's entries (mistakes.h) and each mistake's knob in the one computation
// (variant.h).
#include "oblique/mistakes/mistakes.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "oblique/oblique.h"
#include "variant.h"

namespace oblique::mistakes {

using namespace oblique::oracle;  // NOLINT: the judge the catalogue is checked against

namespace {

// clang-format off
constexpr MistakeEntry kCatalogue[] = {
    {Mistake::zero_one_formula_on_gl, "zero_one_formula_on_gl",
     "the [0, 1] formula on a [-1, 1] matrix",
     "The code scales C by a = 1 / (C . Q) and writes M'_3 = a C, the formula for [0, 1] depth "
     "(Direct3D, Vulkan, Metal), on an OpenGL [-1, 1] matrix. There the near plane is M'_3 + M_4, "
     "so it becomes a C + M_4 instead of a multiple of C, and the far plane misses Q.",
     "For [-1, 1] depth use a = 2 / (C . Q) and M'_3 = a C - M_4; keep a = 1 / (C . Q), "
     "M'_3 = a C for [0, 1] depth. Take the convention as an input, not as an assumption.",
     "every [-1, 1] (gl) matrix",
     "you write the [0, 1] formula, a = 1 / (C . Q) and M'_3 = a C, on a [-1, 1] matrix"},
    {Mistake::gl_formula_on_zero_one, "gl_formula_on_zero_one",
     "the [-1, 1] formula on a [0, 1] matrix",
     "The code scales C by a = 2 / (C . Q) and writes M'_3 = a C - M_4 (OpenGL's formula) on a "
     "[0, 1] matrix, whose near plane is M'_3 alone: the near plane becomes a C - M_4, which is no "
     "multiple of C.",
     "For [0, 1] depth use a = 1 / (C . Q) and M'_3 = a C (near plane M'_3); the far corner's "
     "depth is 0 or 1, not -1 or 1.",
     "every [0, 1] (zero_one) matrix",
     "you write OpenGL's formula, a = 2 / (C . Q) and M'_3 = a C - M_4, on a [0, 1] matrix"},
    {Mistake::camera_space_signs, "camera_space_signs",
     "the far corner's signs taken from C in camera space",
     "The far corner Q' = (sgn C'_x, sgn C'_y, ...) needs the signs of the clip-space plane "
     "C' = M^-T C. The code takes sgn C_x and sgn C_y instead, which agree only for matrices that "
     "keep the signs of x and y: a mirror camera (M11 < 0), a y-flipped one (M22 < 0, Vulkan), an "
     "off-axis, shifted or rotated one picks a corner that is not the farthest, and the far plane "
     "then clips the view volume.",
     "Solve C' = M^-T C (for the perspective shape, C'_x = C_x / M11 and C'_y = C_y / M22) and "
     "take Q' = (sgn C'_x, sgn C'_y, z_far, 1).",
     "matrices where sgn C'_x != sgn C_x or sgn C'_y != sgn C_y",
     "you take Q'_x's and Q'_y's signs from C_x, C_y instead of C' = M^-T C"},
    {Mistake::ignores_m11_sign, "ignores_m11_sign",
     "the perspective fast path ignores the sign of M11",
     "On matrices of the perspective shape the code writes sgn C'_x as sgn C_x, true while "
     "M11 > 0 (C'_x = C_x / M11). A mirror camera made by negating M11 then gets the far corner on "
     "the wrong side in x. Other matrices, solved in general, are right.",
     "sgn C'_x = sgn C_x * sgn M11 on the perspective shape, or solve C' = M^-T C.",
     "perspective-shaped matrices with M11 < 0",
     "you take Q'_x's sign from C_x where M has the perspective shape, ignoring M11's sign"},
    {Mistake::ignores_m22_sign, "ignores_m22_sign",
     "the perspective fast path ignores the sign of M22",
     "On matrices of the perspective shape the code writes sgn C'_y as sgn C_y, true while "
     "M22 > 0. A y-flipped camera (Vulkan's clip space, or a flip for render-to-texture) then "
     "gets the far corner on the wrong side in y.",
     "sgn C'_y = sgn C_y * sgn M22 on the perspective shape, or solve C' = M^-T C.",
     "perspective-shaped matrices with M22 < 0",
     "you take Q'_y's sign from C_y where M has the perspective shape, ignoring M22's sign"},
    {Mistake::far_face_fixed, "far_face_fixed",
     "the far corner's depth fixed at Q'_z = 1",
     "The code takes Q' = (sgn C'_x, sgn C'_y, 1, 1) as the paper's Eq. 7 prints it. The far face "
     "is z = 1 only for forward depth with C'_z > 0: with reversed Z the far face is z = 0, and "
     "where C'_z < 0 (orthographic volumes reaching behind the eye, general matrices) the farthest "
     "corner is on the other face. C is then scaled by its value at a nearer corner.",
     "Q'_z = z_far when sgn C'_z > 0 and z_near when sgn C'_z < 0, with (z_near, z_far) = "
     "(-1, 1) for [-1, 1], (0, 1) for [0, 1] and (1, 0) for reversed Z.",
     "reversed-Z matrices, and wherever C'_z < 0",
     "you put the far corner at Q'_z = 1 whatever the convention and C'_z's sign"},
    {Mistake::wrong_face, "wrong_face",
     "the far corner taken on the near depth face",
     "The code takes Q'_z on the face opposite sgn C'_z, the near face: reversed-Z code "
     "(far face z = 0) run on a forward-Z matrix, or the other way round, or a sign slip in "
     "Q'_z = -sgn C'_z. C is scaled by its value at a nearer corner, the far plane then cuts "
     "through the view volume, or C . Q <= 0 and the input is refused.",
     "Q'_z = z_far when sgn C'_z > 0 and z_near when sgn C'_z < 0, with (z_near, z_far) = "
     "(-1, 1) for [-1, 1], (0, 1) for [0, 1] and (1, 0) for reversed Z.",
     "every matrix (wherever C'_z != 0)",
     "you put the far corner's Q'_z on the face opposite C'_z's sign"},
    {Mistake::left_handed_qw, "left_handed_qw",
     "a left-handed Q_w formula on a right-handed matrix",
     "The perspective closed form has Q_z = 1 / M43 and Q_w = (z - M33 Q_z) / M34: "
     "(z + M33) / M34 for a right-handed matrix (M43 = -1), (z - M33) / M34 for a left-handed one "
     "(M43 = 1). The code uses the left-handed Q_w on a right-handed matrix, so Q is off the far "
     "face and C . Q, and the scale, are wrong.",
     "Q_w = (Q'_z - M33 / M43) / M34, which holds for either handedness.",
     "perspective-shaped matrices with M43 != 1",
     "you compute Q_w as a left-handed matrix needs, (z - M33) / M34"},
    {Mistake::drops_off_axis, "drops_off_axis",
     "the off-axis terms M13, M23 dropped",
     "The code finds C' and Q as if the frustum were symmetric (M13 = M23 = 0), e.g. "
     "Q_x = sgn C'_x / M11 instead of (sgn C'_x + M13) / M11. An off-axis frustum (a portal seen "
     "from the side, TAA jitter, a tiled or asymmetric view) then gets a Q off the far face.",
     "Keep M13 and M23: Q = M^-1 Q', or Q_x = (sgn C'_x - M13 Q_z) / M11 and likewise for y.",
     "matrices with M13 != 0 or M23 != 0",
     "you leave M13 and M23 out of C' and Q"},
    {Mistake::abs_off_axis, "abs_off_axis",
     "the off-axis terms taken as |M13|, |M23|",
     "The code takes the magnitudes of the off-axis terms (fabs(M13), fabs(M23)) into C' and Q, "
     "as if a frustum leaned only right and up. It is right while they are >= 0 and gives a Q off "
     "the far face whenever the frustum has more field of view to the left or below than "
     "opposite: a VR eye, a tiled screenshot's top or right tiles, a portal seen from one side.",
     "Keep the signs: Q = M^-1 Q', or Q_x = (sgn C'_x - M13 Q_z) / M11 with M13 as it is.",
     "matrices with M13 < 0 or M23 < 0",
     "you take |M13| and |M23| in C' and Q"},
    {Mistake::drops_shift, "drops_shift",
     "the stereo / lens-shift terms M14, M24 dropped",
     "The code finds C' and Q from M with M14 = M24 = 0, portal math written for a centred "
     "camera. A stereo eye or lens-shifted projection (translation in clip x or y) then gets a "
     "corner and a scale for another matrix.",
     "Solve with the whole matrix: C' = M^-T C and Q = M^-1 Q'.",
     "matrices with M14 != 0 or M24 != 0",
     "you leave M14 and M24 out of C' and Q"},
    {Mistake::divides_by_m43, "divides_by_m43",
     "the perspective closed form on a matrix of another shape",
     "The code computes Q by the perspective closed form (Q_z = 1 / M43, Q_w = "
     "(z - M33 Q_z) / M34, ...) whatever the matrix. On an orthographic matrix M43 = 0: Q_z is "
     "infinite and the answer NaN; on any other shape Q is not M^-1 Q'.",
     "Use the closed form only for the perspective shape (zeros outside M11, M13, M22, M23, M33, "
     "M34, M43; M43 != 0) and solve Q = M^-1 Q' otherwise.",
     "matrices not of the perspective shape (orthographic: a NaN answer)",
     "you compute Q by the perspective closed form (Q_z = 1 / M43) on every matrix"},
    {Mistake::perspective_rows, "perspective_rows",
     "Listing 5.1's perspective rows on a matrix of another shape",
     "The code computes Q as Listing 5.1 does, Q = ((s_x + M13) / M11, (s_y + M23) / M22, -1, "
     "(z + M33) / M34), which assumes M_4 = (0, 0, -1, 0). On an orthographic or general matrix "
     "this is not M^-1 Q': C is scaled by its value at a point that is no corner.",
     "Use the shortcut only for the perspective shape with M43 = -1; solve Q = M^-1 Q' otherwise.",
     "matrices not of the perspective shape, or with M43 != -1",
     "you compute Q as Listing 5.1 does (M43 = -1 assumed) on every matrix"},
    {Mistake::skips_head_on, "skips_head_on",
     "the modification skipped for a head-on plane",
     "The code returns M unchanged when the plane's normal is (0, 0, -1), reasoning that the "
     "near plane is already parallel to it. But the near plane must also lie on C: the original "
     "near plane is at distance n, the mirror at -C_w / |C_z|. Geometry between them is drawn in "
     "the reflection.",
     "Apply the modification for every plane: for C = (0, 0, -1, -d) it moves the near plane to "
     "z = -d.",
     "planes with C_x = C_y = 0 and C_z < 0",
     "you return M unchanged for a plane with normal (0, 0, -1)"},
    {Mistake::no_camera_guard, "no_camera_guard",
     "no guard when the camera is on or in front of the plane",
     "The modification needs the camera (the eye, the origin of camera space) strictly on C's "
     "negative side, C_w < 0: otherwise the near plane C would keep the camera's side, and no "
     "oblique frustum clips what the user meant. The code answers a matrix anyway.",
     "Refuse (or fall back to the unmodified matrix plus a user clip plane) when C_w >= 0.",
     "planes with C_w >= 0",
     "you answer a matrix when C_w >= 0"},
    {Mistake::no_corner_guard, "no_corner_guard",
     "no guard when the plane misses the view volume",
     "When C keeps nothing of the view volume (C . Q <= 0 at the farthest corner) the scale "
     "a = k / (C . Q) is negative or infinite. The code divides anyway: a near plane that keeps "
     "the wrong side, or infinities when C passes through Q.",
     "Refuse when C . Q <= 0 (nothing is to be drawn), before dividing.",
     "planes with C . Q <= 0",
     "you divide by C . Q when it is <= 0"},
    {Mistake::sign_by_division, "sign_by_division",
     "sgn(x) computed as x / |x|",
     "The code computes the corner's signs as x / |x|, which is NaN for x = 0. A plane with "
     "C'_x, C'_y or C'_z exactly 0 (an axis-aligned water plane seen by an axis-aligned camera) "
     "gets a NaN corner and a NaN matrix.",
     "sgn(x) = (x > 0) - (x < 0); a zero component may take either sign (every such corner is "
     "equally far).",
     "planes with C'_x, C'_y or C'_z exactly 0",
     "you compute sgn(x) as x / |x|"},
    {Mistake::note_flip_as_printed, "note_flip_as_printed",
     "the reversed-Z route through the [0, 1] note's flip matrix as printed",
     "The [0, 1] note builds reversed Z as flip * oblique([0, 1] matrix), its flip printed with "
     "fourth row (0, 0, 1, 1). That row rewrites w (w' = z + w): row 4 of the answer becomes "
     "a C + M_4 instead of M_4, so the side planes and the perspective divide change.",
     "Flip with fourth row (0, 0, 0, 1) (z' = w - z), or directly: M'_3 = M_4 - a C with "
     "a = 1 / (C . Q) and rows 1, 2, 4 unchanged.",
     "every reversed-Z matrix",
     "you flip to reversed Z with the [0, 1] note's flip as printed, row 4 (0, 0, 1, 1)"},
    {Mistake::zero_one_factor_on_gl, "zero_one_factor_on_gl",
     "the [0, 1] factor a = 1 / (C . Q) with OpenGL's form M'_3 = a C - M_4",
     "The code writes row 3 in OpenGL's form, M'_3 = a C - M_4, but scales C by a = 1 / (C . Q), "
     "the [0, 1] factor, as code that mixes a Direct3D listing with an OpenGL one does. The near "
     "plane M'_3 + M_4 = a C is still C, but the far plane M_4 - M'_3 = 2 M_4 - a C passes "
     "through Q only for a = 2 / (C . Q): it cuts through the view volume short of Q.",
     "On a [-1, 1] matrix use a = 2 / (C . Q) with M'_3 = a C - M_4 (and a = 1 / (C . Q) only "
     "with M'_3 = a C on [0, 1]).",
     "every [-1, 1] (gl) matrix",
     "you scale C by a = 1 / (C . Q) while writing OpenGL's M'_3 = a C - M_4"},
    {Mistake::gl_factor_on_zero_one, "gl_factor_on_zero_one",
     "OpenGL's factor a = 2 / (C . Q) on [0, 1] depth",
     "The code keeps the [0, 1] (or reversed-Z) form of row 3 but scales C by a = 2 / (C . Q), "
     "OpenGL's factor. The near plane is still C; the far plane passes through the point where "
     "C is half its value at Q, so it clips the far half of what C keeps.",
     "For [0, 1] and reversed-Z depth use a = 1 / (C . Q).",
     "every [0, 1] and reversed-Z matrix",
     "you scale C by a = 2 / (C . Q) on [0, 1] or reversed-Z depth"},
    {Mistake::zero_one_form_on_gl, "zero_one_form_on_gl",
     "row 3 written M'_3 = a C on an OpenGL matrix, without - M_4",
     "The code scales with OpenGL's a = 2 / (C . Q) but writes M'_3 = a C, dropping the - M_4 "
     "that OpenGL's form needs. The near plane becomes a C + M_4, which is no multiple of C.",
     "On a [-1, 1] matrix M'_3 = a C - M_4.",
     "every [-1, 1] (gl) matrix",
     "you write M'_3 = a C without - M_4 on a [-1, 1] matrix"},
    {Mistake::gl_form_on_zero_one, "gl_form_on_zero_one",
     "row 3 written M'_3 = a C - M_4 on a [0, 1] matrix",
     "The code scales with the [0, 1] factor a = 1 / (C . Q) but writes row 3 in OpenGL's form "
     "a C - M_4. On [0, 1] depth the near plane is M'_3 alone: it becomes a C - M_4, which is no "
     "multiple of C.",
     "On a [0, 1] matrix M'_3 = a C.",
     "every [0, 1] (zero_one) matrix",
     "you write M'_3 = a C - M_4 on a [0, 1] matrix"},
    {Mistake::fixed_corner_signs, "fixed_corner_signs",
     "the far corner's x and y fixed at +1",
     "The code takes Q' = (1, 1, z, 1), the corner of a plane that faces right and up, whatever "
     "the signs of C'_x and C'_y. For a plane that faces left or down in clip space that corner "
     "is not the farthest one: C is scaled by its value at a nearer corner, and the far plane "
     "clips the view volume.",
     "Q'_x = sgn C'_x, Q'_y = sgn C'_y with C' = M^-T C.",
     "planes with C'_x < 0 or C'_y < 0",
     "you take the far corner at Q'_x = Q'_y = 1 whatever the signs of C'"},
    {Mistake::negated_off_axis, "negated_off_axis",
     "the off-axis terms M13, M23 with their signs slipped",
     "The code takes -M13 and -M23 where C' and Q need M13 and M23, as in Q_x = "
     "(sgn C'_x + M13 Q_z) / M11 instead of (sgn C'_x - M13 Q_z) / M11. It is right on a "
     "symmetric frustum; an off-axis one (a portal seen from the side, TAA jitter, a VR eye) gets "
     "a Q off the far face.",
     "Q = M^-1 Q', or Q_x = (sgn C'_x - M13 Q_z) / M11 and likewise for y.",
     "matrices with M13 != 0 or M23 != 0",
     "you take -M13 and -M23 in C' and Q"},
    {Mistake::negated_shift, "negated_shift",
     "the stereo / lens-shift terms M14, M24 with their signs slipped",
     "The code takes -M14 and -M24 where C' and Q need M14 and M24: a stereo eye or lens-shifted "
     "projection gets the corner and the scale of the other eye's matrix.",
     "Solve with the whole matrix: C' = M^-T C and Q = M^-1 Q'.",
     "matrices with M14 != 0 or M24 != 0",
     "you take -M14 and -M24 in C' and Q"},
    {Mistake::assumes_m43_minus_one, "assumes_m43_minus_one",
     "the perspective closed form with Q_z = -1 on every perspective matrix",
     "The code computes Q on the perspective shape as Listing 5.1 does, with Q_z = -1, which "
     "holds for a right-handed matrix (M43 = -1). A left-handed one (M43 = 1, Direct3D's "
     "convention) has Q_z = 1: Q lands behind the camera and C is scaled by its value there.",
     "Q_z = 1 / M43 and Q_w = (Q'_z - M33 Q_z) / M34, which hold for either handedness.",
     "perspective-shaped matrices with M43 != -1",
     "you take Q_z = -1 on every perspective matrix, left-handed ones too"},
    {Mistake::perspective_m4, "perspective_m4",
     "row 3 written as printed for the perspective shape: a C + (0, 0, 1, 0)",
     "The code writes row 3 as a C + (0, 0, 1, 0) (OpenGL; the third entry of row 3 plus one), "
     "which is a C - M_4 only where M_4 = (0, 0, -1, 0). An orthographic matrix (M_4 = "
     "(0, 0, 0, 1)), a left-handed one (M_4 = (0, 0, 1, 0)) or a turned one keeps its own M_4, "
     "so its near plane is not C.",
     "Subtract the matrix's own row 4: M'_3 = a C - M_4 (OpenGL), a C (Direct3D's [0, 1]).",
     "matrices whose row 4 is not (0, 0, -1, 0): orthographic, left-handed, turned",
     "you write row 3 as a C + (0, 0, 1, 0) whatever the matrix's row 4 is"},
    {Mistake::perspective_listing, "perspective_listing",
     "the perspective-only formula (Listing 5.1 as printed) on a matrix of another shape",
     "The code is the printed listing whole: Q = ((s_x + M13) / M11, (s_y + M23) / M22, -1, "
     "(1 + M33) / M34) (the far corner Q' = (s_x, s_y, 1, 1)) and row 3 = a C + (0, 0, 1, 0). "
     "Both assume the right-handed perspective shape (M_4 = (0, 0, -1, 0)). It is right on every perspective frustum; on an orthographic "
     "camera (a shadow map, a top-down map, an editor view) Q is no corner and row 3 keeps the "
     "wrong M_4, so the near plane is not C.",
     "Branch on the matrix: the listing for the right-handed perspective shape only; otherwise "
     "Q = M^-1 Q' and M'_3 = a C - M_4 (for an orthographic camera Q = M^-1 (s_x, s_y, 1, 1)).",
     "orthographic (and left-handed or turned) matrices; every perspective frustum is right",
     "you run the perspective-only listing (its Q and its row 3) on every matrix, orthographic "
     "ones too"},
    {Mistake::through_gl, "through_gl",
     "a route through OpenGL's range and back",
     "The code takes its matrix to OpenGL's depth range (row 3 2 M_3 - M_4 from [0, 1]; from "
     "reversed Z, M_4 - 2 M_3), runs its OpenGL function there and brings row 3 back. The route "
     "is exact; the mistakes named with it are made on the route, in OpenGL's formula, and come "
     "back scaled: OpenGL's factor slip lands as half a [0, 1] factor.",
     "Fix the mistakes on the route, or modify the matrix in its own convention.",
     "matrices of the other conventions, where the mistakes made on the route show",
     "you modify the matrix in OpenGL's range and convert it back"},
    {Mistake::through_zero_one, "through_zero_one",
     "a route through [0, 1]'s range and back",
     "The code takes its matrix to Direct3D's [0, 1] range (row 3 (M_3 + M_4) / 2 from "
     "OpenGL; M_4 - M_3 from reversed Z), runs its [0, 1] function there and brings row 3 back. "
     "The route is exact; the mistakes named with it are made on the route, in [0, 1]'s formula.",
     "Fix the mistakes on the route, or modify the matrix in its own convention.",
     "matrices of the other conventions, where the mistakes made on the route show",
     "you modify the matrix in [0, 1]'s range and convert it back"},
};
// clang-format on

}  // namespace

const MistakeEntry& mistake_entry(Mistake mistake) {
  for (const MistakeEntry& e : kCatalogue) {
    if (e.mistake == mistake) return e;
  }
  throw std::logic_error("a mistake without a catalogue entry");
}

std::optional<Mistake> parse_mistake(std::string_view name) {
  for (const MistakeEntry& e : kCatalogue) {
    if (e.name == name) return e.mistake;
  }
  return std::nullopt;
}

unsigned choices_changed(Mistake mistake) {
  auto bit = [](ModelChoice c) { return 1u << static_cast<unsigned>(c); };
  using C = ModelChoice;
  switch (mistake) {
    case Mistake::zero_one_formula_on_gl:
      return bit(C::formula_gl) | bit(C::factor_gl) | bit(C::form_gl);
    case Mistake::gl_formula_on_zero_one:
      return bit(C::formula_zero_one) | bit(C::factor_zero_one) | bit(C::form_zero_one);
    case Mistake::camera_space_signs:
    case Mistake::fixed_corner_signs: return bit(C::sign_x) | bit(C::sign_y);
    case Mistake::ignores_m11_sign: return bit(C::sign_x);
    case Mistake::ignores_m22_sign: return bit(C::sign_y);
    case Mistake::far_face_fixed:
    case Mistake::wrong_face: return bit(C::face);
    case Mistake::left_handed_qw: return bit(C::q_w);
    case Mistake::drops_off_axis:
    case Mistake::abs_off_axis:
    case Mistake::negated_off_axis: return bit(C::off_axis);
    case Mistake::drops_shift:
    case Mistake::negated_shift: return bit(C::shift);
    case Mistake::divides_by_m43: return bit(C::corner_solve);
    case Mistake::perspective_rows: return bit(C::corner_solve) | bit(C::q_z);
    case Mistake::assumes_m43_minus_one: return bit(C::q_z);
    case Mistake::perspective_m4: return bit(C::form_m4);
    // A route decides where the formula runs; with the assumed M_4 or the note's flip it would
    // be another program than the model's (both are written for one convention).
    case Mistake::through_gl:
    case Mistake::through_zero_one: return bit(C::route) | bit(C::form_m4) | bit(C::route_reversed);
    case Mistake::perspective_listing:
      // The listing reads no M14, M24 (its Q is the perspective shape's, its face fixed): it
      // decides the shift too, and a shift mistake with it is the same program.
      return bit(C::corner_solve) | bit(C::q_z) | bit(C::face) | bit(C::form_m4) | bit(C::shift);
    case Mistake::skips_head_on: return bit(C::head_on);
    case Mistake::no_camera_guard: return bit(C::camera_guard);
    case Mistake::no_corner_guard: return bit(C::corner_guard);
    case Mistake::sign_by_division: return bit(C::sign_function);
    case Mistake::note_flip_as_printed: return bit(C::route_reversed);
    case Mistake::zero_one_factor_on_gl: return bit(C::factor_gl);
    case Mistake::gl_factor_on_zero_one: return bit(C::factor_zero_one);
    case Mistake::zero_one_form_on_gl: return bit(C::form_gl);
    case Mistake::gl_form_on_zero_one: return bit(C::form_zero_one);
  }
  return 0;
}

namespace variant {

bool Knobs::operator==(const Knobs& o) const {
  return camera_guard == o.camera_guard && corner_guard == o.corner_guard &&
         skips_head_on == o.skips_head_on && sign_by_division == o.sign_by_division && x == o.x &&
         y == o.y && face_fixed == o.face_fixed && face_opposite == o.face_opposite &&
         off_axis == o.off_axis && shift == o.shift && closed_form == o.closed_form &&
         assumes_m43_minus_one == o.assumes_m43_minus_one && left_handed_qw == o.left_handed_qw &&
         zero_one_on_gl == o.zero_one_on_gl && gl_on_zero_one == o.gl_on_zero_one &&
         note_flip == o.note_flip && zero_one_factor_on_gl == o.zero_one_factor_on_gl &&
         gl_factor_on_zero_one == o.gl_factor_on_zero_one &&
         zero_one_form_on_gl == o.zero_one_form_on_gl &&
         gl_form_on_zero_one == o.gl_form_on_zero_one && m4_assumed == o.m4_assumed && via == o.via;
}

Knobs knobs_of(Mistake mistake) {
  Knobs k;
  switch (mistake) {
    case Mistake::zero_one_formula_on_gl: k.zero_one_on_gl = true; break;
    case Mistake::gl_formula_on_zero_one: k.gl_on_zero_one = true; break;
    case Mistake::camera_space_signs: k.x = k.y = SignFrom::camera; break;
    case Mistake::ignores_m11_sign: k.x = SignFrom::camera_on_perspective_shape; break;
    case Mistake::ignores_m22_sign: k.y = SignFrom::camera_on_perspective_shape; break;
    case Mistake::far_face_fixed: k.face_fixed = true; break;
    case Mistake::wrong_face: k.face_opposite = true; break;
    case Mistake::left_handed_qw:
      k.closed_form = ClosedForm::perspective_shape;
      k.left_handed_qw = true;
      break;
    case Mistake::assumes_m43_minus_one:
      k.closed_form = ClosedForm::perspective_shape;
      k.assumes_m43_minus_one = true;
      break;
    case Mistake::drops_off_axis: k.off_axis = Entries::dropped; break;
    case Mistake::abs_off_axis: k.off_axis = Entries::magnitude; break;
    case Mistake::negated_off_axis: k.off_axis = Entries::negated; break;
    case Mistake::drops_shift: k.shift = Entries::dropped; break;
    case Mistake::negated_shift: k.shift = Entries::negated; break;
    case Mistake::fixed_corner_signs: k.x = k.y = SignFrom::fixed; break;
    case Mistake::zero_one_factor_on_gl: k.zero_one_factor_on_gl = true; break;
    case Mistake::gl_factor_on_zero_one: k.gl_factor_on_zero_one = true; break;
    case Mistake::zero_one_form_on_gl: k.zero_one_form_on_gl = true; break;
    case Mistake::gl_form_on_zero_one: k.gl_form_on_zero_one = true; break;
    case Mistake::divides_by_m43: k.closed_form = ClosedForm::always; break;
    case Mistake::perspective_rows:
      k.closed_form = ClosedForm::always;
      k.assumes_m43_minus_one = true;
      break;
    case Mistake::perspective_m4: k.m4_assumed = true; break;
    case Mistake::through_gl: k.via = Convention::gl; break;
    case Mistake::through_zero_one: k.via = Convention::zero_one; break;
    case Mistake::perspective_listing:
      k.closed_form = ClosedForm::always;
      k.assumes_m43_minus_one = true;
      k.face_fixed = true;
      k.m4_assumed = true;
      break;
    case Mistake::skips_head_on: k.skips_head_on = true; break;
    case Mistake::no_camera_guard: k.camera_guard = false; break;
    case Mistake::no_corner_guard: k.corner_guard = false; break;
    case Mistake::sign_by_division: k.sign_by_division = true; break;
    case Mistake::note_flip_as_printed: k.note_flip = true; break;
  }
  return k;
}

Knobs knobs_of(const std::vector<Mistake>& mistakes) {
  // Mistakes that change no choice in common set disjoint knobs, except that two may both take
  // the closed form (on the perspective shape, or everywhere: the wider wins).
  Knobs k;
  const Knobs none;
  for (Mistake m : mistakes) {
    const Knobs one = knobs_of(m);
    k.camera_guard = k.camera_guard && one.camera_guard;
    k.corner_guard = k.corner_guard && one.corner_guard;
    k.skips_head_on = k.skips_head_on || one.skips_head_on;
    k.sign_by_division = k.sign_by_division || one.sign_by_division;
    // camera beats camera_on_perspective_shape beats clip (fixed is made alone)
    if (one.x != none.x && k.x != SignFrom::camera) k.x = one.x;
    if (one.y != none.y && k.y != SignFrom::camera) k.y = one.y;
    k.face_fixed = k.face_fixed || one.face_fixed;
    k.face_opposite = k.face_opposite || one.face_opposite;
    if (one.off_axis != none.off_axis) k.off_axis = one.off_axis;
    if (one.shift != none.shift) k.shift = one.shift;
    k.closed_form = std::max(k.closed_form, one.closed_form);
    k.assumes_m43_minus_one = k.assumes_m43_minus_one || one.assumes_m43_minus_one;
    k.left_handed_qw = k.left_handed_qw || one.left_handed_qw;
    k.zero_one_on_gl = k.zero_one_on_gl || one.zero_one_on_gl;
    k.gl_on_zero_one = k.gl_on_zero_one || one.gl_on_zero_one;
    k.note_flip = k.note_flip || one.note_flip;
    k.zero_one_factor_on_gl = k.zero_one_factor_on_gl || one.zero_one_factor_on_gl;
    k.gl_factor_on_zero_one = k.gl_factor_on_zero_one || one.gl_factor_on_zero_one;
    k.zero_one_form_on_gl = k.zero_one_form_on_gl || one.zero_one_form_on_gl;
    k.gl_form_on_zero_one = k.gl_form_on_zero_one || one.gl_form_on_zero_one;
    k.m4_assumed = k.m4_assumed || one.m4_assumed;
    if (one.via) k.via = one.via;
  }
  return k;
}

}  // namespace variant

template <class T>
Implementation<T> mistaken_implementation(const std::vector<Mistake>& mistakes) {
  Implementation<T> impl;
  impl.name = "mistake_";
  for (std::size_t i = 0; i < mistakes.size(); ++i)
    impl.name += (i ? "+" : "") + std::string(mistake_entry(mistakes[i]).name);
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  const variant::Knobs knobs = variant::knobs_of(mistakes);
  impl.run = [knobs](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> right = apply<T>(m, c, convention, Method::general);
    // Input checks no mistake here changes: non-finite, out of the core's range, singular.
    if (right.status == Status::invalid_input || right.status == Status::singular_projection ||
        right.status == Status::out_of_range)
      return Answer<T>{right.status, right.projection};
    const auto mine = variant::evaluate<T>(m, c, convention, knobs);
    const auto careful = variant::evaluate<T>(m, c, convention, variant::Knobs{});
    if (mine.choices == careful.choices || mine.solve_failed)
      return Answer<T>{right.status, right.projection};
    if (mine.status != Status::ok) return Answer<T>{mine.status, m};
    return Answer<T>{Status::ok, variant::answer_matrix(m, mine)};
  };
  return impl;
}

template Implementation<float> mistaken_implementation<float>(const std::vector<Mistake>&);
template Implementation<double> mistaken_implementation<double>(const std::vector<Mistake>&);
template Implementation<long double> mistaken_implementation<long double>(
    const std::vector<Mistake>&);

}  // namespace oblique::mistakes
