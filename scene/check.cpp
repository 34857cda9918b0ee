#include "oblique/scene/check.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

#include "oblique/properties/properties.h"
#include "oblique/protocol/numbers.h"
#include "oblique/protocol/protocol.h"

namespace oblique::scene {

bool SurfaceCheck::properties_hold() const {
  for (const properties::Finding& p : properties) {
    if (!p.holds) return false;
  }
  return true;
}

bool SurfaceCheck::passes() const {
  if (!properties_hold()) return false;
  for (const properties::Finding& p : impl_findings) {
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
bool out_of_view(const Matrix4<double>& projection, const Matrix4<double>& view,
                 const Vector4<double>& world_plane, Convention convention) {
  const Matrix4<double> inverse = (projection * view).inverse();
  const DepthRange range = clip_depth_range(convention);
  const Vector4<double> eye = view.inverse() * Vector4<double>(0, 0, 0, 1);
  const double eye_side = world_plane.dot(eye);
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
             : kind == SurfaceKind::portal
                 ? "the camera is behind the surface (on the portal's back side)"
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
                                              const Vector4<double>& plane, Convention convention,
                                              DepthBuffer buffer) {
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
  d.buffer = buffer;
  if (buffer == DepthBuffer::fixed24) {
    d.bits_lost = d.fraction > 0 ? -std::log2(d.fraction) : INFINITY;
    return d;
  }
  // float32: count the representable values between the two window depths (for non-negative
  // floats the bit patterns are in the order of the values).
  auto index = [&](double z) {
    const double window =
        std::clamp((z - range.z_low) / double(range.z_high - range.z_low), 0.0, 1.0);
    const float f = static_cast<float>(window);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    return static_cast<double>(bits);
  };
  const double used = std::abs(index(to) - index(from));
  const double all = index(range.z_high) - index(range.z_low);
  d.bits_lost = used > 0 ? std::log2(all / used) : INFINITY;
  return d;
}

namespace {

/// Clips a convex or concave polygon (homogeneous clip coordinates) by a x + b y + c z + d w >= 0
/// (Sutherland-Hodgman).
std::vector<Vector4<double>> clip_by(const std::vector<Vector4<double>>& in,
                                     const Vector4<double>& plane) {
  std::vector<Vector4<double>> out;
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector4<double>& a = in[i];
    const Vector4<double>& b = in[(i + 1) % n];
    const double da = plane.dot(a), db = plane.dot(b);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out;
}

}  // namespace

std::optional<Scissor> clip_polygon(const std::vector<Vector3>& polygon,
                                    const Matrix4<double>& view, const Matrix4<double>& projection,
                                    Convention convention, const std::optional<Scissor>& within,
                                    const std::optional<std::array<int, 2>>& viewport) {
  const Matrix4<double> to_clip = projection * view;
  std::vector<Vector4<double>> points;
  for (const Vector3& v : polygon)
    points.push_back(to_clip * Vector4<double>(v.x(), v.y(), v.z(), 1));
  // The six planes of the view volume (depth: gl -w <= z <= w; zero_one and reversed_z
  // 0 <= z <= w), then the parent's rectangle.
  std::vector<Vector4<double>> planes = {
      {1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, -1, 1}};
  planes.push_back(convention == Convention::gl ? Vector4<double>(0, 0, 1, 1)
                                                : Vector4<double>(0, 0, 1, 0));
  if (within) {
    planes.push_back({1, 0, 0, -within->x0});
    planes.push_back({-1, 0, 0, within->x1});
    planes.push_back({0, 1, 0, -within->y0});
    planes.push_back({0, -1, 0, within->y1});
  }
  for (const Vector4<double>& plane : planes) {
    points = clip_by(points, plane);
    if (points.size() < 3) return std::nullopt;
  }
  std::vector<Eigen::Vector2d> ndc;
  for (const Vector4<double>& p : points) {
    if (!(p.w() > 0) || !p.allFinite()) continue;  // on the eye plane: no screen position
    ndc.emplace_back(p.x() / p.w(), p.y() / p.w());
  }
  if (ndc.size() < 3) return std::nullopt;
  Scissor s;
  s.x0 = s.y0 = INFINITY;
  s.x1 = s.y1 = -INFINITY;
  double twice_area = 0;
  for (std::size_t i = 0; i < ndc.size(); ++i) {
    const Eigen::Vector2d& a = ndc[i];
    const Eigen::Vector2d& b = ndc[(i + 1) % ndc.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
    s.x0 = std::min(s.x0, std::clamp(a.x(), -1.0, 1.0));
    s.x1 = std::max(s.x1, std::clamp(a.x(), -1.0, 1.0));
    s.y0 = std::min(s.y0, std::clamp(a.y(), -1.0, 1.0));
    s.y1 = std::max(s.y1, std::clamp(a.y(), -1.0, 1.0));
  }
  s.ndc_area = std::abs(twice_area) / 2;
  if (!(s.ndc_area > 0) || !std::isfinite(s.ndc_area)) return std::nullopt;  // edge-on
  if (viewport) {
    const double w = (*viewport)[0], h = (*viewport)[1];
    auto px = [](double ndc, double size, bool up) {
      const double x = (ndc + 1) / 2 * size;
      return static_cast<int>(std::clamp(up ? std::ceil(x) : std::floor(x), 0.0, size));
    };
    const int x0 = px(s.x0, w, false), x1 = px(s.x1, w, true);
    const int y0 = px(s.y0, h, false), y1 = px(s.y1, h, true);
    s.pixels = std::array<int, 4>{x0, y0, x1 - x0, y1 - y0};
    s.covered_pixels = std::min(s.ndc_area, 4.0) / 4 * w * h;
  }
  return s;
}

namespace {

/// A pass whose view others are seen through: the main camera (level 0) or a rendered pass.
struct Through {
  Matrix4<double> view;
  Matrix4<double> projection;  ///< what it renders with (the oblique matrix for a pass)
  Matrix4<double> original;    ///< the camera's own projection
  std::optional<Scissor> rectangle;
  std::vector<std::size_t> path;
  std::string name;
  int level = 0;
  /// The plane the pass is seen through, in its world (kept side positive); none for the main
  /// camera.
  std::optional<Vector4<double>> exit_plane;
};

/// Whether every vertex lies in the plane (within rounding of its coordinates).
bool in_plane(const std::vector<Vector3>& polygon, const Vector4<double>& plane) {
  const double n = plane.head<3>().norm();
  for (const Vector3& v : polygon) {
    if (!(std::abs(plane.head<3>().dot(v) + plane.w()) <= 1e-9 * n * (1 + v.norm()))) return false;
  }
  return true;
}

class Checker {
 public:
  Checker(const Scene& scene, SceneCheck& out) : scene_(scene), out_(out) {}

  void passes_through(const Through& parent) {
    const int level = parent.level + 1;
    for (std::size_t i = 0; i < scene_.surfaces.size(); ++i) {
      if (!parent.path.empty() && parent.path.back() == i) continue;  // not seen through itself
      if (out_.surfaces.size() >= kMaxPasses) {
        out_.truncated = true;
        return;
      }
      const Surface& surface = scene_.surfaces[i];
      SurfaceCheck s;
      s.name = parent.name.empty() ? surface.name : parent.name + " > " + surface.name;
      s.path = parent.path;
      s.path.push_back(i);
      s.level = level;
      s.kind = surface.kind;
      const Vector4<double> world_plane = surface.plane();
      switch (surface.kind) {
        case SurfaceKind::mirror: s.view = parent.view * reflection(world_plane); break;
        case SurfaceKind::portal: s.view = parent.view * surface.portal_transform; break;
        case SurfaceKind::clip: s.view = parent.view; break;
      }
      // The kept side, in the pass camera's space: a portal keeps what is in front of the
      // linked portal (this portal's plane turned around, carried through the portal).
      const Vector4<double> kept_plane =
          surface.kind == SurfaceKind::portal
              ? Vector4<double>(surface.portal_transform.transpose() * -world_plane)
              : world_plane;
      s.plane_in_camera = plane_in(s.view, kept_plane);
      const ObliqueResult<double> result =
          apply<double>(scene_.camera.projection, s.plane_in_camera, scene_.convention);
      s.status = result.status;
      s.method = result.method;
      // Visible through the parent: the polygon clipped by what the parent renders (and its
      // rectangle); an infinite plane by the corners of the parent camera's own volume.
      std::optional<Scissor> scissor;
      bool visible = false;
      if (surface.bounded()) {
        scissor = clip_polygon(surface.polygon, parent.view, parent.projection, scene_.convention,
                               parent.rectangle, scene_.viewport);
        // One in the plane the parent is seen through (a portal's own exit) is not seen.
        visible = scissor.has_value() &&
                  !(parent.exit_plane && in_plane(surface.polygon, *parent.exit_plane));
      } else {
        visible = !out_of_view(parent.original, parent.view, world_plane, scene_.convention);
      }
      if (result.status == Status::camera_not_behind_plane) {
        s.reason = reason_for(result.status, surface.kind);
      } else if (!visible) {
        s.reason = level == 1 ? "the surface is outside the main view volume"
                              : "not visible through its parent";
      } else if (!result.ok()) {
        s.reason = reason_for(result.status, surface.kind);
      } else if (level > scene_.max_depth) {
        s.reason = "depth limit (max_depth " + std::to_string(scene_.max_depth) + ")";
      } else {
        s.render = true;
        s.projection = result.projection;
        s.scissor = scissor;
        s.properties = judge(scene_.camera.projection, s.plane_in_camera, scene_.convention,
                             result.projection);
        s.depth = depth_precision(scene_.camera.projection, result.projection, s.plane_in_camera,
                                  scene_.convention, scene_.depth_buffer);
      }
      // Beyond the depth limit only the passes that would have been rendered are listed.
      if (level > scene_.max_depth && s.reason.rfind("depth limit", 0) != 0) continue;
      const bool render = s.render;
      Through next{s.view, result.projection, scene_.camera.projection, scissor, s.path, s.name,
                   level,  kept_plane};
      out_.surfaces.push_back(std::move(s));
      if (render && surface.kind != SurfaceKind::clip) passes_through(next);
    }
  }

 private:
  const Scene& scene_;
  SceneCheck& out_;
};

}  // namespace

SceneCheck check_scene(const Scene& scene) {
  SceneCheck out;
  out.scene = scene.name;
  out.convention = scene.convention;
  out.depth_buffer = scene.depth_buffer;
  out.max_depth = scene.max_depth;
  const Camera& camera = scene.camera;
  Checker(scene, out)
      .passes_through(Through{camera.view,
                              camera.projection,
                              camera.projection,
                              std::nullopt,
                              {},
                              "",
                              0,
                              std::nullopt});
  return out;
}

namespace {

/// The request's M and C in T (Eigen's cast: IEEE rounding, an infinity beyond T's range).
template <class T>
Matrix4<T> request_projection(const Scene& scene) {
  static_assert(std::numeric_limits<T>::is_iec559);
  return scene.camera.projection.template cast<T>();
}
template <class T>
Vector4<T> request_plane(const SurfaceCheck& pass) {
  return pass.plane_in_camera.template cast<T>();
}

template <class T>
void judge_answer_in(const Scene& scene, SurfaceCheck& pass, const std::string& line) {
  pass.impl_answer = line;
  pass.impl_findings.clear();
  auto protocol_error = [&](const std::string& why) {
    properties::Finding f;
    f.kind = "protocol";
    f.relation = "the answer is a protocol answer line";
    f.lhs = why;
    f.rhs = "{\"status\": ..., \"projection\": [16 numbers]}";
    f.ratio = 1e300;
    pass.impl_findings.push_back(f);
  };
  const protocol::ParsedAnswer parsed = protocol::parse_answer(line);
  if (!parsed.valid) return protocol_error(parsed.error);
  const std::optional<Status> status = parse_status(parsed.status);
  if (!status) return protocol_error("unknown status \"" + parsed.status + "\"");
  properties::Outcome<T> outcome{*status, Matrix4<T>::Zero()};
  if (*status == Status::ok) {
    if (!parsed.projection) return protocol_error("an ok answer without a projection");
    for (int i = 0; i < 16; ++i) {
      const std::string& token = (*parsed.projection)[static_cast<std::size_t>(i)];
      std::string why;
      std::optional<T> value = protocol::parse_number<T>(token, &why);
      if (!value) {  // beyond T's range: an infinite entry to judge (as verify does)
        std::string wide_why;
        if (const auto wide = protocol::parse_number<long double>(token, &wide_why))
          value =
              *wide < 0 ? -std::numeric_limits<T>::infinity() : std::numeric_limits<T>::infinity();
      }
      if (!value) return protocol_error("projection[" + std::to_string(i) + "]: " + why);
      outcome.projection(i / 4, i % 4) = *value;
    }
  }
  const properties::Problem<T> problem(request_projection<T>(scene), request_plane<T>(pass),
                                       scene.convention);
  properties::Checks checks;
  checks.statuses = properties::StatusContract::any_refusal;
  checks.row3_accuracy = true;
  // As verify: the judgement stops at the first violation (every = true would go on to the
  // properties after a non-finite answer, whose exact arithmetic cannot take infinities).
  pass.impl_findings = properties::judge(problem, outcome, checks).checks;
}

}  // namespace

std::string impl_request(const Scene& scene, const SurfaceCheck& pass,
                         protocol::Precision precision) {
  switch (precision) {
    case protocol::Precision::float32:
      return protocol::request_line<float>(request_projection<float>(scene),
                                           request_plane<float>(pass), scene.convention);
    case protocol::Precision::float64: break;
    case protocol::Precision::long_double:
      return protocol::request_line<long double>(request_projection<long double>(scene),
                                                 request_plane<long double>(pass),
                                                 scene.convention);
  }
  return protocol::request_line<double>(request_projection<double>(scene),
                                        request_plane<double>(pass), scene.convention);
}

void judge_impl_answer(const Scene& scene, SurfaceCheck& pass, const std::string& line,
                       protocol::Precision precision) {
  switch (precision) {
    case protocol::Precision::float32: return judge_answer_in<float>(scene, pass, line);
    case protocol::Precision::float64: return judge_answer_in<double>(scene, pass, line);
    case protocol::Precision::long_double: return judge_answer_in<long double>(scene, pass, line);
  }
}

namespace {

std::string number(double x) {
  return protocol::format_number<double>(x);
}

const char* kind_name(SurfaceKind k) {
  switch (k) {
    case SurfaceKind::mirror: return "mirror";
    case SurfaceKind::clip: return "clip";
    case SurfaceKind::portal: return "portal";
  }
  return "?";
}

const char* buffer_name(DepthBuffer b) {
  return b == DepthBuffer::fixed24 ? "fixed24" : "float32";
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
        {"kind", kind_name(s.kind)},
        {"path", s.path},
        {"level", s.level},
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
        {"scissor_ndc", s.scissor
                            ? json({s.scissor->x0, s.scissor->y0, s.scissor->x1, s.scissor->y1})
                            : json(nullptr)},
        {"scissor_pixels",
         s.scissor && s.scissor->pixels ? json(*s.scissor->pixels) : json(nullptr)},
        {"covered_pixels",
         s.scissor && s.scissor->covered_pixels ? json(*s.scissor->covered_pixels) : json(nullptr)},
    });
    if (s.impl_answer) {
      json findings = json::array();
      for (const properties::Finding& f : s.impl_findings)
        findings.push_back({{"property", f.kind},
                            {"holds", f.holds},
                            {"relation", f.relation},
                            {"residual", f.lhs},
                            {"bound", f.rhs}});
      surfaces.back()["impl"] = {
          {"answer", *s.impl_answer},
          {"precision", std::string(protocol::precision_name(check.impl_precision))},
          {"findings", findings}};
    }
  }
  const json out = {{"scene", check.scene},
                    {"convention", std::string(convention_name(check.convention))},
                    {"depth_buffer", buffer_name(check.depth_buffer)},
                    {"max_depth", check.max_depth},
                    {"truncated", check.truncated},
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
  out << "scene " << printable(check.scene) << " (" << convention_name(check.convention) << ", "
      << buffer_name(check.depth_buffer) << " depth buffer, max_depth " << check.max_depth
      << ")\n\n";
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
    out << cell(own_line ? "" : names[i], width) << "  " << cell(kind_name(s.kind), 6) << "  "
        << cell(s.render ? "render" : "skip", 6) << "  "
        << cell(s.render ? (s.properties_hold() ? "pass" : "FAIL") : "-", 10) << "  "
        << cell(s.depth ? fixed2(s.depth->bits_lost) : "-", 15) << "  " << s.reason << "\n";
  }
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    out << "\n" << printable(s.name) << " (" << kind_name(s.kind) << "): ";
    out << "render, " << method_name(s.method) << " method, "
        << (s.properties_hold() ? "every property holds" : "A PROPERTY FAILS") << "\n";
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
          << " bits of the "
          << (s.depth->buffer == DepthBuffer::fixed24 ? "24-bit fixed-point" : "32-bit float")
          << " buffer lost\n";
    } else {
      out << "  depth along the view axis: the axis does not pass through the kept region\n";
    }
    if (s.scissor) {
      out << "  scissor (NDC): [" << number(s.scissor->x0) << ", " << number(s.scissor->x1)
          << "] x [" << number(s.scissor->y0) << ", " << number(s.scissor->y1) << "]";
      if (s.scissor->pixels) {
        const auto& px = *s.scissor->pixels;
        out << "; pixels x " << px[0] << ", y " << px[1] << ", " << px[2] << " x " << px[3] << " ("
            << static_cast<long long>(px[2]) * px[3] << " pixels), the surface covers "
            << number(std::round(*s.scissor->covered_pixels)) << " pixels";
      }
      out << "\n";
    }
  }
  bool any_impl = false;
  for (const SurfaceCheck& s : check.surfaces) any_impl = any_impl || s.impl_answer.has_value();
  if (any_impl) {
    out << "\nthe implementation's answers (--impl), judged as oblique verify --precision "
        << protocol::precision_name(check.impl_precision) << " judges:\n";
    for (const SurfaceCheck& s : check.surfaces) {
      if (!s.impl_answer) continue;
      bool holds = true;
      for (const properties::Finding& f : s.impl_findings) holds = holds && f.holds;
      out << "  " << printable(s.name) << ": " << (holds ? "pass" : "FAIL") << "\n";
      for (const properties::Finding& f : s.impl_findings) {
        if (f.holds) continue;
        out << "    FAIL " << f.kind << ": " << f.relation << "\n      " << printable(f.lhs)
            << "\n      bound: " << printable(f.rhs) << "\n";
      }
    }
  }
  if (check.truncated)
    out << "\nmore than " << kMaxPasses << " passes: the rest were not looked at\n";
  return out.str();
}

}  // namespace oblique::scene
