// The checker's verdict on one answer, as users see it: a Finding per check, the Judgement that
// lists them, and which inputs an implementation is not judged on (not_judged()). Light: no GMP,
// no checker (oblique/oracle/checker.h judges; judge.h is the checker's own judge()).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "oblique/oracle/vocabulary.h"
#include "oblique/protocol/numbers.h"
#include "oblique/status.h"

namespace oblique::oracle {

/// What a finding is about: the status, a finite answer, a property (check_of()), row 3's
/// accuracy, an ulps promise; and what the tools that run a program see of it (crash, timeout,
/// protocol: never from judge()).
enum class Check : std::uint8_t {
  status,                    ///< the answered status is one the contract allows for the input
  finite_result,             ///< an ok answer has finite entries
  near_is_clip_plane,        ///< the properties, in Property's order
  side_rows_unchanged,       ///<
  far_plane_through_corner,  ///<
  no_clipping,               ///<
  infinite_edge_parallel,    ///<
  extracted_planes_match,    ///<
  row3_accuracy,             ///< row 3 within Problem::row3_bounds() of the exact row
  accurate_ulps,             ///< every entry within Checks::max_ulps of the rounded exact answer
  methods_agree,             ///< the property suite's cross-check of the core's two methods
  crash,                     ///< the program ended before answering
  timeout,                   ///< the program did not answer in time
  protocol,                  ///< the program's answer is not a protocol answer line (the last)
};

constexpr Check check_of(Property p) noexcept {
  return static_cast<Check>(static_cast<int>(Check::near_is_clip_plane) + static_cast<int>(p));
}
constexpr std::optional<Property> property_of(Check c) noexcept {
  if (c < Check::near_is_clip_plane || c > Check::extracted_planes_match) return std::nullopt;
  return static_cast<Property>(static_cast<int>(c) - static_cast<int>(Check::near_is_clip_plane));
}

/// The names of the checks that are not properties (a property's check is named by the property:
/// property_names).
inline constexpr EnumName<Check> tool_check_names[] = {
    {Check::status, "status"},
    {Check::finite_result, "finite_result"},
    {Check::row3_accuracy, "row3_accuracy"},
    {Check::accurate_ulps, "accurate_ulps"},
    {Check::methods_agree, "closed_form_and_general_agree"},
    {Check::crash, "crash"},
    {Check::timeout, "timeout"},
    {Check::protocol, "protocol"}};

/// A check's name: a property's own (property_name()), "status", "row3_accuracy", ...
std::string_view check_name(Check c) noexcept;
/// The check of that name, if any.
std::optional<Check> parse_check(std::string_view name) noexcept;

/// Which outcome of its check a finding shows, and so what its numbers mean.
enum class Shows : std::uint8_t {
  /// |residual| against bound (far' . Q, far' . p at a vertex, ulps, row 3's worst entry).
  residual,
  /// A check the filtered checker settled in intervals: it holds, ratio approximate, no residual.
  certified,
  /// The answered status (Finding::answered) against the statuses the input allows.
  statuses,
  /// M' has a NaN or an infinite entry.
  non_finite_answer,
  /// near_is_clip_plane: lambda and the worst residual / bound (ratio); `wrong_side` when no
  /// lambda > 0 fits because near' is C negated, `no_fit` when none fits otherwise.
  lambda_fit,
  wrong_side,
  no_fit,
  /// An entry of M' (row, column) is `value`, not `reference` (M's entry, the exact entry).
  entry,
  /// no_clipping: far' . p (residual) below -bound at a corner, or at an edge's crossing of C.
  below_at_corner,
  below_at_edge_crossing,
  /// no_clipping holds: no vertex is below its bound.
  no_vertex_below,
  /// extracted_planes_match: side plane `row` differs by `residual`; the near plane has a
  /// non-finite component; n . C = `residual` (must be > 0).
  side_plane_differs,
  near_plane_not_finite,
  near_plane_side,
  /// C lies within rounding of the far corner Q: no bound exists, nothing is judged.
  no_bound,
  /// infinite_edge_parallel: Q_w (reference) and far' . Q (residual) against bound.
  edge_direction,
  /// What a program did (crash, timeout, protocol), in Finding::message.
  program,
};

/// One check on one answer: which check, whether it holds, and what it measured, as numbers
/// (the words come from relation_text(), residual_text() and bound_text(), made only when a
/// report or a console line is written).
struct Finding {
  Check check = Check::status;
  bool holds = false;
  /// |residual| / bound, where the check measures one (it holds at <= 1); none for a check that
  /// is a yes or a no (a status, equal entries, a sign). Infinite where the bound is 0 and the
  /// residual is not.
  std::optional<double> ratio;
  Shows shows = Shows::residual;
  double residual = 0;      ///< the measured side (its meaning: Shows)
  double bound = 0;         ///< the bound it is held to
  double lambda = 0;        ///< near_is_clip_plane: the scale of C near' is compared with
  int row = 0, column = 0;  ///< 1-based entry (or side plane: row) the numbers are about; 0: none
  double value = 0;         ///< Shows::entry: the answer's entry
  double reference = 0;     ///< Shows::entry: what it must be; Shows::edge_direction: Q_w
  Status answered = Status::ok;  ///< Shows::statuses: the status answered
  Status exact = Status::ok;     ///< Shows::statuses: the input's exact status
  std::vector<Status> allowed;   ///< Shows::statuses: the statuses the input allows
  std::string message;           ///< Shows::program: what the program did, in the tool's words
};

/// What the check compares, in words ("|far' . Q| <= bound").
std::string relation_text(const Finding& f);
/// The measured side in words, with its numbers ("far' . p = -3.5 at a corner").
std::string residual_text(const Finding& f);
/// The side it is held to ("2.2e-16", "> 0", "camera_not_behind_plane or invalid_input").
std::string bound_text(const Finding& f);
/// Both sides as console lines after `indent`: "expected:"/"got:" for a status, else
/// "residual:"/"bound:".
std::string sides_text(const Finding& f, const std::string& indent);
/// The finding's numbers by name, for the JSON forms (reports, check's output): only those its
/// Shows gives a meaning.
std::vector<std::pair<std::string, double>> finding_numbers(const Finding& f);

/// The checks that applied, in order.
struct [[nodiscard]] Judgement {
  std::vector<Finding> checks;

  /// The first check that fails, or nullptr.
  const Finding* violation() const {
    for (const Finding& f : checks) {
      if (!f.holds) return &f;
    }
    return nullptr;
  }
  bool holds() const { return violation() == nullptr; }
};

/// "a or b or c".
inline std::string status_list(const std::vector<Status>& statuses) {
  std::string out;
  for (Status s : statuses) out += (out.empty() ? "" : " or ") + std::string(status_code(s));
  return out;
}

/// Whether an implementation under `contract` has every refusal (nothing is left out for it).
inline bool has_every_refusal(StatusContract contract, const std::vector<Status>& refusals) {
  return contract == StatusContract::any_refusal ||
         (contract == StatusContract::exact && refusals.empty());
}

/// Why an implementation is not judged on an input, or "" when it is: the one rule every tool
/// (the property suite, `oblique verify`, the fuzz driver) leaves inputs out by. An answer is
/// judged only where some reply the implementation can give is right:
///  - an input without an exact answer, when its status is not one the implementation has (it
///    has none under answers_only; under exact, `refusals` lists the ones it has, empty: all);
///  - an input *undecidable at the implementation's precision*: it has an exact answer, but it
///    lies within rounding (in T) of a status boundary (C . Q of zero, a singular M, the end of
///    T's range), so acceptable_statuses() holds a refusal besides ok. A computed C . Q there
///    may have either sign or be zero, the answer may be anything, and only a refusal is right;
///    left out when the implementation has none of the refusals allowed (answers_only: none).
/// any_refusal has every refusal: nothing is left out. What the input is decides, never how it
/// was generated.
template <class T>
std::string not_judged(Status exact, const std::vector<Status>& acceptable, StatusContract contract,
                       const std::vector<Status>& refusals = {}) {
  if (has_every_refusal(contract, refusals)) return "";
  auto has = [&](Status s) {
    return contract == StatusContract::exact &&
           std::find(refusals.begin(), refusals.end(), s) != refusals.end();
  };
  if (exact != Status::ok) {
    if (has(exact)) return "";
    return contract == StatusContract::answers_only
               ? "inputs without an answer"
               : "inputs needing status " + std::string(status_code(exact));
  }
  // The first allowed refusal names the boundary; the input is judged when any is the
  // implementation's.
  std::optional<Status> boundary;
  for (Status s : acceptable) {
    if (s == Status::ok) continue;
    if (has(s)) return "";
    if (!boundary) boundary = s;
  }
  if (!boundary) return "";
  const std::string scalar(protocol::scalar_name<T>());
  const std::string where =
      *boundary == Status::plane_misses_view_volume ? "C . Q within rounding of 0"
      : *boundary == Status::singular_projection    ? "M within rounding of singular"
                                                    : "rounding allows out_of_range";
  return "inputs undecidable in " + scalar + " (" + where + ")";
}

}  // namespace oblique::oracle
