// `oblique check`: for each surface of a scene, decide whether its pass is rendered or skipped
// (from the core's statuses and the main camera's view volume), and for rendered passes give the
// pass camera's view and oblique projection, the properties that apply to it with their
// residuals, and the depth precision left along the view axis.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/properties/judge.h"
#include "oblique/scene/scene.h"

namespace oblique::scene {

/// Depth along the pass camera's view axis, from where it enters the kept region to where it
/// leaves the view volume (the paper's Eq. 19, for any matrix and convention).
struct DepthPrecision {
  double far_depth = 0;  ///< NDC depth at the far end of the kept part of the axis
  double fraction = 0;   ///< of the depth range [z_low, z_high] that the axis still spans
  double bits_lost = 0;  ///< log2(1 / fraction): bits of a fixed-point depth buffer not used
};

struct SurfaceCheck {
  std::string name;
  SurfaceKind kind = SurfaceKind::mirror;
  bool render = false;
  std::string reason;               ///< why it is skipped (empty when rendered)
  Status status = Status::ok;       ///< what the core answered (ok when it was not asked)
  Matrix4<double> view;             ///< world -> pass camera (mirrors: main view x reflection)
  Vector4<double> plane_in_camera;  ///< the surface plane in the pass camera's space
  std::optional<Matrix4<double>> projection;  ///< the oblique projection, when rendered
  Method method = Method::automatic;
  /// The properties that apply to its camera and convention, judged (properties::judge()).
  std::vector<properties::Finding> properties;
  std::optional<DepthPrecision> depth;

  bool passes() const;
};

struct SceneCheck {
  std::string scene;
  Convention convention = Convention::gl;
  std::vector<SurfaceCheck> surfaces;
  bool passes() const;
};

SceneCheck check_scene(const Scene& scene);

/// {"scene": ..., "surfaces": [{"name", "action", "reason", "view", "projection", "method",
/// "properties": {name: bool}, "depth_bits_lost", ...}]}; numbers round-trip.
std::string to_json(const SceneCheck& check);

/// A table a person reads.
std::string to_text(const SceneCheck& check);

/// Depth precision of `oblique` (the oblique version of `original`) along the view axis.
std::optional<DepthPrecision> depth_precision(const Matrix4<double>& original,
                                              const Matrix4<double>& oblique,
                                              const Vector4<double>& plane, Convention convention);

}  // namespace oblique::scene
