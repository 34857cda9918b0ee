// Names a person types (subcommands, flags, families, places, statuses, fields) and what to say
// when one is unknown: the list of known names and the closest of them ("did you mean ...?").
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace oblique::protocol {

/// The known name closest to `name` in edit distance (letters swapped, missing, extra or
/// changed), or "" when none is close enough to be what was meant: at most a third of the
/// longer name's letters apart (at most 3), or `name` being a prefix of exactly one.
std::string closest_name(std::string_view name, const std::vector<std::string>& known);

/// "a, b, c".
std::string name_list(const std::vector<std::string>& names);

/// `what` "name" is unknown, with the suggestion and the list, e.g. `unknown family "perspectve"
/// (did you mean perspective?; known: perspective, off_axis, ...)`.
std::string unknown_name(std::string_view what, std::string_view name,
                         const std::vector<std::string>& known);

}  // namespace oblique::protocol
