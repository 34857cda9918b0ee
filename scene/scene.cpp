#include "oblique/scene/scene.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <stdexcept>

#include "oblique/projection.h"
#include "oblique/protocol/protocol.h"

namespace oblique::scene {

Vector4<double> Surface::plane() const {
  return Vector4<double>(normal.x(), normal.y(), normal.z(), -normal.dot(point));
}

namespace {

/// The same direction with its largest component in [1, 2): scaled by a power of two (exactly),
/// so |v|^2 neither overflows nor underflows. Zero for a zero or non-finite vector.
Vector3 unit_direction(const Vector3& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0) || !std::isfinite(largest)) return Vector3::Zero();
  return std::ldexp(1.0, -std::ilogb(largest)) * v;
}

}  // namespace

std::optional<Matrix4<double>> look_at(const Vector3& eye, const Vector3& target,
                                       const Vector3& up) {
  const Vector3 forward = target - eye;
  const Vector3 f = unit_direction(forward).normalized();
  const Vector3 up_unit = unit_direction(up).normalized();
  if (!(f.norm() > 0) || !(up_unit.norm() > 0)) return std::nullopt;
  const Vector3 side = f.cross(up_unit);
  if (!(side.norm() > 1e-12)) return std::nullopt;  // up parallel to the view direction
  const Vector3 s = side.normalized();
  const Vector3 u = s.cross(f);
  Matrix4<double> v = Matrix4<double>::Identity();
  v.block<1, 3>(0, 0) = s.transpose();
  v.block<1, 3>(1, 0) = u.transpose();
  v.block<1, 3>(2, 0) = -f.transpose();
  v(0, 3) = -s.dot(eye);
  v(1, 3) = -u.dot(eye);
  v(2, 3) = f.dot(eye);
  return v;
}

Matrix4<double> reflection(const Vector4<double>& plane_in) {
  // The reflection does not depend on the plane's scale: scaled (exactly) so |n|^2 is in range.
  const double largest = plane_in.head<3>().cwiseAbs().maxCoeff();
  const Vector4<double> plane = largest > 0 && std::isfinite(largest)
                                    ? std::ldexp(1.0, -std::ilogb(largest)) * plane_in
                                    : plane_in;
  const Vector3 n = plane.head<3>();
  const double nn = n.squaredNorm();
  Matrix4<double> r = Matrix4<double>::Identity();
  r.block<3, 3>(0, 0) -= 2 * n * n.transpose() / nn;
  r.block<3, 1>(0, 3) = -2 * plane.w() * n / nn;
  return r;
}

namespace {

using json = nlohmann::json;

/// A field that is missing, of the wrong type or degenerate: the message names its path.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw FieldError(path + ": " + what);
}

/// Numbers are read from their text (ScanningDom); one beyond double's range arrives as NaN, which
/// JSON itself cannot write.
constexpr const char* kOutOfRange = "out of the range of a double";

/// nlohmann's DOM builder, run on protocol::scan_json_numbers()'s masked text so that no number
/// can make the parser throw; each number is converted from its own text (NaN when it overflows).
class ScanningDom final : public nlohmann::json_sax<json> {
 public:
  ScanningDom(json& root, const std::vector<std::string_view>& numbers)
      : dom_(root, false), numbers_(numbers) {}
  std::string error;

  bool null() override { return dom_.null(); }
  bool boolean(bool b) override { return dom_.boolean(b); }
  bool number_integer(number_integer_t) override { return number(); }
  bool number_unsigned(number_unsigned_t) override { return number(); }
  bool number_float(number_float_t, const string_t&) override { return number(); }
  bool string(string_t& s) override { return dom_.string(s); }
  bool binary(binary_t& b) override { return dom_.binary(b); }
  bool start_object(std::size_t n) override { return dom_.start_object(n); }
  bool key(string_t& k) override { return dom_.key(k); }
  bool end_object() override { return dom_.end_object(); }
  bool start_array(std::size_t n) override { return dom_.start_array(n); }
  bool end_array() override { return dom_.end_array(); }
  bool parse_error(std::size_t, const std::string&,
                   const nlohmann::detail::exception& ex) override {
    error = protocol::json_error_text(ex.what());
    return false;
  }

 private:
  bool number() {
    if (next_ >= numbers_.size()) {  // cannot happen for text the parser accepted
      error = "internal error: number tokens out of step";
      return false;
    }
    const std::string text(numbers_[next_++]);
    errno = 0;
    char* end = nullptr;
    double x = std::strtod(text.c_str(), &end);
    if (!std::isfinite(x)) x = std::numeric_limits<double>::quiet_NaN();
    return dom_.number_float(x, text);
  }
  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::vector<std::string_view>& numbers_;
  std::size_t next_ = 0;
};

/// What a value is, for messages: "a string", "an array of 2", ...
std::string type_of(const json& v) {
  if (v.is_array()) return "an array of " + std::to_string(v.size());
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "a number";
    default: return "a value";
  }
}

const json& member(const json& object, const std::string& path, const char* key) {
  if (!object.is_object())
    fail(path.empty() ? "(top level)" : path,
         std::string("must be an object, not ") + type_of(object));
  const auto it = object.find(key);
  if (it == object.end()) fail(path.empty() ? key : path + "." + key, "missing");
  return *it;
}

std::string join(const std::string& path, const char* key) {
  return path.empty() ? key : path + "." + key;
}

double number(const json& object, const std::string& path, const char* key) {
  const json& v = member(object, path, key);
  if (!v.is_number()) fail(join(path, key), std::string("must be a number, not ") + type_of(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(join(path, key), kOutOfRange);
  return x;
}

std::string text(const json& object, const std::string& path, const char* key) {
  const json& v = member(object, path, key);
  if (!v.is_string()) fail(join(path, key), std::string("must be a string, not ") + type_of(v));
  return v.get<std::string>();
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
    out(i) = v[static_cast<std::size_t>(i)].get<double>();
    if (!std::isfinite(out(i))) fail(where + "[" + std::to_string(i) + "]", kOutOfRange);
  }
  return out;
}

/// A camera whose matrices overflow or whose view volume has no finite corners in double (far =
/// 1e308 with near = 1e-308, a box of +-1e308) is refused here, before any surface is looked at:
/// every later test (visibility, the core) would see NaN.
void validate_camera(const Camera& c, const std::string& p) {
  const char* why = "degenerate in double (near, far or the box out of range)";
  if (!c.projection.allFinite()) fail(p, std::string(why) + ": the matrix overflows");
  if (!c.view.allFinite()) fail("camera.view", "eye or target out of the range of a double");
  const Matrix4<double> view_projection = c.projection * c.view;
  if (!view_projection.allFinite())
    fail("camera", "projection x view overflows a double (eye or target too far out)");
  if (c.projection.determinant() == 0) fail(p, std::string(why) + ": the matrix is singular");
  const Matrix4<double> inverse = view_projection.inverse();
  if (!inverse.allFinite())
    fail(p, std::string(why) + ": the view volume's corners are not finite");
  // The near and far faces of every convention: z = -1, 0, 1.
  for (int x : {-1, 1}) {
    for (int y : {-1, 1}) {
      for (int z : {-1, 0, 1}) {
        const Vector4<double> corner = inverse * Vector4<double>(x, y, z, 1);
        if (!corner.allFinite() || corner.isZero(0))
          fail(p, std::string(why) + ": a corner of the view volume is not finite");
      }
    }
  }
}

/// Refuses a value that is not an object, and any key of `object` not in `known`, naming its
/// path (nlohmann's iterator key() throws on anything but an object).
void only_keys(const json& object, const std::string& path,
               std::initializer_list<const char*> known) {
  if (!object.is_object())
    fail(path.empty() ? "(top level)" : path,
         std::string("must be an object, not ") + type_of(object));
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (ok) continue;
    std::string list;
    for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    fail(join(path, it.key().c_str()), "unknown key (known here: " + list + ")");
  }
}

bool has(const json& object, const char* key) {
  return object.is_object() && object.find(key) != object.end();
}

bool boolean(const json& object, const std::string& path, const char* key) {
  if (!has(object, key)) return false;
  const json& v = object.at(key);
  if (!v.is_boolean())
    fail(join(path, key), std::string("must be true or false, not ") + type_of(v));
  return v.get<bool>();
}

/// An integer in [low, high].
int integer(const json& v, const std::string& where, int low, int high) {
  if (!v.is_number()) fail(where, "must be an integer, not " + type_of(v));
  const double x = v.get<double>();
  if (!(x >= low && x <= high) || x != std::floor(x))
    fail(where,
         "must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  return static_cast<int>(x);
}

/// 16 numbers in a named layout ("row_major" or "column_major"), or 4 rows of 4 ("rows").
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
        const double x = rows[i][j].get<double>();
        if (!std::isfinite(x)) fail(where + "[" + std::to_string(j) + "]", kOutOfRange);
        m(static_cast<int>(i), static_cast<int>(j)) = x;
      }
    }
    return m;
  }
  const json& values = member(object, path, "matrix");
  const std::string layout = text(object, path, "layout");
  if (layout != "row_major" && layout != "column_major")
    fail(path + ".layout", "unknown layout \"" + layout + "\" (row_major or column_major)");
  if (!values.is_array() || values.size() != 16)
    fail(path + ".matrix", "must be 16 numbers, not " + type_of(values));
  for (std::size_t k = 0; k < 16; ++k) {
    const std::string where = path + ".matrix[" + std::to_string(k) + "]";
    if (!values[k].is_number()) fail(where, "must be a number, not " + type_of(values[k]));
    const double x = values[k].get<double>();
    if (!std::isfinite(x)) fail(where, kOutOfRange);
    const int a = static_cast<int>(k / 4), b = static_cast<int>(k % 4);
    if (layout == "row_major") {
      m(a, b) = x;
    } else {
      m(b, a) = x;
    }
  }
  return m;
}

Matrix4<double> read_projection(const json& projection, Convention convention,
                                ProjectionType& type_out) {
  const std::string p = "camera.projection";
  const std::string type = text(projection, p, "type");
  constexpr double kPi = 3.14159265358979323846;
  auto near_far = [&](bool finite_far, bool positive_near) {
    const double n = number(projection, p, "near");
    if (positive_near && !(n > 0)) fail(p + ".near", "must be > 0 (got " + std::to_string(n) + ")");
    if (!finite_far) return std::pair<double, double>(n, 0);
    const double f = number(projection, p, "far");
    if (!(f > n)) fail(p + ".far", "must be > near (got " + std::to_string(f) + ")");
    return std::pair<double, double>(n, f);
  };
  auto fov_aspect = [&]() {
    const bool deg = has(projection, "fovy_deg"), rad = has(projection, "fovy_rad");
    if (deg && rad) fail(p + ".fovy_rad", "give fovy_deg or fovy_rad, not both");
    if (!deg && !rad) fail(p + ".fovy_deg", "missing (or fovy_rad)");
    double fovy = 0;
    if (deg) {
      fovy = number(projection, p, "fovy_deg");
      if (!(fovy > 0 && fovy < 180)) fail(p + ".fovy_deg", "must be in (0, 180) degrees");
      fovy *= kPi / 180;
    } else {
      fovy = number(projection, p, "fovy_rad");
      if (!(fovy > 0 && fovy < kPi)) fail(p + ".fovy_rad", "must be in (0, pi) radians");
    }
    const double aspect = number(projection, p, "aspect");
    if (!(aspect > 0)) fail(p + ".aspect", "must be > 0");
    return std::pair<double, double>(fovy, aspect);
  };
  auto box = [&]() {
    const double l = number(projection, p, "left"), r = number(projection, p, "right");
    const double b = number(projection, p, "bottom"), t = number(projection, p, "top");
    if (l == r) fail(p + ".right", "must differ from left");
    if (b == t) fail(p + ".top", "must differ from bottom");
    return std::array<double, 4>{l, r, b, t};
  };
  Matrix4<double> m;
  if (type == "perspective") {
    only_keys(projection, p,
              {"type", "fovy_deg", "fovy_rad", "aspect", "near", "far", "infinite_far", "y_flip"});
    const auto [fovy, aspect] = fov_aspect();
    const bool infinite = boolean(projection, p, "infinite_far");
    if (infinite && has(projection, "far")) fail(p + ".far", "not allowed with infinite_far");
    const auto [n, f] = near_far(!infinite, true);
    type_out = infinite ? ProjectionType::infinite : ProjectionType::perspective;
    m = infinite ? infinite_perspective<double>(fovy, aspect, n, convention)
                 : perspective<double>(fovy, aspect, n, f, convention);
  } else if (type == "infinite") {
    only_keys(projection, p, {"type", "fovy_deg", "fovy_rad", "aspect", "near", "y_flip"});
    type_out = ProjectionType::infinite;
    const auto [fovy, aspect] = fov_aspect();
    const double n = near_far(false, true).first;
    m = infinite_perspective<double>(fovy, aspect, n, convention);
  } else if (type == "frustum") {
    only_keys(projection, p,
              {"type", "left", "right", "bottom", "top", "near", "far", "infinite_far", "y_flip"});
    const auto [l, r, b, t] = box();
    const bool infinite = boolean(projection, p, "infinite_far");
    if (infinite && has(projection, "far")) fail(p + ".far", "not allowed with infinite_far");
    const auto [n, f] = near_far(!infinite, true);
    type_out = infinite ? ProjectionType::infinite : ProjectionType::frustum;
    m = infinite ? infinite_frustum<double>(l, r, b, t, n, convention)
                 : frustum<double>(l, r, b, t, n, f, convention);
  } else if (type == "orthographic") {
    only_keys(projection, p, {"type", "left", "right", "bottom", "top", "near", "far", "y_flip"});
    type_out = ProjectionType::orthographic;
    const auto [l, r, b, t] = box();
    const auto [n, f] = near_far(true, false);  // glOrtho allows near <= 0
    m = orthographic<double>(l, r, b, t, n, f, convention);
  } else if (type == "matrix") {
    only_keys(projection, p, {"type", "rows", "matrix", "layout", "y_flip"});
    type_out = ProjectionType::matrix;
    m = matrix16(projection, p);
    if (m.determinant() == 0)
      fail(p + (has(projection, "rows") ? ".rows" : ".matrix"), "the matrix is singular");
  } else {
    fail(p + ".type",
         "unknown type \"" + type + "\" (perspective, infinite, frustum, orthographic or matrix)");
  }
  // Vulkan's y-flip: clip y negated (the image is upside down relative to GL).
  if (boolean(projection, p, "y_flip")) m.row(1) = -m.row(1);
  return m;
}

void read_view(const json& view, Camera& c) {
  const std::string p = "camera.view";
  if (!view.is_object()) fail(p, std::string("must be an object, not ") + type_of(view));
  if (has(view, "matrix")) {
    only_keys(view, p, {"matrix", "layout"});
    c.view = matrix16(view, p);
    if (c.view.row(3) != Vector4<double>(0, 0, 0, 1).transpose())
      fail(p + ".matrix", "must be affine (last row 0, 0, 0, 1 in the layout given)");
    const Eigen::Matrix3d r = c.view.block<3, 3>(0, 0);
    if (!(std::abs(r.determinant()) > 0) || !std::isfinite(r.determinant()))
      fail(p + ".matrix", "the rotation part is singular");
    const Eigen::Matrix3d ri = r.inverse();
    c.eye = -ri * c.view.block<3, 1>(0, 3);
    c.target = c.eye + ri * Vector3(0, 0, -1);
    c.up = ri * Vector3(0, 1, 0);
  } else if (has(view, "position")) {
    only_keys(view, p, {"position", "quaternion_xyzw"});
    c.eye = vector3(view, p, "position");
    const json& q = member(view, p, "quaternion_xyzw");
    if (!q.is_array() || q.size() != 4)
      fail(p + ".quaternion_xyzw", "must be 4 numbers x, y, z, w, not " + type_of(q));
    Vector4<double> v;
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string where = p + ".quaternion_xyzw[" + std::to_string(i) + "]";
      if (!q[i].is_number()) fail(where, "must be a number, not " + type_of(q[i]));
      v(static_cast<int>(i)) = q[i].get<double>();
      if (!std::isfinite(v(static_cast<int>(i)))) fail(where, kOutOfRange);
    }
    const double largest = v.cwiseAbs().maxCoeff();
    if (!(largest > 0)) fail(p + ".quaternion_xyzw", "must not be zero");
    v = (std::ldexp(1.0, -std::ilogb(largest)) * v).normalized();
    // The camera's rotation (camera -> world); the camera looks along its -z with +y up.
    const Eigen::Matrix3d r = Eigen::Quaterniond(v(3), v(0), v(1), v(2)).toRotationMatrix();
    c.view = Matrix4<double>::Identity();
    c.view.block<3, 3>(0, 0) = r.transpose();
    c.view.block<3, 1>(0, 3) = -r.transpose() * c.eye;
    c.target = c.eye + r * Vector3(0, 0, -1);
    c.up = r * Vector3(0, 1, 0);
  } else {
    only_keys(view, p, {"eye", "target", "up"});
    c.eye = vector3(view, p, "eye");
    c.target = vector3(view, p, "target");
    c.up = vector3(view, p, "up");
    if (c.eye == c.target) fail(p + ".target", "must differ from eye");
    if (!(c.up.norm() > 0)) fail(p + ".up", "must not be the zero vector");
    const auto v = look_at(c.eye, c.target, c.up);
    if (!v) fail(p + ".up", "must not be parallel to the view direction");
    c.view = *v;
  }
}

Camera read_camera(const json& root, Convention convention) {
  const json& camera = member(root, "", "camera");
  only_keys(camera, "camera", {"projection", "view"});
  const json& projection = member(camera, "camera", "projection");
  Camera c;
  c.projection = read_projection(projection, convention, c.type);
  read_view(member(camera, "camera", "view"), c);
  validate_camera(c, "camera.projection");
  return c;
}

/// A unit normal from a direction of any length (scaled by a power of two first).
Vector3 unit_normal(const Vector3& n, const std::string& where) {
  const Vector3 u = unit_direction(n).normalized();
  if (!(u.norm() > 0) || !u.allFinite()) fail(where, "must not be the zero vector");
  return u;
}

std::vector<Vector3> read_polygon(const json& vertices, const std::string& where) {
  if (!vertices.is_array() || vertices.size() < 3 || vertices.size() > kMaxPolygonVertices)
    fail(where, "must be an array of 3 to " + std::to_string(kMaxPolygonVertices) +
                    " vertices [x, y, z], not " + type_of(vertices));
  std::vector<Vector3> out;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    const json& v = vertices[i];
    if (!v.is_array() || v.size() != 3)
      fail(at, "must be an array of 3 numbers, not " + type_of(v));
    Vector3 p;
    for (int k = 0; k < 3; ++k) {
      if (!v[static_cast<std::size_t>(k)].is_number())
        fail(at + "[" + std::to_string(k) + "]",
             "must be a number, not " + type_of(v[static_cast<std::size_t>(k)]));
      p(k) = v[static_cast<std::size_t>(k)].get<double>();
      if (!std::isfinite(p(k))) fail(at + "[" + std::to_string(k) + "]", kOutOfRange);
    }
    out.push_back(p);
  }
  return out;
}

/// The polygon's plane: Newell's normal (counter-clockwise seen from the front) and centroid;
/// refuses a polygon that is degenerate, not planar or out of range.
void polygon_plane(Surface& out, const std::string& where) {
  Vector3 centroid = Vector3::Zero();
  for (const Vector3& v : out.polygon) centroid += v / static_cast<double>(out.polygon.size());
  double extent = 0;
  for (const Vector3& v : out.polygon)
    extent = std::max(extent, (v - centroid).cwiseAbs().maxCoeff());
  if (!centroid.allFinite() || !std::isfinite(extent)) fail(where, "out of the range of a double");
  if (!(extent > 0)) fail(where, "degenerate: every vertex is the same point");
  const double scale = std::ldexp(1.0, -std::ilogb(extent));
  Vector3 newell = Vector3::Zero();
  const std::size_t n = out.polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3 a = scale * (out.polygon[i] - centroid);
    const Vector3 b = scale * (out.polygon[(i + 1) % n] - centroid);
    newell += a.cross(b);
  }
  if (!(newell.norm() > 1e-12)) fail(where, "degenerate: the vertices are collinear (no area)");
  out.normal = newell.normalized();
  out.point = centroid;
  for (std::size_t i = 0; i < n; ++i) {
    const double off = std::abs(out.normal.dot(scale * (out.polygon[i] - centroid)));
    if (off > 1e-9)
      fail(where + "[" + std::to_string(i) + "]", "not in the plane of the others (not planar)");
  }
}

Surface read_surface(const json& s, const std::string& path) {
  Surface out;
  if (!s.is_object()) fail(path, std::string("must be an object, not ") + type_of(s));
  only_keys(s, path, {"name", "kind", "plane", "polygon", "rectangle", "linked"});
  out.name = text(s, path, "name");
  const std::string kind = text(s, path, "kind");
  if (kind == "mirror") {
    out.kind = SurfaceKind::mirror;
  } else if (kind == "clip") {
    out.kind = SurfaceKind::clip;
  } else if (kind == "portal") {
    out.kind = SurfaceKind::portal;
  } else {
    fail(path + ".kind", "unknown kind \"" + kind + "\" (mirror, clip or portal)");
  }
  const int shapes = int{has(s, "plane")} + int{has(s, "polygon")} + int{has(s, "rectangle")};
  if (shapes == 0) fail(path + ".plane", "missing (or polygon, or rectangle)");
  if (shapes != 1) fail(path + ".plane", "give exactly one of plane, polygon or rectangle");
  if (out.kind != SurfaceKind::portal && has(s, "linked"))
    fail(path + ".linked", "only a portal has a linked portal");
  std::optional<Matrix4<double>> frame;
  if (has(s, "plane")) {
    const json& plane = s.at("plane");
    if (!plane.is_object()) fail(path + ".plane", "must be an object, not " + type_of(plane));
    only_keys(plane, path + ".plane", {"normal", "point"});
    out.normal = vector3(plane, path + ".plane", "normal");
    out.point = vector3(plane, path + ".plane", "point");
    // A normal is a direction: its length does not matter. One far from length 1 (beyond
    // 2^+-64) is made a unit vector (scaled by a power of two first), so |n|^2 and n . p stay in
    // range.
    const double largest = out.normal.cwiseAbs().maxCoeff();
    if (!(largest > 0)) fail(path + ".plane.normal", "must not be the zero vector");
    if (std::abs(std::ilogb(largest)) > 64) out.normal = unit_direction(out.normal).normalized();
  } else if (has(s, "polygon")) {
    const json& polygon = s.at("polygon");
    if (!polygon.is_object())
      fail(path + ".polygon", "must be an object {\"vertices\": [...]}, not " + type_of(polygon));
    only_keys(polygon, path + ".polygon", {"vertices"});
    out.polygon =
        read_polygon(member(polygon, path + ".polygon", "vertices"), path + ".polygon.vertices");
    polygon_plane(out, path + ".polygon.vertices");
  } else {
    const std::string r = path + ".rectangle";
    const json& rect = s.at("rectangle");
    if (!rect.is_object()) fail(r, "must be an object, not " + type_of(rect));
    only_keys(rect, r, {"center", "normal", "up", "size"});
    const Vector3 center = vector3(rect, r, "center");
    const Vector3 normal = unit_normal(vector3(rect, r, "normal"), r + ".normal");
    const Vector3 up = vector3(rect, r, "up");
    const json& size = member(rect, r, "size");
    if (!size.is_array() || size.size() != 2)
      fail(r + ".size", std::string("must be [width, height], not ") + type_of(size));
    for (std::size_t i = 0; i < 2; ++i) {
      if (!size[i].is_number())
        fail(r + ".size[" + std::to_string(i) + "]",
             std::string("must be a number, not ") + type_of(size[i]));
    }
    const double w = size[0].get<double>(), h = size[1].get<double>();
    if (!(w > 0 && h > 0) || !std::isfinite(w) || !std::isfinite(h))
      fail(r + ".size", "width and height must be finite and > 0");
    frame = rectangle_frame(center, normal, up);
    if (!frame) fail(r + ".up", "must not be the zero vector nor parallel to the normal");
    const Vector3 right = frame->block<3, 1>(0, 0), u = frame->block<3, 1>(0, 1);
    for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
      out.polygon.push_back(center + a * w / 2 * right + b * h / 2 * u);
    out.normal = normal;
    out.point = center;
    for (const Vector3& v : out.polygon)
      if (!v.allFinite()) fail(r, "out of the range of a double");
  }
  if (out.kind == SurfaceKind::portal) {
    if (!frame) fail(path + ".rectangle", "a portal is a rectangle (its frame places the view)");
    const std::string l = path + ".linked";
    const json& linked = member(s, path, "linked");
    if (!linked.is_object())
      fail(l, "must be an object {center, normal, up}, not " + type_of(linked));
    only_keys(linked, l, {"center", "normal", "up"});
    const auto other = rectangle_frame(vector3(linked, l, "center"),
                                       unit_normal(vector3(linked, l, "normal"), l + ".normal"),
                                       vector3(linked, l, "up"));
    if (!other) fail(l + ".up", "must not be the zero vector nor parallel to the normal");
    out.portal_transform = portal_map(*frame, *other);
    if (!out.portal_transform.allFinite()) fail(l, "out of the range of a double");
  }
  if (!out.plane().allFinite())
    fail(path + (has(s, "plane") ? ".plane.point" : ""),
         "out of range for this normal (n . point overflows a double)");
  return out;
}

}  // namespace

std::optional<Matrix4<double>> rectangle_frame(const Vector3& center, const Vector3& normal_in,
                                               const Vector3& up_in) {
  const Vector3 normal = unit_direction(normal_in).normalized();
  const Vector3 up_dir = unit_direction(up_in).normalized();
  const Vector3 right = up_dir.cross(normal);
  if (!(right.norm() > 1e-12) || !center.allFinite()) return std::nullopt;
  Matrix4<double> f = Matrix4<double>::Identity();
  f.block<3, 1>(0, 0) = right.normalized();
  f.block<3, 1>(0, 1) = normal.cross(right.normalized());
  f.block<3, 1>(0, 2) = normal;
  f.block<3, 1>(0, 3) = center;
  return f;
}

Matrix4<double> portal_map(const Matrix4<double>& frame, const Matrix4<double>& linked) {
  // Through the portal, in front of the linked one is behind this one: x and z turn around.
  const Matrix4<double> turn = Vector4<double>(-1, 1, -1, 1).asDiagonal();
  return frame * turn * linked.inverse();
}

namespace {}  // namespace

ParsedScene read_scene_file(const std::string& path) {
  ParsedScene out;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    out.error = "is a directory, not a scene file";
    return out;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    out.error = std::string("cannot open: ") + std::strerror(errno);
    return out;
  }
  // Read in blocks, never more than kMaxSceneBytes + 1 (a device like /dev/zero never ends).
  std::string text;
  char block[65536];
  while (file && text.size() <= kMaxSceneBytes) {
    file.read(block, sizeof block);
    text.append(block, static_cast<std::size_t>(file.gcount()));
  }
  if (file.bad()) {
    out.error = std::string("cannot read: ") + std::strerror(errno);
    return out;
  }
  if (text.size() > kMaxSceneBytes) {
    out.error = "larger than " + std::to_string(kMaxSceneBytes) + " bytes: not a scene file";
    return out;
  }
  return parse_scene(text);
}

ParsedScene parse_scene(std::string_view text_in) {
  ParsedScene out;
  if (const auto nul = text_in.find('\0'); nul != std::string_view::npos) {
    out.error = "not valid JSON: a NUL byte at offset " + std::to_string(nul);
    return out;
  }
  std::string error;
  const std::optional<protocol::JsonNumbers> numbers =
      protocol::scan_json_numbers(text_in, kMaxSceneNumbers, &error);
  if (!numbers) {
    out.error = "not a scene: " + error;
    return out;
  }
  json root;
  ScanningDom dom(root, numbers->texts);
  if (!json::sax_parse(numbers->masked.begin(), numbers->masked.end(), &dom,
                       json::input_format_t::json, true, false)) {
    out.error = "not valid JSON: " + (dom.error.empty() ? std::string("parse error") : dom.error);
    return out;
  }
  try {
    Scene scene;
    if (!root.is_object())
      fail("(top level)", std::string("must be an object, not ") + type_of(root));
    only_keys(
        root, "",
        {"name", "convention", "depth_buffer", "camera", "surfaces", "max_depth", "viewport"});
    scene.name = text(root, "", "name");
    const std::string convention = text(root, "", "convention");
    const auto c = parse_convention(convention);
    if (!c)
      fail("convention", "unknown convention \"" + convention + "\" (gl, zero_one, reversed_z)");
    scene.convention = *c;
    // A reversed-Z buffer is a float buffer (that is what reversing is for); else 24-bit fixed.
    scene.depth_buffer =
        scene.convention == Convention::reversed_z ? DepthBuffer::float32 : DepthBuffer::fixed24;
    if (has(root, "depth_buffer")) {
      const std::string buffer = text(root, "", "depth_buffer");
      if (buffer == "fixed24") {
        scene.depth_buffer = DepthBuffer::fixed24;
      } else if (buffer == "float32") {
        scene.depth_buffer = DepthBuffer::float32;
      } else {
        fail("depth_buffer", "unknown depth buffer \"" + buffer + "\" (fixed24 or float32)");
      }
    }
    if (has(root, "max_depth"))
      scene.max_depth = integer(root.at("max_depth"), "max_depth", 1, kMaxDepth);
    if (has(root, "viewport")) {
      const json& v = root.at("viewport");
      if (!v.is_array() || v.size() != 2)
        fail("viewport", "must be [width, height] in pixels, not " + type_of(v));
      scene.viewport = std::array<int, 2>{integer(v[0], "viewport[0]", 1, 1 << 16),
                                          integer(v[1], "viewport[1]", 1, 1 << 16)};
    }
    scene.camera = read_camera(root, scene.convention);
    const json& surfaces = member(root, "", "surfaces");
    if (!surfaces.is_array())
      fail("surfaces", std::string("must be an array, not ") + type_of(surfaces));
    for (std::size_t i = 0; i < surfaces.size(); ++i)
      scene.surfaces.push_back(read_surface(surfaces[i], "surfaces[" + std::to_string(i) + "]"));
    out.scene = std::move(scene);
  } catch (const FieldError& e) {
    out.error = e.what();
  } catch (const json::exception& e) {
    // Every access above checks its value's type first; should one not, the scene is still
    // refused with a message (exit 2), never an abort.
    out.error = std::string("internal error reading the scene (please report it): ") + e.what();
  }
  return out;
}

}  // namespace oblique::scene
