// Scene files for `oblique check`: a camera as engines hold it (a view matrix in a named layout,
// eye/target/up, or position + quaternion; a field of view with its unit in the key, frustum
// bounds or a matrix; y-flip, reversed Z, infinite far) and the surfaces that need an oblique pass
// (mirrors, clip planes, portals), bounded (a polygon or a rectangle) or infinite (a plane), read
// from JSON with errors that name the field, or the line and column of malformed JSON. Unknown
// keys are refused with their path.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/oracle/consumers.h"
#include "oblique/plane.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/references/pass_camera.h"
#include "oblique/util/enum_names.h"

namespace oblique::scene {

using Vector3 = Eigen::Vector3d;

enum class ProjectionType { perspective, infinite, frustum, orthographic, matrix };

// (The depth buffer's format, DepthBuffer: the core's oblique/references/depth_reconstruction.h.)

struct Camera {
  ProjectionType type = ProjectionType::perspective;
  Matrix4<double> projection = Matrix4<double>::Identity();  ///< built in the scene's convention
  /// eye/target/up as given (eye/target/up views), else the eye from the view matrix, target one
  /// unit along the view direction and up its up vector.
  Vector3 eye = Vector3::Zero(), target = -Vector3::UnitZ(), up = Vector3::UnitY();
  Matrix4<double> view = Matrix4<double>::Identity();  ///< world -> camera
};

enum class SurfaceKind { mirror, clip, portal };

/// A surface's "kind" in a scene file.
inline constexpr EnumName<SurfaceKind> surface_kind_names[] = {
    {SurfaceKind::mirror, "mirror"},
    {SurfaceKind::clip, "clip"},
    {SurfaceKind::portal, "portal"},
};
constexpr std::string_view surface_kind_name(SurfaceKind kind) noexcept {
  return name_in(surface_kind_names, kind);
}

struct Surface {
  std::string name;
  SurfaceKind kind = SurfaceKind::mirror;
  Vector3 normal = Vector3::UnitY();  ///< toward the front: the side that is seen and kept
  Vector3 point = Vector3::Zero();
  /// The bounded surface, counter-clockwise seen from its front; empty for an infinite plane.
  std::vector<Vector3> polygon;
  /// Portals: world -> world, from around the linked portal to behind this one (rectangle frame
  /// x (rotation by 180 degrees about up) x linked frame^-1); identity otherwise.
  Matrix4<double> portal_transform = Matrix4<double>::Identity();
  /// Portals: this portal's frame and the linked one's (columns right, up, normal, centre), from
  /// which portal_transform is made.
  Matrix4<double> portal_frame = Matrix4<double>::Identity(),
                  linked_frame = Matrix4<double>::Identity();
  /// The world-space plane (n, -n . p), positive in front.
  Vector4<double> plane() const;
  bool bounded() const { return !polygon.empty(); }
};

/// The code around the matrix a scene's passes have, checked by `oblique check` (the consumer
/// properties, docs/consumers.md): reconstruction (view position and linear depth from the depth
/// buffer), culling (planes extracted from the pass's matrix), cascades (corners of its volume),
/// camera_plane (the surface's plane in the pass camera's space) and pass_view (the mirror's or
/// portal's view).
enum class SceneConsumer { reconstruction, culling, cascades, camera_plane, pass_view };

inline constexpr EnumName<SceneConsumer> scene_consumer_names[] = {
    {SceneConsumer::reconstruction, "reconstruction"},
    {SceneConsumer::culling, "culling"},
    {SceneConsumer::cascades, "cascades"},
    {SceneConsumer::camera_plane, "camera_plane"},
    {SceneConsumer::pass_view, "pass_view"},
};
inline constexpr auto all_scene_consumers = values_in(scene_consumer_names);
constexpr std::string_view scene_consumer_name(SceneConsumer value) noexcept {
  return name_in(scene_consumer_names, value);
}
/// Inverse of scene_consumer_name(); none for an unknown name.
constexpr std::optional<SceneConsumer> parse_scene_consumer(std::string_view name) noexcept {
  return value_in(scene_consumer_names, name);
}

/// Where a mirror pass puts the mirror's flip, as the scene's engine builds the pass
/// ("mirror_flip"): in the view (main view times the reflection: an improper camera, its winding
/// flipped), or a proper camera diag(-1, 1, 1, 1) V R whose horizontal flip is done in the
/// projection (M11 negated: the pass asks the oblique function about M diag(-1, 1, 1, 1)) or in
/// the texture lookup (the projection as it is).
enum class MirrorFlip { view, projection_x, texture };

inline constexpr EnumName<MirrorFlip> mirror_flip_names[] = {
    {MirrorFlip::view, "view"},
    {MirrorFlip::projection_x, "projection_x"},
    {MirrorFlip::texture, "texture"},
};
constexpr std::string_view mirror_flip_name(MirrorFlip value) noexcept {
  return name_in(mirror_flip_names, value);
}
constexpr std::optional<MirrorFlip> parse_mirror_flip(std::string_view name) noexcept {
  return value_in(mirror_flip_names, name);
}

struct Scene {
  std::string name;
  Convention convention = Convention::gl;
  DepthBuffer depth_buffer = DepthBuffer::fixed24;
  Camera camera;
  std::vector<Surface> surfaces;
  int max_depth = 1;  ///< passes seen through passes, up to this many levels
  std::optional<std::array<int, 2>> viewport;  ///< width, height in pixels
  /// What each rendered pass feeds its matrix to ("consumers"): only these are checked.
  std::vector<SceneConsumer> consumers;
  /// How the engine builds a mirror pass's camera ("mirror_design": reflected_view, the default,
  /// or proper_camera): what `check --impl` judges the program's mirror_view by.
  oracle::MirrorDesign mirror_design = oracle::MirrorDesign::reflected_view;
  /// Where its mirror passes put the flip ("mirror_flip"); a flip outside the view makes the
  /// design proper_camera, and a proper_camera design without it flips in the projection.
  MirrorFlip mirror_flip = MirrorFlip::view;
};

/// A scene, or why the text is not one (naming the field, or the line and column).
struct ParsedScene {
  std::optional<Scene> scene;
  std::string error;
  /// What is accepted but likely a mistake, each naming its field ("camera.projection.fovy_deg:
  /// 1.22 degrees is a very narrow view; if it is in radians ...").
  std::vector<std::string> warnings;
};

/// Every failure names the field (numbers beyond double's range, degenerate cameras whose view
/// volume has no finite corners in double, a normal or up vector of zero length, an unknown key)
/// or the position. Directions (up, normals, quaternions) are judged by direction, whatever their
/// length.
ParsedScene parse_scene(std::string_view text);

/// The most a scene file may hold: bytes, and numbers.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxSceneNumbers = std::size_t{1} << 20;
/// The deepest recursion a scene may ask for, and the most vertices a polygon may have.
inline constexpr int kMaxDepth = 8;
inline constexpr std::size_t kMaxPolygonVertices = 64;

/// parse_scene() of a file's text; a file that cannot be opened or read, a directory, or one
/// larger than kMaxSceneBytes (read no further: /dev/zero) is refused with its reason.
ParsedScene read_scene_file(const std::string& path);

/// gluLookAt's view matrix; empty when eye = target or up is parallel to the view direction.
std::optional<Matrix4<double>> look_at(const Vector3& eye, const Vector3& target,
                                       const Vector3& up);

// (A mirror's reflection, a portal's map and the plane in a pass camera's space: the core's
// oblique/references/pass_camera.h.)

/// The frame (columns right = up x normal, up, normal, center) of a rectangle; empty when up is
/// parallel to the normal.
std::optional<Matrix4<double>> rectangle_frame(const Vector3& center, const Vector3& normal,
                                               const Vector3& up);

}  // namespace oblique::scene
