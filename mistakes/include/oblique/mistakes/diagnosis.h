// Diagnosis of a finding: which known mistakes (mistakes.h) explain the answers an implementation
// gave. Every entry of the catalogue, then every two and every three that change no choice of
// the model in common, is evaluated in exact arithmetic on each case seen, and the smallest that
// fit are named; a set explains the finding when, on every case where its answer is decided (not
// within rounding of a boundary), the implementation's answer is that answer within the rounding
// of the implementation's precision (the bounds of tolerance.h) or the same refusal, and on at
// least one wrong answer it is an answer the correct method does not give. Where none fits, a
// numerical route (numerical_routes.h) that reproduces the answers is named instead. With a probe
// (the implementation asked again) the cases where the candidates part are asked too, so that
// one cause is left where the finding alone fits several. No cause is a guess: when none fits,
// the diagnosis says so. Compiled in oblique::properties (float, double, long double).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/depth_convention.h"
#include "oblique/mistakes/answer_geometry.h"
#include "oblique/mistakes/mistakes.h"
#include "oblique/mistakes/numerical_routes.h"
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique::mistakes {

/// One case and what the implementation answered, with the checker's verdict on it.
template <class T>
struct Observation {
  Matrix4<T> matrix = Matrix4<T>::Identity();
  Vector4<T> plane = Vector4<T>::Zero();
  Convention convention = Convention::gl;
  Status status = Status::ok;
  Matrix4<T> projection = Matrix4<T>::Identity();  ///< the answer, when status is ok
  bool wrong = false;                              ///< the checker found a violation in this answer
  /// The case's family, where the caller knows it (the panel's cases always have theirs).
  std::optional<cases::Family> family;
};

/// Asks the implementation about one more case (of `family`): its observation, or none when the
/// case is not one the implementation promises anything for (its contract leaves it out: a
/// family or a convention it does not serve).
template <class T>
using Probe = std::function<std::optional<Observation<T>>(const Matrix4<T>&, const Vector4<T>&,
                                                          Convention, cases::Family family)>;

/// A choice of the modification, where a cause decided otherwise than the correct method.
enum class Choice {
  camera_guard,  ///< refuses when C_w >= 0 (1) or not (0)
  head_on,       ///< M returned unchanged (1)
  solve,         ///< entries of M left out of the solves (1)
  closed_form,   ///< Q by the perspective closed form (1)
  nan_sign,      ///< a sign computed as NaN (1)
  corner_guard,  ///< refuses when C . Q <= 0 (1) or not (0)
  sign_x,        ///< the far corner's x sign
  sign_y,        ///< the far corner's y sign
  face,          ///< the far corner's depth Q'_z
  formula,       ///< whose formula: 0 gl, 1 zero_one, 2 reversed_z
  row4,          ///< row 4 rewritten (1)
  factor,        ///< the factor's numerator k in a = k / (C . Q)
  form,          ///< row 3's multiple of M_4
  q_z,           ///< the closed form's Q_z = -1 assumed (1)
  q_w,           ///< the closed form's left-handed Q_w (1)
  m4,            ///< row 3's M_4 taken as (0, 0, -1, 0) (1)
  route,         ///< the formula run in another convention, the row brought back (1)
};

struct ChoiceDifference {
  Choice choice = Choice::sign_x;
  double mistaken = 0, right = 0;
};

/// One family's answers, diagnosed alone (Diagnosis::families).
struct FamilyDiagnosis {
  cases::Family family = cases::Family::perspective;
  int seen = 0, wrong = 0;  ///< cases of the family judged, answers of it the checker rejected
  /// The causes that explain every answer of this family (none where it has no wrong answer).
  std::vector<std::vector<Mistake>> causes;
  /// Where none explains them: what the family's first wrong answer does (answer_geometry.h).
  std::optional<AnswerGeometry> geometry;
};

/// A numerical cause (numerical_routes.h): the correct formula along `route`, rounded in T,
/// reproduces every answer seen. Measured on the first wrong answer it reproduces.
struct NumericalCause {
  NumericalRoute route = NumericalRoute::reversed_z_through_zero_one;
  bool non_finite = false;    ///< the answer there is not finite (the step divided by 0)
  double relative_error = 0;  ///< max |answered - correct| / max |a C| over row 3
  int bits_lost = 0;          ///< of T's `precision` significant bits
  int precision = 0;
};

struct Diagnosis {
  bool ran = false;  ///< false where nothing was diagnosed (no wrong answer with a case)
  /// The smallest causes that explain every answer seen: each one mistake, or two or three made
  /// together. Empty: no known mistake, nor up to three together, reproduces the answers.
  std::vector<std::vector<Mistake>> causes;
  int seen = 0, wrong = 0;  ///< cases judged (including probes), answers the checker rejected
  int probed = 0;           ///< of them, cases asked by the diagnosis
  /// For the first cause: answers it decides, and of them those where it is not the correct
  /// answer (each a wrong answer of the implementation) and those where it is (each right).
  int decided = 0, wrong_where_it_differs = 0, right_where_it_agrees = 0;
  /// The evidence, on the first wrong answer the first cause reproduces: the statuses and the
  /// row (0-based) it changes, as answered, as the cause gives it and as it should be.
  Status answered = Status::ok, mistaken = Status::ok, right = Status::ok;
  int row = 2;
  std::optional<std::array<double, 4>> answered_row, mistaken_row, right_row;
  std::vector<ChoiceDifference> differences;  ///< what the cause decided otherwise there
  /// Where no known mistake reproduces the answers but the correct modification of M^T,
  /// transposed back, does (each refusal and each answer to half of T's digits, at least one
  /// wrong one among them): the function reads its matrix in the other layout (a row-vector
  /// engine declared as column vectors, or the 16 numbers in the other order).
  bool transposed_layout = false;
  /// Where no known mistake reproduces the answers but the correct formula along a numerical
  /// route does (computed in T): that route.
  std::optional<NumericalCause> numerical;
  /// Where no known mistake reproduces the answers: what the first wrong answer (status ok, finite)
  /// does, in geometry (answer_geometry.h).
  std::optional<AnswerGeometry> geometry;
  /// Where no cause explains every answer but the answers part by family (right on some
  /// families, wrong on others): each family's own diagnosis, in the order of cases::Family.
  std::vector<FamilyDiagnosis> families;
};

/// The most mistakes a cause is made of: the diagnosis tries every cause of up to this many
/// mistakes that change no choice in common (choices_changed()), and names the smallest that fit.
inline constexpr int kMostMistakes = 3;
/// The most choices: those mistakes, and a route through another convention they are made on
/// (all_routes: a cause with a mistake of the formula, run on the route, is one size up).
inline constexpr int kMostChoices = kMostMistakes + 1;

/// Every cause of `size` choices the diagnosis tries (1 to kMostChoices): mistakes that change no
/// choice in common, with a route where one of them changes the formula, each a program no
/// smaller cause is (their knobs differ).
std::vector<std::vector<Mistake>> causes_tried(int size);

/// How many cases the diagnosis asks a probe per convention (its fixed panel).
inline constexpr int kPanelCasesPerConvention = 225;

/// The diagnosis of the answers `seen` (at least one wrong), with more cases asked through
/// `probe` when given (in every convention the probe does not decline). `answers_only`: the
/// implementation has no refusals (a void function, an answers-only contract): where a cause
/// refuses and it answers, that is no evidence either way, so no cause needs the guards' mistakes
/// to explain what it cannot help.
template <class T>
Diagnosis diagnose(const std::vector<Observation<T>>& seen, const Probe<T>& probe = {},
                   bool answers_only = false);

extern template Diagnosis diagnose<float>(const std::vector<Observation<float>>&,
                                          const Probe<float>&, bool);
extern template Diagnosis diagnose<double>(const std::vector<Observation<double>>&,
                                           const Probe<double>&, bool);
extern template Diagnosis diagnose<long double>(const std::vector<Observation<long double>>&,
                                                const Probe<long double>&, bool);

/// "camera_space_signs" or "no_camera_guard + sign_by_division".
std::string cause_name(const std::vector<Mistake>& cause);
/// The causes joined by " or ", "no known mistake", or "" where nothing was diagnosed.
std::string cause_names(const Diagnosis& diagnosis);
/// One line for a console: "likely cause: NAME (title); fix: ..." or "likely cause: no known
/// mistake reproduces these answers".
std::string likely_cause_line(const Diagnosis& diagnosis);
/// The report's "Likely cause" section (Markdown, from its heading).
std::string likely_cause_markdown(const Diagnosis& diagnosis);
/// What the cause decided otherwise, in words: "the far corner's x sign: 1 (right: -1)".
std::string choice_text(const ChoiceDifference& difference);

}  // namespace oblique::mistakes
