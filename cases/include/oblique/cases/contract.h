// What an implementation promises, said once for every way in: oblique::testing's property runs,
// the oblique::fuzzing driver and `oblique verify` (its --contract file, flags and reports).
//
//   oblique::Contract c;                                    // C++: lists empty = every value
//   c.families = {oblique::cases::Family::perspective};
//   c.statuses = oblique::cases::StatusContract::answers_only;
//
//   {"families": ["perspective"], "statuses": "answers_only"}   // the same, as JSON
//
// The JSON form has one reader (read_contract) and one writer (contract_json): the contract a
// verify report prints can be pasted into a test as
//   oblique::read_contract(R"({...})").value()
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/cases/checks.h"
#include "oblique/cases/property.h"
#include "oblique/depth_convention.h"
#include "oblique/expected.h"
#include "oblique/status.h"
#include "oblique/util/enum_names.h"

namespace oblique {

/// The clip planes an implementation is given.
enum class Planes {
  any,  ///< any scale (the generators' `scaled` place included)
  unit  ///< a unit normal, as engines build planes (the `scaled` place is left out)
};

struct Contract {
  /// The projections it is given (empty: every family). What each admits: case_kinds.h.
  std::vector<cases::Family> families;
  /// The depth conventions it is for (empty: the implementation's own, stated to adapt(); for a
  /// program under `oblique verify`: gl, the protocol's default).
  std::vector<Convention> conventions;
  /// The hard places of planes it is given (empty: every place).
  std::vector<cases::Place> places;
  Planes planes = Planes::any;
  /// How its statuses are judged (empty: from the implementation: adapt() knows a void, bool or
  /// Status function; a program under `oblique verify`: any_refusal).
  std::optional<cases::StatusContract> statuses;
  /// Under StatusContract::exact: the refusals it implements (empty: every one). Inputs needing
  /// another are not judged (oracle::not_judged()).
  std::vector<Status> refusals;
  /// The kinds of input without an answer it is given, where statuses are judged (empty: all).
  std::vector<cases::Defect> defects;
  /// The properties judged (empty: every one, extracted_planes_match included).
  std::vector<cases::Property> properties;
  /// Row 3 of an answer within the accuracy careful arithmetic achieves in its scalar type
  /// (Problem::row3_bounds()): a promise beyond the properties, which plain float arithmetic
  /// breaks on extreme inputs (a subnormal C_w). Empty: the implementation's (a function given
  /// to adapt() makes none; a program under `oblique verify` is held to it, as verify always has).
  std::optional<bool> row3_accuracy;
};

/// The contract of the oblique function as engines write it: the projections an engine builds
/// (the perspective shape, right-handed: every off-axis and jittered frustum, finite or
/// infinite, flipped in x, y or both, as a mirror pass or a Vulkan projection flips it), planes
/// with a unit normal, and answers only (an engine does not ask about inputs without an answer).
/// The conventions: the function's own. Give the function engine_perspective_only (adapter.h);
/// in JSON, {"preset": "engine"}; on verify's command line, --preset engine.
Contract engine_contract();

/// The contract a preset's name stands for (only "engine" now), or none.
std::optional<Contract> preset_contract(std::string_view name);
std::vector<std::string> preset_names();

/// The contract with each empty list filled (families, places, defects, properties: every one;
/// conventions, statuses, row3_accuracy: the implementation's own) and, for unit planes, the
/// `scaled` place dropped (a unit normal undoes the scaling) unless it is the only place.
Contract resolved(Contract contract, const std::vector<Convention>& own_conventions,
                  cases::StatusContract own_statuses, bool own_row3_accuracy);

/// The contract's JSON form: an object with any of the fields
///   "preset": a preset's name (preset_contract()), read first: the other fields change it;
///   "families", "conventions" (or "all"), "places", "defects", "properties": lists of names;
///   "planes": "any" or "unit";
///   "statuses": "exact", "any_refusal", "answers_only", or a list of refusal codes (exact, with
///   only those refusals);
///   "exclude": families, places and defects to leave out of the lists (filled first);
///   "row3_accuracy": true or false.
/// Unknown fields and names are refused, with the known ones and the closest ("did you mean").
Expected<Contract> read_contract(std::string_view json);
/// read_contract() of a file's text; errors name the file.
Expected<Contract> read_contract_file(const std::string& path);

/// The contract with one field of its JSON form set from names, as a command line gives them
/// (`--families perspective,infinite`): the field's list is replaced ("exclude" removes), with
/// the same names, checks and messages as read_contract().
Expected<Contract> with_field(Contract contract, const std::string& field,
                              const std::vector<std::string>& names);

/// Leaves the named families, places and defects out of the contract's lists (each filled with
/// every value first when empty). Refuses an unknown name and a list left empty.
Expected<Contract> exclude(Contract contract, const std::vector<std::string>& names);

/// The JSON form of `contract`, one line, every list as given (empty lists and unset statuses
/// left out, so read_contract() gives the same contract back).
std::string contract_json(const Contract& contract);

/// The names the property and refusal fields accept, for help texts and messages (the families,
/// conventions, places, defects and status contracts: names_in(family_names) and so on).
std::vector<std::string> property_names();
std::vector<std::string> refusal_names();

/// How a contract's statuses are judged, by name ("statuses").
inline constexpr EnumName<cases::StatusContract> status_contract_names[] = {
    {cases::StatusContract::exact, "exact"},
    {cases::StatusContract::any_refusal, "any_refusal"},
    {cases::StatusContract::answers_only, "answers_only"},
};
constexpr std::string_view status_contract_name(cases::StatusContract s) noexcept {
  return name_in(status_contract_names, s);
}
/// Inverse of status_contract_name(); none for an unknown name.
constexpr std::optional<cases::StatusContract> parse_status_contract(
    std::string_view name) noexcept {
  return value_in(status_contract_names, name);
}

std::optional<cases::Property> parse_property(std::string_view name) noexcept;

}  // namespace oblique
