#include "oblique/scene/scene.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
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
    error = ex.what();
    if (const auto pos = error.find("] "); pos != std::string::npos) error.erase(0, pos + 2);
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

const char* type_of(const json& v) {
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
  if (!object.is_object()) fail(path, std::string("must be an object, not ") + type_of(object));
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
  if (!v.is_array() || v.size() != 3) fail(where, "must be an array of 3 numbers");
  Vector3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[static_cast<std::size_t>(i)].is_number())
      fail(where + "[" + std::to_string(i) + "]", "must be a number");
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

Camera read_camera(const json& root, Convention convention) {
  const json& camera = member(root, "", "camera");
  const json& projection = member(camera, "camera", "projection");
  const std::string p = "camera.projection";
  const std::string type = text(projection, p, "type");
  Camera c;
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
    const double fovy = number(projection, p, "fovy_deg");
    if (!(fovy > 0 && fovy < 180)) fail(p + ".fovy_deg", "must be in (0, 180)");
    const double aspect = number(projection, p, "aspect");
    if (!(aspect > 0)) fail(p + ".aspect", "must be > 0");
    return std::pair<double, double>(fovy * kPi / 180, aspect);
  };
  auto box = [&]() {
    const double l = number(projection, p, "left"), r = number(projection, p, "right");
    const double b = number(projection, p, "bottom"), t = number(projection, p, "top");
    if (l == r) fail(p + ".right", "must differ from left");
    if (b == t) fail(p + ".top", "must differ from bottom");
    return std::array<double, 4>{l, r, b, t};
  };
  if (type == "perspective") {
    c.type = ProjectionType::perspective;
    const auto [fovy, aspect] = fov_aspect();
    const auto [n, f] = near_far(true, true);
    c.projection = perspective<double>(fovy, aspect, n, f, convention);
  } else if (type == "infinite") {
    c.type = ProjectionType::infinite;
    const auto [fovy, aspect] = fov_aspect();
    const auto [n, f] = near_far(false, true);
    (void)f;
    c.projection = infinite_perspective<double>(fovy, aspect, n, convention);
  } else if (type == "frustum") {
    c.type = ProjectionType::frustum;
    const auto [l, r, b, t] = box();
    const auto [n, f] = near_far(true, true);
    c.projection = frustum<double>(l, r, b, t, n, f, convention);
  } else if (type == "orthographic") {
    c.type = ProjectionType::orthographic;
    const auto [l, r, b, t] = box();
    const auto [n, f] = near_far(true, false);  // glOrtho allows near <= 0
    c.projection = orthographic<double>(l, r, b, t, n, f, convention);
  } else if (type == "matrix") {
    c.type = ProjectionType::matrix;
    const json& rows = member(projection, p, "rows");
    if (!rows.is_array() || rows.size() != 4) fail(p + ".rows", "must be 4 rows of 4 numbers");
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string where = p + ".rows[" + std::to_string(i) + "]";
      if (!rows[i].is_array() || rows[i].size() != 4) fail(where, "must be 4 numbers");
      for (std::size_t j = 0; j < 4; ++j) {
        if (!rows[i][j].is_number())
          fail(where + "[" + std::to_string(j) + "]", "must be a number");
        const double x = rows[i][j].get<double>();
        if (!std::isfinite(x)) fail(where + "[" + std::to_string(j) + "]", kOutOfRange);
        c.projection(static_cast<int>(i), static_cast<int>(j)) = x;
      }
    }
    if (c.projection.determinant() == 0) fail(p + ".rows", "the matrix is singular");
  } else {
    fail(p + ".type",
         "unknown type \"" + type + "\" (perspective, infinite, frustum, orthographic or matrix)");
  }
  const json& view = member(camera, "camera", "view");
  c.eye = vector3(view, "camera.view", "eye");
  c.target = vector3(view, "camera.view", "target");
  c.up = vector3(view, "camera.view", "up");
  if (c.eye == c.target) fail("camera.view.target", "must differ from eye");
  if (!(c.up.norm() > 0)) fail("camera.view.up", "must not be the zero vector");
  const auto v = look_at(c.eye, c.target, c.up);
  if (!v) fail("camera.view.up", "must not be parallel to the view direction");
  c.view = *v;
  validate_camera(c, p);
  return c;
}

Surface read_surface(const json& s, const std::string& path) {
  Surface out;
  out.name = text(s, path, "name");
  const std::string kind = text(s, path, "kind");
  if (kind == "mirror") {
    out.kind = SurfaceKind::mirror;
  } else if (kind == "clip") {
    out.kind = SurfaceKind::clip;
  } else {
    fail(path + ".kind", "unknown kind \"" + kind + "\" (mirror or clip)");
  }
  const json& plane = member(s, path, "plane");
  out.normal = vector3(plane, path + ".plane", "normal");
  out.point = vector3(plane, path + ".plane", "point");
  // A normal is a direction: its length does not matter. One far from length 1 (beyond 2^+-64) is
  // made a unit vector (scaled by a power of two first), so |n|^2 and n . p stay in range.
  const double largest = out.normal.cwiseAbs().maxCoeff();
  if (!(largest > 0)) fail(path + ".plane.normal", "must not be the zero vector");
  if (std::abs(std::ilogb(largest)) > 64) out.normal = unit_direction(out.normal).normalized();
  if (!out.plane().allFinite())
    fail(path + ".plane.point", "out of range for this normal (n . point overflows a double)");
  return out;
}

}  // namespace

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
    scene.name = text(root, "", "name");
    const std::string convention = text(root, "", "convention");
    const auto c = parse_convention(convention);
    if (!c)
      fail("convention", "unknown convention \"" + convention + "\" (gl, zero_one, reversed_z)");
    scene.convention = *c;
    scene.camera = read_camera(root, scene.convention);
    const json& surfaces = member(root, "", "surfaces");
    if (!surfaces.is_array())
      fail("surfaces", std::string("must be an array, not ") + type_of(surfaces));
    for (std::size_t i = 0; i < surfaces.size(); ++i)
      scene.surfaces.push_back(read_surface(surfaces[i], "surfaces[" + std::to_string(i) + "]"));
    out.scene = std::move(scene);
  } catch (const FieldError& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace oblique::scene
