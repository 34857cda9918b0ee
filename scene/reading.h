// The scene reader's parts (internal to oblique::scene): typed reads of a scene file's fields
// that name the field's path in their message (FieldError), the camera and the surfaces.
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "oblique/protocol/json.h"
#include "oblique/scene/scene.h"

namespace oblique::scene::reading {

using json = protocol::JsonValue;

/// A field that is missing, of the wrong type or degenerate: the message names its path.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& path, const std::string& what);
/// `what` "name" is unknown at `path`: the closest of `known` ("did you mean ...?") and the list.
[[noreturn]] void fail_unknown(const std::string& path, const std::string& what,
                               const std::string& name, const std::vector<std::string>& known);

/// Numbers are read from their text; one beyond double's range is NaN here (JSON itself cannot
/// write NaN), which the readers below refuse by name.
inline constexpr const char* kOutOfRange = "out of the range of a double";

/// A number's value, NaN when it is beyond double's range.
double as_double(const json& v);
/// What a value is, for messages: "a string", "an array of 2", ...
std::string type_of(const json& v);
/// "path.key" ("key" at the top level).
std::string join(const std::string& path, const char* key);
const json& member(const json& object, const std::string& path, const char* key);
double number(const json& object, const std::string& path, const char* key);
std::string text(const json& object, const std::string& path, const char* key);
Vector3 vector3(const json& object, const std::string& path, const char* key);
/// Refuses a value that is not an object, and any key of `object` not in `known`, naming its
/// path.
void only_keys(const json& object, const std::string& path,
               std::initializer_list<const char*> known);
bool has(const json& object, const char* key);
/// An optional boolean field (false when absent).
bool boolean(const json& object, const std::string& path, const char* key);
/// An integer in [low, high].
int integer(const json& v, const std::string& where, int low, int high);
/// 16 numbers in a named layout ("row_major" or "column_major"), or 4 rows of 4 ("rows").
Matrix4<double> matrix16(const json& object, const std::string& path);

/// The same direction with its largest component in [1, 2): scaled by a power of two (exactly),
/// so |v|^2 neither overflows nor underflows. Zero for a zero or non-finite vector.
Vector3 unit_direction(const Vector3& v);

/// The scene's "camera" (projection and view), refused when degenerate in double; what is
/// accepted but likely a mistake (a fovy_deg that reads as radians) is added to `warnings`.
Camera read_camera(const json& root, Convention convention, std::vector<std::string>& warnings);
/// One of the scene's "surfaces".
Surface read_surface(const json& s, const std::string& path);

}  // namespace oblique::scene::reading
