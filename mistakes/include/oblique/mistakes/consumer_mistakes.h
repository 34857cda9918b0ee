// The catalogue of known mistakes in the code around the oblique matrix (consumers: depth
// reconstruction, culling planes, the pass camera and its plane, the view volume's corners), each
// as the wrong function it is, and the diagnosis of a consumer finding: which of them gives the
// answer that was judged wrong. Every way in (verify --consumers, the in-process test, check
// --impl) asks and judges through oracle::consumer_round() or the asks it plans, and passes
// explain_consumer() there. Compiled in oblique::mistakes. docs/consumers.md lists the entries.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/oracle/consumers.h"

namespace oblique::mistakes {

enum class ConsumerMistake {
  reconstructs_with_original,     ///< view_position: the unmodified matrix's inverse on M' depth
  ndc_depth_of_other_convention,  ///< view_position: z = 2 d - 1 on [0, 1] depth, z = d on gl
  reads_reversed_as_forward,      ///< view_position: 1 - d on reversed Z before M'^-1
  reads_v_the_other_way,          ///< view_position: NDC y negated (v read the other way up)
  ignores_oblique_row,            ///< view_position: z from M'33, M'34, M'43 alone, x / M'11
  transposed_matrix,              ///< view_position: (M'^-1)^T b (the layout read as the other)
  linearises_with_near_far,       ///< linear_depth: n f / (f - d (f - n)), n, f off M ("zparams")
  world_with_original,            ///< world_position: (M V)^-1, the unmodified matrix's
  world_through_view,             ///< world_position: V v instead of V^-1 v
  gl_planes_on_any_matrix,        ///< culling_planes: OpenGL's near and far rows on any matrix
  planes_of_transpose,            ///< culling_planes: the rows of M^T (the layout misread)
  plane_without_translation,      ///< camera_plane: the normal rotated, C_w kept from world space
  plane_flipped_for_mirrors,      ///< camera_plane: W^-T P negated again where W mirrors
  plane_through_view,             ///< camera_plane: W P instead of W^-T P
  mirror_by_reflected_look_at,    ///< mirror_view: a look-at of the reflected eye: no flip
  portal_without_turn,            ///< portal_view: without the half turn about up
  corners_of_oblique_matrix,      ///< corners: M'^-1's eight corners over w
};

inline constexpr ConsumerMistake all_consumer_mistakes[] = {
    ConsumerMistake::reconstructs_with_original,  ConsumerMistake::ndc_depth_of_other_convention,
    ConsumerMistake::reads_reversed_as_forward,   ConsumerMistake::reads_v_the_other_way,
    ConsumerMistake::ignores_oblique_row,         ConsumerMistake::transposed_matrix,
    ConsumerMistake::linearises_with_near_far,    ConsumerMistake::world_with_original,
    ConsumerMistake::world_through_view,          ConsumerMistake::gl_planes_on_any_matrix,
    ConsumerMistake::planes_of_transpose,         ConsumerMistake::plane_without_translation,
    ConsumerMistake::plane_flipped_for_mirrors,   ConsumerMistake::plane_through_view,
    ConsumerMistake::mirror_by_reflected_look_at, ConsumerMistake::portal_without_turn,
    ConsumerMistake::corners_of_oblique_matrix,
};

struct ConsumerMistakeEntry {
  ConsumerMistake mistake;
  protocol::ConsumerKind kind;   ///< the function it is a wrong version of
  std::string_view name;         ///< "reconstructs_with_original"
  std::string_view title;        ///< a short phrase
  std::string_view explanation;  ///< what the code does and why it is wrong
  std::string_view fix;
  /// What the answers show, first: "your answers are a reconstruction with ...".
  std::string_view effect;
};

const ConsumerMistakeEntry& consumer_mistake_entry(ConsumerMistake mistake);
std::optional<ConsumerMistake> parse_consumer_mistake(std::string_view name);

/// The wrong function of `mistake` as a Consumers that gives only that function (its kind's).
template <class T>
Consumers<T> mistaken_consumers(ConsumerMistake mistake);

/// Sets `finding.likely_cause` for a violated finding of the answer `answer` to `ask`: the
/// catalogue's entries of the ask's kind whose function, asked the same inputs, gives `answer`
/// (to half of T's digits; planes up to a positive scale, corners in any order), where the
/// correct function does not (names joined by " or "; empty when none, or when the answer is
/// that close to the correct one too). An oracle::Explain.
template <class T>
void explain_consumer(const oracle::ConsumerAsk<T>& ask, const std::vector<T>& answer,
                      oracle::ConsumerFinding& finding);

/// Appended to a likely cause named on a run's first failing case and carried to its shrunk one,
/// where the answer is too close to the correct one to name it (consumer_cause_line() and
/// consumer_cause_markdown() say so).
inline constexpr const char* kNamedBeforeShrinking = " (named on the first failing case)";

/// "likely cause: NAME (title); fix: ..." for a finding's likely_cause ("" for none).
std::string consumer_cause_line(const std::string& likely_cause);
/// The report's "Likely cause" section for it and what the answers show (a finding's
/// answers_show): Markdown, from its heading; "" where both are empty. Without a name it says no
/// known mistake gives the answer, after what the answer shows.
std::string consumer_cause_markdown(const std::string& likely_cause,
                                    const std::string& answers_show = "");

#define OBLIQUE_CONSUMER_MISTAKES_EXTERN(T)                                                      \
  extern template Consumers<T> mistaken_consumers<T>(ConsumerMistake);                           \
  extern template void explain_consumer<T>(const oracle::ConsumerAsk<T>&, const std::vector<T>&, \
                                           oracle::ConsumerFinding&);
OBLIQUE_CONSUMER_MISTAKES_EXTERN(float)
OBLIQUE_CONSUMER_MISTAKES_EXTERN(double)
OBLIQUE_CONSUMER_MISTAKES_EXTERN(long double)
#undef OBLIQUE_CONSUMER_MISTAKES_EXTERN

}  // namespace oblique::mistakes
