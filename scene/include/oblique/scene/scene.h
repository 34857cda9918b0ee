// Scene files for `oblique check`: a camera (projection and gluLookAt view) and the surfaces that
// need an oblique pass (mirrors, clip planes), read from JSON with errors that name the field, or
// the line and column of malformed JSON.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"

namespace oblique::scene {

using Vector3 = Eigen::Vector3d;

enum class ProjectionType { perspective, infinite, frustum, orthographic, matrix };

struct Camera {
  ProjectionType type = ProjectionType::perspective;
  Matrix4<double> projection = Matrix4<double>::Identity();  ///< built in the scene's convention
  Vector3 eye = Vector3::Zero(), target = -Vector3::UnitZ(), up = Vector3::UnitY();
  Matrix4<double> view = Matrix4<double>::Identity();  ///< world -> camera, as gluLookAt builds it
};

enum class SurfaceKind { mirror, clip };

struct Surface {
  std::string name;
  SurfaceKind kind = SurfaceKind::mirror;
  Vector3 normal = Vector3::UnitY();  ///< toward the front: the side that is seen and kept
  Vector3 point = Vector3::Zero();
  /// The world-space plane (n, -n . p), positive in front.
  Vector4<double> plane() const;
};

struct Scene {
  std::string name;
  Convention convention = Convention::gl;
  Camera camera;
  std::vector<Surface> surfaces;
};

/// A scene, or why the text is not one (naming the field, or the line and column).
struct ParsedScene {
  std::optional<Scene> scene;
  std::string error;
};

/// Every failure names the field (numbers beyond double's range, degenerate cameras whose view
/// volume has no finite corners in double, a normal or up vector of zero length) or the position.
/// Directions (up, normals) are judged by direction, whatever their length.
ParsedScene parse_scene(std::string_view text);

/// The most a scene file may hold: bytes, and numbers.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxSceneNumbers = std::size_t{1} << 20;

/// parse_scene() of a file's text; a file that cannot be opened or read, a directory, or one
/// larger than kMaxSceneBytes (read no further: /dev/zero) is refused with its reason.
ParsedScene read_scene_file(const std::string& path);

/// gluLookAt's view matrix; empty when eye = target or up is parallel to the view direction.
std::optional<Matrix4<double>> look_at(const Vector3& eye, const Vector3& target,
                                       const Vector3& up);

/// The reflection through a world-space plane (n, d): p -> p - 2 (n . p + d) n / |n|^2.
Matrix4<double> reflection(const Vector4<double>& plane);

}  // namespace oblique::scene
