#include "oblique/scene/check.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string_view>
#include <vector>

#include "oblique/properties/properties.h"
#include "oblique/protocol/numbers.h"

namespace oblique::scene {

bool SurfaceCheck::passes() const {
  for (const properties::Finding& p : properties) {
    if (!p.holds) return false;
  }
  return true;
}

bool SceneCheck::passes() const {
  for (const SurfaceCheck& s : surfaces) {
    if (!s.passes()) return false;
  }
  return true;
}

namespace {

/// The near and far faces' clip-space depth (reversed Z: near at z = 1).
double near_face(Convention c) {
  return c == Convention::reversed_z ? 1 : clip_depth_range(c).z_low;
}
double far_face(Convention c) {
  return c == Convention::reversed_z ? 0 : clip_depth_range(c).z_high;
}

/// The plane in the space that `to_camera` maps world points into: planes go by M^-T.
Vector4<double> plane_in(const Matrix4<double>& to_camera, const Vector4<double>& world_plane) {
  return to_camera.inverse().transpose() * world_plane;
}

/// Whether the main camera's view volume lies entirely on the camera's side of the plane (it
/// does not see the surface at all). Corners at infinity count by direction.
bool out_of_view(const Camera& camera, const Vector4<double>& world_plane, Convention convention) {
  const Matrix4<double> inverse = (camera.projection * camera.view).inverse();
  const DepthRange range = clip_depth_range(convention);
  const double eye_side =
      world_plane.dot(Vector4<double>(camera.eye.x(), camera.eye.y(), camera.eye.z(), 1));
  for (int x : {-1, 1}) {
    for (int y : {-1, 1}) {
      for (int z : {range.z_low, range.z_high}) {
        Vector4<double> corner = inverse * Vector4<double>(x, y, z, 1);
        if (corner.w() < 0) corner = -corner;  // the same point, with w >= 0
        const double side = world_plane.dot(corner);
        if (side * eye_side < 0) return false;  // this corner is beyond the surface
      }
    }
  }
  return true;
}

std::string reason_for(Status status, SurfaceKind kind) {
  switch (status) {
    case Status::camera_not_behind_plane:
      return kind == SurfaceKind::mirror
                 ? "the camera is behind the surface (on the mirror's back side)"
                 : "the camera is on the kept side of the clip plane (oblique clipping needs it "
                   "behind)";
    case Status::plane_misses_view_volume:
      return "the oblique volume is empty (nothing the pass camera sees is in front of the "
             "surface)";
    default: return std::string(status_message(status));
  }
}

/// Every property that applies to the pass, holding or not.
std::vector<properties::Finding> judge(const Matrix4<double>& projection,
                                       const Vector4<double>& plane, Convention convention,
                                       const Matrix4<double>& result) {
  const properties::Problem<double> problem(projection, plane, convention);
  properties::Checks checks;
  checks.every = true;
  return properties::judge(problem, properties::Outcome<double>{Status::ok, result}, checks).checks;
}

}  // namespace

std::optional<DepthPrecision> depth_precision(const Matrix4<double>& original,
                                              const Matrix4<double>& oblique,
                                              const Vector4<double>& plane, Convention convention) {
  const Matrix4<double> inverse = original.inverse();
  Vector4<double> a = inverse * Vector4<double>(0, 0, near_face(convention), 1);
  Vector4<double> b = inverse * Vector4<double>(0, 0, far_face(convention), 1);
  if (a.w() < 0) a = -a;
  if (b.w() < 0) b = -b;
  // Points of the axis: (1 - s) a + s b for s in [0, 1] (b may be a direction, w = 0: then the
  // segment's far end is at infinity and the same formula holds for the homogeneous points).
  const double ca = plane.dot(a), cb = plane.dot(b);
  if (ca < 0 && cb < 0) return std::nullopt;  // the axis never enters the kept region
  auto depth = [&](const Vector4<double>& p) {
    return oblique.row(2).dot(p) / oblique.row(3).dot(p);
  };
  const double near_value = near_face(convention);
  double from = 0, to = 0;
  if (ca >= 0 && cb >= 0) {
    from = depth(a);
    to = depth(b);
  } else if (ca < 0) {
    from = near_value;  // the axis enters through the oblique near plane
    to = depth(b);
  } else {
    from = depth(a);
    to = near_value;
  }
  const DepthRange range = clip_depth_range(convention);
  DepthPrecision d;
  d.far_depth = std::abs(to - near_value) >= std::abs(from - near_value) ? to : from;
  d.fraction = std::abs(to - from) / (range.z_high - range.z_low);
  d.bits_lost = d.fraction > 0 ? -std::log2(d.fraction) : INFINITY;
  return d;
}

SceneCheck check_scene(const Scene& scene) {
  SceneCheck out;
  out.scene = scene.name;
  out.convention = scene.convention;
  const Camera& camera = scene.camera;
  for (const Surface& surface : scene.surfaces) {
    SurfaceCheck s;
    s.name = surface.name;
    s.kind = surface.kind;
    const Vector4<double> world_plane = surface.plane();
    s.view = surface.kind == SurfaceKind::mirror
                 ? Matrix4<double>(camera.view * reflection(world_plane))
                 : camera.view;
    s.plane_in_camera = plane_in(s.view, world_plane);
    const ObliqueResult<double> result =
        apply<double>(camera.projection, s.plane_in_camera, scene.convention);
    s.status = result.status;
    s.method = result.method;
    if (result.status == Status::camera_not_behind_plane) {
      s.reason = reason_for(result.status, surface.kind);
    } else if (out_of_view(camera, world_plane, scene.convention)) {
      s.reason = "the surface is outside the main view volume";
    } else if (!result.ok()) {
      s.reason = reason_for(result.status, surface.kind);
    } else {
      s.render = true;
      s.projection = result.projection;
      s.properties =
          judge(camera.projection, s.plane_in_camera, scene.convention, result.projection);
      s.depth = depth_precision(camera.projection, result.projection, s.plane_in_camera,
                                scene.convention);
    }
    out.surfaces.push_back(std::move(s));
  }
  return out;
}

namespace {

std::string number(double x) {
  return protocol::format_number<double>(x);
}

std::string fixed2(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.2f", x);
  return buffer;
}

nlohmann::ordered_json matrix_json(const Matrix4<double>& m) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (int i = 0; i < 16; ++i) out.push_back(m(i / 4, i % 4));
  return out;
}

}  // namespace

std::string to_json(const SceneCheck& check) {
  using json = nlohmann::ordered_json;  // fields in the documented order; non-finite -> null
  json surfaces = json::array();
  for (const SurfaceCheck& s : check.surfaces) {
    json properties = json::object(), residuals = json::object();
    for (const properties::Finding& p : s.properties) {
      properties[p.kind] = p.holds;
      residuals[p.kind] = p.ratio;
    }
    surfaces.push_back({
        {"name", s.name},
        {"kind", s.kind == SurfaceKind::mirror ? "mirror" : "clip"},
        {"action", s.render ? "render" : "skip"},
        {"reason", s.render ? json(nullptr) : json(s.reason)},
        {"status", std::string(status_code(s.status))},
        {"view", matrix_json(s.view)},
        {"projection", s.projection ? matrix_json(*s.projection) : json(nullptr)},
        {"method", s.render ? json(std::string(method_name(s.method))) : json(nullptr)},
        {"properties", properties},
        {"residuals", residuals},
        {"max_depth", s.depth ? json(s.depth->far_depth) : json(nullptr)},
        {"depth_fraction", s.depth ? json(s.depth->fraction) : json(nullptr)},
        {"depth_bits_lost", s.depth ? json(s.depth->bits_lost) : json(nullptr)},
    });
  }
  const json out = {{"scene", check.scene},
                    {"convention", std::string(convention_name(check.convention))},
                    {"surfaces", surfaces}};
  return out.dump(-1, ' ', false, json::error_handler_t::replace);
}

namespace {

/// A name as printed in the table: control characters and DEL escaped (\n, \t, \x1b, ...), so a
/// name cannot move the cursor or forge rows.
std::string printable(std::string_view name) {
  std::string out;
  for (const char ch : name) {
    const auto byte = static_cast<unsigned char>(ch);
    if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\t') {
      out += "\\t";
    } else if (ch == '\r') {
      out += "\\r";
    } else if (ch == '\\') {
      out += "\\\\";
    } else if (byte < 0x20 || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace

std::string to_text(const SceneCheck& check) {
  std::ostringstream out;
  out << "scene " << printable(check.scene) << " (" << convention_name(check.convention) << ")\n\n";
  // The summary table, then the details of each rendered pass. The name column is as wide as the
  // longest name up to kNameColumn; a longer name has a line of its own above its row.
  constexpr std::size_t kNameColumn = 32;
  std::vector<std::string> names;
  std::size_t width = 7;
  for (const SurfaceCheck& s : check.surfaces) {
    names.push_back(printable(s.name));
    if (names.back().size() <= kNameColumn) width = std::max(width, names.back().size());
  }
  auto cell = [](std::string text, std::size_t w) {
    text.resize(std::max(w, text.size()), ' ');
    return text;
  };
  out << cell("surface", width) << "  kind    action  properties  depth bits lost  reason\n";
  for (std::size_t i = 0; i < check.surfaces.size(); ++i) {
    const SurfaceCheck& s = check.surfaces[i];
    const bool own_line = names[i].size() > width;
    if (own_line) out << names[i] << "\n";
    out << cell(own_line ? "" : names[i], width) << "  "
        << cell(s.kind == SurfaceKind::mirror ? "mirror" : "clip", 6) << "  "
        << cell(s.render ? "render" : "skip", 6) << "  "
        << cell(s.render ? (s.passes() ? "pass" : "FAIL") : "-", 10) << "  "
        << cell(s.depth ? fixed2(s.depth->bits_lost) : "-", 15) << "  " << s.reason << "\n";
  }
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    out << "\n"
        << printable(s.name) << " (" << (s.kind == SurfaceKind::mirror ? "mirror" : "clip")
        << "): ";
    out << "render, " << method_name(s.method) << " method, "
        << (s.passes() ? "every property holds" : "A PROPERTY FAILS") << "\n";
    out << "  view:       ";
    for (int i = 0; i < 4; ++i) {
      out << (i ? "              " : "") << "[";
      for (int j = 0; j < 4; ++j) out << (j ? ", " : "") << number(s.view(i, j));
      out << "]\n";
    }
    out << "  projection: ";
    for (int i = 0; i < 4; ++i) {
      out << (i ? "              " : "") << "[";
      for (int j = 0; j < 4; ++j) out << (j ? ", " : "") << number((*s.projection)(i, j));
      out << "]\n";
    }
    for (const properties::Finding& p : s.properties) {
      out << "  " << (p.holds ? "ok   " : "FAIL ") << p.kind;
      if (p.ratio > 0) out << "  (residual / bound " << number(p.ratio) << ")";
      out << "\n";
    }
    if (s.depth) {
      out << "  depth along the view axis: reaches " << number(s.depth->far_depth) << ", spans "
          << number(s.depth->fraction) << " of the range: " << number(s.depth->bits_lost)
          << " bits of a 24-bit buffer lost\n";
    } else {
      out << "  depth along the view axis: the axis does not pass through the kept region\n";
    }
  }
  return out.str();
}

}  // namespace oblique::scene
