// The scene's camera: its projection (built from parameters or given as a matrix, in the
// scene's convention) and its view (look-at, position and quaternion, or a matrix).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "oblique/projection.h"
#include "oblique/protocol/numbers.h"
#include "reading.h"

namespace oblique::scene::reading {

namespace {

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

Matrix4<double> read_projection(const json& projection, Convention convention,
                                std::vector<std::string>& warnings, ProjectionType& type_out) {
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
  auto rounded = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return std::string(text);
  };
  auto fov_aspect = [&]() {
    const bool deg = has(projection, "fovy_deg"), rad = has(projection, "fovy_rad");
    if (deg && rad) fail(p + ".fovy_rad", "give fovy_deg or fovy_rad, not both");
    if (!deg && !rad) fail(p + ".fovy_deg", "missing (or fovy_rad)");
    double fovy = 0;
    if (deg) {
      fovy = number(projection, p, "fovy_deg");
      if (!(fovy > 0 && fovy < 180)) fail(p + ".fovy_deg", "must be in (0, 180) degrees");
      // A value that is a plausible angle in radians is most likely one (70 degrees is 1.22).
      if (fovy <= kPi)
        warnings.push_back(p + ".fovy_deg: " + protocol::format_number(fovy) +
                           " degrees is a very narrow view; if it is in radians (" +
                           rounded(fovy * 180 / kPi) +
                           " degrees), write \"fovy_rad\": " + protocol::format_number(fovy));
      fovy *= kPi / 180;
    } else {
      fovy = number(projection, p, "fovy_rad");
      if (fovy >= kPi && fovy < 180)
        fail(p + ".fovy_rad",
             "must be in (0, pi) radians; if " + protocol::format_number(fovy) +
                 " is in degrees, write \"fovy_deg\": " + protocol::format_number(fovy));
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
    fail_unknown(p + ".type", "type", type,
                 {"perspective", "infinite", "frustum", "orthographic", "matrix"});
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
      v(static_cast<int>(i)) = as_double(q[i]);
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

}  // namespace

Camera read_camera(const json& root, Convention convention, std::vector<std::string>& warnings) {
  const json& camera = member(root, "", "camera");
  only_keys(camera, "camera", {"projection", "view"});
  const json& projection = member(camera, "camera", "projection");
  Camera c;
  c.projection = read_projection(projection, convention, warnings, c.type);
  read_view(member(camera, "camera", "view"), c);
  validate_camera(c, "camera.projection");
  return c;
}

}  // namespace oblique::scene::reading
