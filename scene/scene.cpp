#include "oblique/scene/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>

#include "oblique/projection.h"

namespace oblique::scene {

Vector4<double> Surface::plane() const {
  return Vector4<double>(normal.x(), normal.y(), normal.z(), -normal.dot(point));
}

std::optional<Matrix4<double>> look_at(const Vector3& eye, const Vector3& target,
                                       const Vector3& up) {
  const Vector3 forward = target - eye;
  if (!(forward.norm() > 0) || !(up.norm() > 0)) return std::nullopt;
  const Vector3 f = forward.normalized();
  const Vector3 side = f.cross(up.normalized());
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

Matrix4<double> reflection(const Vector4<double>& plane) {
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
  if (!std::isfinite(x)) fail(join(path, key), "must be finite");
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
    if (!std::isfinite(out(i))) fail(where + "[" + std::to_string(i) + "]", "must be finite");
  }
  return out;
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
        if (!std::isfinite(x)) fail(where + "[" + std::to_string(j) + "]", "must be finite");
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
  if (!(out.normal.norm() > 0)) fail(path + ".plane.normal", "must not be the zero vector");
  return out;
}

}  // namespace

ParsedScene parse_scene(std::string_view text_in) {
  ParsedScene out;
  json root;
  try {
    root = json::parse(text_in.begin(), text_in.end());
  } catch (const json::parse_error& e) {
    std::string message = e.what();
    if (const auto pos = message.find("] "); pos != std::string::npos) message.erase(0, pos + 2);
    out.error = "not valid JSON: " + message;
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
