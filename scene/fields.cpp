// Typed reads of a scene file's fields, each naming the field's path when it refuses one.
#include <cmath>
#include <cstdlib>
#include <limits>

#include "reading.h"

#include "oblique/protocol/names.h"

namespace oblique::scene::reading {

void fail(const std::string& path, const std::string& what) {
  throw FieldError(path + ": " + what);
}

void fail_unknown(const std::string& path, const std::string& what, const std::string& name,
                  const std::vector<std::string>& known) {
  fail(path, protocol::unknown_name(what, name, known));
}

/// A number's value, NaN when it is beyond double's range.
double as_double(const json& v) {
  const double x = std::strtod(v.text.c_str(), nullptr);
  return std::isfinite(x) ? x : std::numeric_limits<double>::quiet_NaN();
}

/// What a value is, for messages: "a string", "an array of 2", ...
std::string type_of(const json& v) {
  if (v.is_array()) return "an array of " + std::to_string(v.size());
  return protocol::kind_name(v.kind);
}

const json& member(const json& object, const std::string& path, const char* key) {
  if (!object.is_object())
    fail(path.empty() ? "(top level)" : path,
         std::string("must be an object, not ") + type_of(object));
  const json* found = object.find(key);
  if (!found) fail(path.empty() ? key : path + "." + key, "missing");
  return *found;
}

std::string join(const std::string& path, const char* key) {
  return path.empty() ? key : path + "." + key;
}

double number(const json& object, const std::string& path, const char* key) {
  const json& v = member(object, path, key);
  if (!v.is_number()) fail(join(path, key), std::string("must be a number, not ") + type_of(v));
  const double x = as_double(v);
  if (!std::isfinite(x)) fail(join(path, key), kOutOfRange);
  return x;
}

std::string text(const json& object, const std::string& path, const char* key) {
  const json& v = member(object, path, key);
  if (!v.is_string()) fail(join(path, key), std::string("must be a string, not ") + type_of(v));
  return v.text;
}

Vector3 vector3(const json& object, const std::string& path, const char* key) {
  const json& v = member(object, path, key);
  const std::string where = join(path, key);
  if (!v.is_array() || v.size() != 3)
    fail(where, std::string("must be an array of 3 numbers, not ") + type_of(v));
  Vector3 out;
  for (int i = 0; i < 3; ++i) {
    const json& x = v[static_cast<std::size_t>(i)];
    if (!x.is_number())
      fail(where + "[" + std::to_string(i) + "]",
           std::string("must be a number, not ") + type_of(x));
    out(i) = as_double(v[static_cast<std::size_t>(i)]);
    if (!std::isfinite(out(i))) fail(where + "[" + std::to_string(i) + "]", kOutOfRange);
  }
  return out;
}

/// Refuses a value that is not an object, and any key of `object` not in `known`, naming its
/// path.
void only_keys(const json& object, const std::string& path,
               std::initializer_list<const char*> known) {
  if (!object.is_object())
    fail(path.empty() ? "(top level)" : path,
         std::string("must be an object, not ") + type_of(object));
  for (const auto& [key, value] : object.members) {
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (ok) continue;
    std::string list;
    for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    fail(join(path, key.c_str()), "unknown key (known here: " + list + ")");
  }
}

bool has(const json& object, const char* key) {
  return object.is_object() && object.find(key) != nullptr;
}

bool boolean(const json& object, const std::string& path, const char* key) {
  if (!has(object, key)) return false;
  const json& v = object.at(key);
  if (!v.is_boolean())
    fail(join(path, key), std::string("must be true or false, not ") + type_of(v));
  return v.text == "true";
}

/// An integer in [low, high].
int integer(const json& v, const std::string& where, int low, int high) {
  if (!v.is_number()) fail(where, "must be an integer, not " + type_of(v));
  const double x = as_double(v);
  if (!(x >= low && x <= high) || x != std::floor(x))
    fail(where,
         "must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  return static_cast<int>(x);
}

/// 16 numbers in a named layout ("row_major" or "column_major" of the column-vector matrix, or
/// "row_vectors": a row-vector engine's matrix, M^T, by rows, as DirectXMath stores it), or 4
/// rows of 4 ("rows").
Matrix4<double> matrix16(const json& object, const std::string& path) {
  Matrix4<double> m;
  if (has(object, "rows")) {
    const json& rows = object.at("rows");
    if (!rows.is_array() || rows.size() != 4)
      fail(path + ".rows", "must be 4 rows of 4 numbers, not " + type_of(rows));
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string where = path + ".rows[" + std::to_string(i) + "]";
      if (!rows[i].is_array() || rows[i].size() != 4)
        fail(where, "must be 4 numbers, not " + type_of(rows[i]));
      for (std::size_t j = 0; j < 4; ++j) {
        if (!rows[i][j].is_number())
          fail(where + "[" + std::to_string(j) + "]",
               "must be a number, not " + type_of(rows[i][j]));
        const double x = as_double(rows[i][j]);
        if (!std::isfinite(x)) fail(where + "[" + std::to_string(j) + "]", kOutOfRange);
        m(static_cast<int>(i), static_cast<int>(j)) = x;
      }
    }
    return m;
  }
  const json& values = member(object, path, "matrix");
  const std::string layout = text(object, path, "layout");
  if (layout != "row_major" && layout != "column_major" && layout != "row_vectors")
    fail_unknown(path + ".layout", "layout", layout, {"row_major", "column_major", "row_vectors"});
  if (!values.is_array() || values.size() != 16)
    fail(path + ".matrix", "must be 16 numbers, not " + type_of(values));
  for (std::size_t k = 0; k < 16; ++k) {
    const std::string where = path + ".matrix[" + std::to_string(k) + "]";
    if (!values[k].is_number()) fail(where, "must be a number, not " + type_of(values[k]));
    const double x = as_double(values[k]);
    if (!std::isfinite(x)) fail(where, kOutOfRange);
    const int a = static_cast<int>(k / 4), b = static_cast<int>(k % 4);
    if (layout == "row_major") {
      m(a, b) = x;
    } else {  // column_major, and row_vectors' M^T by rows: the same numbers
      m(b, a) = x;
    }
  }
  return m;
}

/// The same direction with its largest component in [1, 2): scaled by a power of two (exactly),
/// so |v|^2 neither overflows nor underflows. Zero for a zero or non-finite vector.
Vector3 unit_direction(const Vector3& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0) || !std::isfinite(largest)) return Vector3::Zero();
  return std::ldexp(1.0, -std::ilogb(largest)) * v;
}

}  // namespace oblique::scene::reading
