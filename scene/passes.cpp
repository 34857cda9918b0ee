// oblique check's passes: for each surface (recursively through mirrors and portals, up to the
// scene's depth), render or skip with the reason, the pass camera's oblique projection, the
// properties that apply and the depth precision left.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "oblique/oracle/problem.h"
#include "oblique/scene/check.h"

namespace oblique::scene {

bool SurfaceCheck::properties_hold() const {
  for (const oracle::Finding& p : properties) {
    if (!p.holds) return false;
  }
  return true;
}

bool SurfaceCheck::passes() const {
  if (!properties_hold()) return false;
  for (const oracle::Finding& p : impl_findings) {
    if (!p.holds) return false;
  }
  for (const auto* list : {&consumers, &impl_consumers}) {
    for (const ConsumerResult& c : *list) {
      if (!c.holds()) return false;
    }
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
std::vector<oracle::Finding> judge(const Matrix4<double>& projection, const Vector4<double>& plane,
                                   Convention convention, const Matrix4<double>& result) {
  const oracle::Problem<double> problem(projection, plane, convention);
  cases::Checks checks;
  checks.every = true;
  return oracle::judge(problem, Answer<double>{Status::ok, result}, checks).checks;
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
      if (visible_passes_ >= kMaxPasses) {
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
      // The pass camera, as the scene's engine builds it: a mirror's flip in its view, or a
      // proper camera S V R (S = diag(-1, 1, 1, 1)) with the flip in its projection (P S: the same
      // image) or in the texture lookup.
      const Matrix4<double> flip = Vector4<double>(-1, 1, 1, 1).asDiagonal();
      s.camera_projection = parent.original;
      switch (surface.kind) {
        case SurfaceKind::mirror:
          s.view = mirror_view(parent.view, world_plane);
          if (scene_.mirror_flip != MirrorFlip::view) s.view = flip * s.view;
          if (scene_.mirror_flip == MirrorFlip::projection_x)
            s.camera_projection = parent.original * flip;
          break;
        case SurfaceKind::portal: s.view = parent.view * surface.portal_transform; break;
        case SurfaceKind::clip: s.view = parent.view; break;
      }
      // The kept side, in the pass camera's space: a portal keeps what is in front of the
      // linked portal (this portal's plane turned around, carried through the portal).
      const Vector4<double> kept_plane =
          surface.kind == SurfaceKind::portal
              ? portal_kept_plane(surface.portal_transform, world_plane)
              : world_plane;
      s.plane_in_camera = plane_in_camera(s.view, kept_plane);
      s.parent_view = parent.view;
      s.kept_plane = kept_plane;
      const ObliqueResult<double> result =
          apply<double>(s.camera_projection, s.plane_in_camera, scene_.convention);
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
      // The cap is on passes that can be seen: surfaces out of view are only listed while the
      // list has room, and never keep a visible one from being looked at.
      if (!visible || result.status == Status::camera_not_behind_plane) {
        if (out_.surfaces.size() >= kMaxPasses) {
          ++out_.unlisted;
          continue;
        }
      } else {
        ++visible_passes_;
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
        s.properties =
            judge(s.camera_projection, s.plane_in_camera, scene_.convention, result.projection);
        s.depth = depth_precision(s.camera_projection, result.projection, s.plane_in_camera,
                                  scene_.convention, scene_.depth_buffer);
        if (!scene_.consumers.empty())
          s.consumers = judge_consumers<double>(scene_, s, oracle::reference_consumers<double>());
      }
      // Beyond the depth limit only the passes that would have been rendered are listed.
      if (level > scene_.max_depth && s.reason.rfind("depth limit", 0) != 0) continue;
      const bool render = s.render;
      Through next{s.view, result.projection, s.camera_projection, scissor, s.path, s.name,
                   level,  kept_plane};
      out_.surfaces.push_back(std::move(s));
      if (render && surface.kind != SurfaceKind::clip) passes_through(next);
    }
  }

 private:
  std::size_t visible_passes_ = 0;  ///< passes looked at that the parent can see
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

}  // namespace oblique::scene
