// The catalogue of known mistakes: the wrong variants of the oblique modification that engines
// and the printed formulas ship, each with its name, what it does, the fix, and where it shows.
// diagnosis.h names the entry that explains a finding; mistaken_implementation() runs an entry
// (or two together) as an implementation, for the suite's own tests and fuzzing.
// docs/mistakes.md lists the catalogue with a worked example each.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "oblique/oracle/implementation.h"

namespace oblique::mistakes {

using oracle::Implementation;

enum class Mistake {
  zero_one_formula_on_gl,  ///< a = 1 / (C . Q), M'_3 = a C on a [-1, 1] matrix
  gl_formula_on_zero_one,  ///< a = 2 / (C . Q), M'_3 = a C - M_4 on a [0, 1] matrix
  camera_space_signs,      ///< the corner's x, y signs from C instead of C' = M^-T C
  ignores_m11_sign,        ///< the perspective fast path's x sign from C (mirror cameras)
  ignores_m22_sign,        ///< the perspective fast path's y sign from C (y-flipped cameras)
  far_face_fixed,          ///< Q'_z = 1 whatever the convention and sgn(C'_z) (Eq. 7)
  wrong_face,              ///< Q'_z on the face opposite sgn(C'_z): the near face
  left_handed_qw,          ///< Q_w = (z - M33) / M34 on a right-handed matrix
  drops_off_axis,          ///< M13, M23 left out of C' and Q
  abs_off_axis,            ///< |M13|, |M23| in C' and Q: a frustum leaning left or down
  drops_shift,             ///< M14, M24 (stereo, lens shift) left out of C' and Q
  divides_by_m43,          ///< the perspective closed form on every matrix (Q_z = 1 / M43)
  perspective_rows,        ///< Listing 5.1's Q (M43 = -1 assumed) on every matrix
  skips_head_on,           ///< M returned unchanged for a plane with normal (0, 0, -1)
  no_camera_guard,         ///< no refusal when C_w >= 0
  no_corner_guard,         ///< no refusal when C . Q <= 0
  sign_by_division,        ///< sgn(x) = x / |x|, NaN at 0
  note_flip_as_printed,    ///< reversed Z through the [0, 1] note's flip, fourth row (0, 0, 1, 1)
  zero_one_factor_on_gl,   ///< a = 1 / (C . Q) kept with the gl form M'_3 = a C - M_4
  gl_factor_on_zero_one,   ///< a = 2 / (C . Q) on a [0, 1] or reversed-Z matrix, its form kept
  zero_one_form_on_gl,     ///< M'_3 = a C (no - M_4) with the gl factor a = 2 / (C . Q)
  gl_form_on_zero_one,     ///< M'_3 = a C - M_4 with the [0, 1] factor a = 1 / (C . Q)
  fixed_corner_signs,      ///< Q'_x = Q'_y = 1 whatever the signs of C'
  negated_off_axis,        ///< -M13, -M23 in C' and Q (the lean's sign slipped)
  negated_shift,           ///< -M14, -M24 in C' and Q
  assumes_m43_minus_one,   ///< the perspective closed form with Q_z = -1 (Listing 5.1) on M43 = 1
  perspective_m4,          ///< row 3 = a C + (0, 0, 1, 0) as printed: M_4 = (0, 0, -1, 0) assumed
  perspective_listing,     ///< Listing 5.1 whole (its Q and its row 3) on every matrix
  // Routes: not mistakes alone (a right formula on a route is right), a choice a cause can make
  // with the mistakes made on it (all_routes; routes_of()).
  through_gl,        ///< the matrix taken to OpenGL's range, modified there, brought back
  through_zero_one,  ///< ... to [0, 1]'s (reversed Z's gives the same answers, every mistake
                     ///< of the model made on it: the two formulas are one up to M_4 - row 3)
};

inline constexpr Mistake all_mistakes[] = {
    Mistake::zero_one_formula_on_gl,
    Mistake::gl_formula_on_zero_one,
    Mistake::camera_space_signs,
    Mistake::ignores_m11_sign,
    Mistake::ignores_m22_sign,
    Mistake::far_face_fixed,
    Mistake::wrong_face,
    Mistake::left_handed_qw,
    Mistake::drops_off_axis,
    Mistake::abs_off_axis,
    Mistake::drops_shift,
    Mistake::divides_by_m43,
    Mistake::perspective_rows,
    Mistake::skips_head_on,
    Mistake::no_camera_guard,
    Mistake::no_corner_guard,
    Mistake::sign_by_division,
    Mistake::note_flip_as_printed,
    Mistake::zero_one_factor_on_gl,
    Mistake::gl_factor_on_zero_one,
    Mistake::zero_one_form_on_gl,
    Mistake::gl_form_on_zero_one,
    Mistake::fixed_corner_signs,
    Mistake::negated_off_axis,
    Mistake::negated_shift,
    Mistake::assumes_m43_minus_one,
    Mistake::perspective_m4,
    Mistake::perspective_listing,
};

/// The routes through another convention and back: each made with mistakes of the formula on it
/// (the formula, factor and form choices; a route with none of them is the same program as
/// without it), never alone.
inline constexpr Mistake all_routes[] = {Mistake::through_gl, Mistake::through_zero_one};

/// The modification's choices (docs/mistakes.md, "The model of the computation"): the correct
/// method takes one alternative of each, a mistake another of one or a few of them.
enum class ModelChoice {
  camera_guard,      ///< refuse when C_w >= 0
  corner_guard,      ///< refuse when C . Q <= 0
  head_on,           ///< modify for a head-on plane too
  sign_function,     ///< how sgn is computed
  sign_x,            ///< where Q'_x's sign is read
  sign_y,            ///< where Q'_y's sign is read
  face,              ///< which depth face Q'_z takes
  corner_solve,      ///< Q = M^-1 Q' solved, or the perspective closed form
  q_z,               ///< the closed form's Q_z: 1 / M43, or -1 assumed
  q_w,               ///< the closed form's Q_w: right- or left-handed
  off_axis,          ///< what C' and Q take for M13, M23
  shift,             ///< what C' and Q take for M14, M24
  formula_gl,        ///< whose formula on a gl matrix (range, factor, form together)
  formula_zero_one,  ///< whose formula on a [0, 1] matrix
  factor_gl,         ///< the factor's numerator on a gl matrix
  factor_zero_one,   ///< the factor's numerator on a [0, 1] or reversed-Z matrix
  form_gl,           ///< row 3's form on a gl matrix
  form_zero_one,     ///< row 3's form on a [0, 1] matrix
  route_reversed,    ///< the route reversed Z is computed by
  form_m4,           ///< the M_4 row 3's form takes: M's, or the perspective shape's
  route,             ///< the convention the formula runs in: the matrix's own, or another's
};
inline constexpr int kModelChoices = 21;

/// The choices `mistake` changes, as bits (1 << ModelChoice). Mistakes combine (a program with
/// several) where they change no choice in common.
unsigned choices_changed(Mistake mistake);

/// One entry of the catalogue.
struct MistakeEntry {
  Mistake mistake;
  std::string_view name;         ///< e.g. "zero_one_formula_on_gl"
  std::string_view title;        ///< a short phrase: "the [0, 1] formula on a [-1, 1] matrix"
  std::string_view explanation;  ///< what the code does and why it is wrong (a paragraph)
  std::string_view fix;          ///< the fix, in words and formula
  std::string_view shows;        ///< the inputs where it gives a wrong answer
  /// What the code does, said to its author: "you take Q'_y's sign from C_y where M has the
  /// perspective shape, ignoring M22's sign" (a cause of several mistakes is said this way).
  std::string_view you;
};

const MistakeEntry& mistake_entry(Mistake mistake);
/// The mistake called `name` (MistakeEntry::name), if any.
std::optional<Mistake> parse_mistake(std::string_view name);

/// The modification with `mistakes` made (one, or several together), computing in T as an engine
/// does: the core's general method where the mistakes change none of its choices, the mistaken
/// formula elsewhere. Named "mistake_" + the names joined by "+". Compiled in oblique::properties.
template <class T>
Implementation<T> mistaken_implementation(const std::vector<Mistake>& mistakes);

extern template Implementation<float> mistaken_implementation<float>(const std::vector<Mistake>&);
extern template Implementation<double> mistaken_implementation<double>(const std::vector<Mistake>&);
extern template Implementation<long double> mistaken_implementation<long double>(
    const std::vector<Mistake>&);

}  // namespace oblique::mistakes
