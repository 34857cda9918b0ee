// `oblique check`: for each surface of a scene, decide whether its pass is rendered or skipped
// (from the core's statuses and the main camera's view volume), and for rendered passes give the
// pass camera's view and oblique projection, the properties that apply to it with their
// residuals, and the depth precision left along the view axis.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oblique/expected.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/oracle/judge.h"
#include "oblique/protocol/matrix_order.h"
#include "oblique/protocol/numbers.h"
#include "oblique/scene/scene.h"

namespace oblique::scene {

/// Depth along the pass camera's view axis, from where it enters the kept region to where it
/// leaves the view volume (the paper's Eq. 19, for any matrix and convention).
struct DepthPrecision {
  double far_depth = 0;  ///< NDC depth at the far end of the kept part of the axis
  double fraction = 0;   ///< of the depth range [z_low, z_high] that the axis still spans
  /// log2(values of the buffer / values the axis still spans): for fixed24, log2(1 / fraction);
  /// for float32, the float32 values between the window depths (z - z_low) / (z_high - z_low)
  /// of the axis's two ends, against those in [0, 1].
  double bits_lost = 0;
  DepthBuffer buffer = DepthBuffer::fixed24;
};

/// The screen rectangle a visible bounded surface covers (the scissor an engine sets), from its
/// polygon clipped against the parent pass's view volume (and the parent's own rectangle).
struct Scissor {
  double x0 = -1, y0 = -1, x1 = 1, y1 = 1;  ///< NDC
  double ndc_area = 0;                      ///< of the clipped polygon, in NDC units (4 = all)
  /// With the scene's viewport: pixels x from the left, y from the edge where NDC y = -1 (the
  /// bottom in GL, the top with a y-flipped projection); outward-rounded, clamped.
  std::optional<std::array<int, 4>> pixels;  ///< x, y, width, height
  std::optional<double> covered_pixels;      ///< the polygon's own area in pixels
};

/// One consumer of a rendered pass (Scene::consumers), asked and judged by its properties
/// (oblique/oracle/consumers.h).
struct ConsumerResult {
  SceneConsumer consumer = SceneConsumer::reconstruction;
  long judged = 0;  ///< answers judged
  /// Cases no implementation in the precision can settle (not judged), by why.
  std::map<std::string, long> left_out_why;
  long left_out() const {
    long n = 0;
    for (const auto& [why, count] : left_out_why) n += count;
    return n;
  }
  std::string note;  ///< why nothing applies (a clip pass has no view of its own), else empty
  std::optional<oracle::ConsumerFinding> violation;  ///< the first
  std::string inputs;                                ///< the violation's inputs (a Markdown list)
  double worst_ratio = 0;                            ///< the largest residual / bound judged
  double depth_waste = 0;  ///< cascades: how much deeper the corners reach than the kept region
  bool holds() const { return !violation; }
};

struct SurfaceCheck {
  std::string name;               ///< the pass's path: "hall mirror > window"
  std::vector<std::size_t> path;  ///< indices into Scene::surfaces, outermost first
  int level = 1;                  ///< 1 for a pass the main camera sees
  SurfaceKind kind = SurfaceKind::mirror;
  bool render = false;
  std::string reason;          ///< why it is skipped (empty when rendered)
  Status status = Status::ok;  ///< what the core answered (ok when it was not asked)
  Matrix4<double> view;        ///< world -> pass camera (mirrors: main view x reflection)
  /// The pass camera's own projection, before the oblique modification: the scene camera's, its
  /// x negated on a mirror pass whose flip is in the projection (mirror_flip projection_x).
  Matrix4<double> camera_projection = Matrix4<double>::Identity();
  Vector4<double> plane_in_camera;            ///< the surface plane in the pass camera's space
  std::optional<Matrix4<double>> projection;  ///< the oblique projection, when rendered
  Method method = Method::automatic;
  /// The properties that apply to its camera and convention, judged (oracle::judge()).
  std::vector<oracle::Finding> properties;
  std::optional<DepthPrecision> depth;
  std::optional<Scissor> scissor;  ///< rendered bounded surfaces

  /// What the pass is seen from and keeps, for its consumers: the parent pass's (or the main
  /// camera's) view, and the world plane whose front it keeps.
  Matrix4<double> parent_view = Matrix4<double>::Identity();
  Vector4<double> kept_plane = Vector4<double>::Zero();
  /// The scene's consumers with the core's references (what a right implementation gives).
  std::vector<ConsumerResult> consumers;
  /// `--impl`: the same asked of the user's program.
  std::vector<ConsumerResult> impl_consumers;

  /// `--impl`: the user's answer to this pass's request, judged (empty when not asked).
  std::optional<std::string> impl_answer;
  std::vector<oracle::Finding> impl_findings;

  /// Every property of our oblique matrix holds.
  bool properties_hold() const;
  /// properties_hold(), and the user's answer and consumers (when asked) violate nothing.
  bool passes() const;
};

struct SceneCheck {
  std::string scene;
  Convention convention = Convention::gl;
  DepthBuffer depth_buffer = DepthBuffer::fixed24;
  int max_depth = 1;
  std::vector<SurfaceCheck> surfaces;  ///< every pass, depth first: a pass, then those within it
  bool truncated = false;              ///< more than kMaxPasses passes: the rest not looked at
  std::size_t unlisted = 0;  ///< surfaces out of view not listed (the list was full): not passes
  /// `--impl --precision`: the scalar type of the requests sent and of the bounds the answers
  /// are judged with (as `oblique verify --precision`).
  protocol::Precision impl_precision = protocol::Precision::float64;
  /// `--layout`: how the program takes and writes its matrices (its requests put in that order).
  protocol::MatrixOrder impl_order = protocol::MatrixOrder::rows;
  /// `--shader FILE[:FUNCTION]`: the shader whose depth functions answered impl_consumers (in
  /// float, on the GPU path); empty: --impl's program did.
  std::string impl_shader;
  /// `--impl`: which known mistake explains its answers (all the passes' cases; ran only when
  /// one is wrong).
  mistakes::Diagnosis impl_diagnosis;
  bool passes() const;
};

inline constexpr std::size_t kMaxPasses = 512;

SceneCheck check_scene(const Scene& scene);

/// The request line `oblique check --impl` sends for a rendered pass (the protocol's writer): the
/// scene camera's projection and the pass's plane rounded to `precision` (IEEE: a value beyond
/// its range becomes an infinity, which the implementation should refuse).
std::string impl_request(const Scene& scene, const SurfaceCheck& pass,
                         protocol::Precision precision = protocol::Precision::float64);

/// Judges the user's answer line to impl_request(scene, pass, precision) as `oblique verify
/// --precision` does: the problem is the request's rounded M and C, the bounds those of
/// `precision` (StatusContract::any_refusal, row 3's accuracy; the checks up to the first
/// violation); a line that is not an answer is one failing finding "protocol". Stores them in
/// pass.impl_findings.
void judge_impl_answer(const Scene& scene, SurfaceCheck& pass, const std::string& line,
                       protocol::Precision precision = protocol::Precision::float64);

/// `oblique check --impl`: starts `command` (run by /bin/sh), sends it every rendered pass's
/// request (in check.impl_precision), and judges each answer (judge_impl_answer()). The number of
/// passes judged, or why none were: the program could not be started, or did not answer every
/// request within 4 x `timeout_seconds` (what it wrote on standard error included).
Expected<std::size_t> judge_implementation(const Scene& scene, SceneCheck& check,
                                           const std::string& command, double timeout_seconds);

/// {"scene": ..., "surfaces": [{"name", "action", "reason", "view", "projection", "method",
/// "properties": {name: bool}, "depth_bits_lost", ...}]}; numbers round-trip.
std::string to_json(const SceneCheck& check);

/// Each consumer the scene names, for a rendered pass, asked of `who` in T (M and C rounded to T)
/// and judged: reconstruction on kConsumerSamples depth samples of the pass's kept region, culling
/// and cascades on the pass's matrix (the consumer round every tool shares), camera_plane and
/// pass_view on the pass's own views and plane. Throws what `who` throws (a program's failure).
template <class T>
std::vector<ConsumerResult> judge_consumers(const Scene& scene, const SurfaceCheck& pass,
                                            const Consumers<T>& who);

inline constexpr int kConsumerSamples = 64;

/// `oblique check --impl` on a scene with consumers: the user's program (`command`, a new process)
/// asked the consumer request kinds of every rendered pass in check.impl_precision, stored in
/// impl_consumers, its depth consumers at `sampling`'s positions. Fails, saying why, when the
/// program does not answer as the protocol says.
Expected<Done> judge_implementation_consumers(const Scene& scene, SceneCheck& check,
                                              const std::string& command, double timeout_seconds,
                                              oracle::Sampling sampling = oracle::Sampling::pixels);

/// `oblique check --shader`: the scene's reconstruction consumer answered by a shader's depth
/// functions (`shader`, a Consumers<float> of oblique::shader, judged with the GPU's arithmetic)
/// on every rendered pass, stored in impl_consumers. Fails, saying why, where the scene names no
/// reconstruction consumer, or the shader cannot be run.
Expected<Done> judge_shader_consumers(const Scene& scene, SceneCheck& check,
                                      const Consumers<float>& shader);

/// The scene as --shader checks it: its consumers only the reconstruction one.
Scene reconstruction_only(const Scene& scene);

/// What a check judged of the consumers the scene names (its claims about the engine), over every
/// rendered pass: the implementation's (`impl`, with --impl) or the core's references.
struct ConsumerCoverage {
  /// One line per named consumer of which nothing was judged: why (no pass rendered, none it
  /// applies to, every answer left out and why) and what to change.
  std::vector<std::string> unjudged;
  /// "NAME L of D, ..." for the consumers with more than run::kLeftOutWarning of their answers left
  /// out (a single one is no pattern); empty when none.
  std::string partly;
};
ConsumerCoverage consumer_coverage(const Scene& scene, const SceneCheck& check, bool impl);

/// A table a person reads.
std::string to_text(const SceneCheck& check);

/// Depth precision of `oblique` (the oblique version of `original`) along the view axis.
std::optional<DepthPrecision> depth_precision(const Matrix4<double>& original,
                                              const Matrix4<double>& oblique,
                                              const Vector4<double>& plane, Convention convention,
                                              DepthBuffer buffer = DepthBuffer::fixed24);

/// The polygon (world space) clipped against the view volume of `projection` x `view` and, when
/// given, the NDC rectangle `within`: empty when nothing of it is left (homogeneous clipping
/// against each plane, as a GPU clips).
std::optional<Scissor> clip_polygon(const std::vector<Vector3>& polygon,
                                    const Matrix4<double>& view, const Matrix4<double>& projection,
                                    Convention convention, const std::optional<Scissor>& within,
                                    const std::optional<std::array<int, 2>>& viewport);

}  // namespace oblique::scene
