// The scene's surfaces: mirrors, portals and clip planes, given as a plane, a polygon or a
// rectangle (a portal's with the rectangle it links to), and the frames a rectangle defines.
#include <cmath>

#include "reading.h"

namespace oblique::scene {

namespace reading {

namespace {

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
      p(k) = as_double(v[static_cast<std::size_t>(k)]);
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

}  // namespace

Surface read_surface(const json& s, const std::string& path) {
  Surface out;
  if (!s.is_object()) fail(path, std::string("must be an object, not ") + type_of(s));
  only_keys(s, path, {"name", "kind", "plane", "polygon", "rectangle", "linked"});
  out.name = text(s, path, "name");
  const std::string kind = text(s, path, "kind");
  if (const std::optional<SurfaceKind> k = value_in(surface_kind_names, kind)) {
    out.kind = *k;
  } else {
    fail_unknown(path + ".kind", "kind", kind, names_in(surface_kind_names));
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
    const double w = as_double(size[0]), h = as_double(size[1]);
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
    out.portal_frame = *frame;
    out.linked_frame = *other;
    out.portal_transform = portal_map(*frame, *other);
    if (!out.portal_transform.allFinite()) fail(l, "out of the range of a double");
  }
  if (!out.plane().allFinite())
    fail(path + (has(s, "plane") ? ".plane.point" : ""),
         "out of range for this normal (n . point overflows a double)");
  return out;
}

}  // namespace reading

using reading::unit_direction;

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

}  // namespace oblique::scene
