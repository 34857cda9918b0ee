// The properties of the code around the oblique matrix ("consumers"): depth reconstruction,
// culling planes, the pass camera and its plane, and a view volume's corners. Each judge takes the
// inputs as the consumer got them (in T) and its answer, and decides in exact rational arithmetic
// against the bounds of tolerance.h. The references are the core's (depth_reconstruction.h,
// frustum_planes.h, pass_camera.h, kept_region.h); docs/consumers.md has the formulas.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/protocol/consumer_messages.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/references/frustum_planes.h"
#include "oblique/util/enum_names.h"

namespace oblique::oracle {

/// The consumer properties, each of which alone rejects its class of wrong answers.
enum class ConsumerCheck {
  view_position,          ///< the reconstructed point is the pixel's point within the buffer's
                          ///< quantisation and the solve's rounding
  linear_depth,           ///< the same, for its distance along the view axis
  world_position,         ///< the same, for the point in world space (the pass camera's view)
  culling_keeps_visible,  ///< no vertex of the kept region is outside an extracted plane
  culling_near_is_c,      ///< the extracted near plane is C up to a positive scale
  plane_on_surface,       ///< world points of the surface lie on the camera-space plane
  plane_kept_side,        ///< the camera-space plane keeps the surface's front
  mirror_view,            ///< the mirror pass's view is the main view times the reflection
  portal_view,            ///< the portal pass's view is the main view times the portal's map
  corners_contain_kept,   ///< the corners' convex hull contains the kept region
};

inline constexpr EnumName<ConsumerCheck> consumer_check_names[] = {
    {ConsumerCheck::view_position, "view_position"},
    {ConsumerCheck::linear_depth, "linear_depth"},
    {ConsumerCheck::world_position, "world_position"},
    {ConsumerCheck::culling_keeps_visible, "culling_keeps_visible"},
    {ConsumerCheck::culling_near_is_c, "culling_near_is_c"},
    {ConsumerCheck::plane_on_surface, "plane_on_surface"},
    {ConsumerCheck::plane_kept_side, "plane_kept_side"},
    {ConsumerCheck::mirror_view, "mirror_view"},
    {ConsumerCheck::portal_view, "portal_view"},
    {ConsumerCheck::corners_contain_kept, "corners_contain_kept"},
};
inline constexpr auto all_consumer_checks = values_in(consumer_check_names);

constexpr std::string_view consumer_check_name(ConsumerCheck check) noexcept {
  return name_in(consumer_check_names, check);
}
/// Inverse of consumer_check_name(); none for an unknown name.
constexpr std::optional<ConsumerCheck> parse_consumer_check(std::string_view name) noexcept {
  return value_in(consumer_check_names, name);
}

/// Why `check` has nothing to judge on the matrices of `family`, or "" when it has: the corners
/// of an infinite frustum's kept region (unbounded), the linear depth of a rotated or general
/// camera (it does not look along z). A run leaves such families out, saying so, rather than
/// count each of their cases left out.
std::string_view not_applicable(ConsumerCheck check, cases::Family family);

/// One consumer property's verdict on one answer.
struct [[nodiscard]] ConsumerFinding {
  ConsumerCheck check = ConsumerCheck::view_position;
  bool judged = true;  ///< false: the case was not judged (why: `detail`, and `unjudged`)
  /// Why a finding is not judged (where `judged` is false), for the tallies that say how much
  /// of what a contract claims was judged: `undecided`, a case the contract claims that could not
  /// be decided (within rounding, not determined in T, refused by accepts); `unclaimed`, a case
  /// no consumer contract claims (M and C have no oblique matrix: an input without an answer);
  /// `not_applicable`, a property that says nothing of this matrix (the corners of an unbounded
  /// kept region). Only `undecided` counts toward "judged in part only".
  enum class Unjudged { undecided, unclaimed, not_applicable };
  Unjudged unjudged = Unjudged::undecided;
  bool holds = true;
  /// The worst residual over its bound (<= 1 within); for a failed kept-side or near-plane
  /// check, the margin by which the sign is wrong, over its bound.
  double ratio = 0;
  std::string detail;  ///< what was compared, in words and round-trip numbers
  /// The points the finding is about (camera space), for a report's pictures, and what they are.
  std::vector<Eigen::Vector3d> points;
  std::string points_what;
  /// corners_contain_kept: how much longer than the kept region's the corners' extent along the
  /// view axis is (1: as tight as it can be); 0 when not measured.
  double depth_waste = 0;
  /// For a violated finding about a pass camera or its plane (no oblique matrix's case to draw):
  /// what a report draws, in `drawn_space`: named sets of line segments and points (cameras as
  /// an eye with its view direction and up, planes as squares with their kept side's normal).
  struct Drawn {
    std::string name;
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines;
    std::vector<Eigen::Vector3d> points;
  };
  std::vector<Drawn> drawn;
  std::string drawn_space;
  /// For a violated finding: the known consumer mistakes whose function gives the answer
  /// (mistakes/consumer_mistakes.h; names joined by " or "), empty when none is known or the
  /// finding was not explained.
  std::string likely_cause;
  /// For a violated finding explained: what the answer shows, in words, whatever names it (for
  /// a view position where it projects against the pixel's ray; else how far it is from the
  /// right answer).
  std::string answers_show;
};

/// The pixel of a render target a sample is read at: the target's size and the pixel's column
/// and row, the row counted from the bottom (NDC y = -1) up. An empty target (width 0) is an
/// arbitrary position, no pixel's.
struct Pixel {
  int width = 0, height = 0;
  int x = 0, y = 0;
  /// Read at the pixel's centre (Sampling::pixels), else at the sample's NDC, within the pixel.
  bool at_centre = false;
};

/// Where the depth functions are asked (Consumers::sampling).
enum class Sampling {
  /// At pixel centres of render targets of real sizes (1920 x 1080, odd sizes, 1 x 1, 16384
  /// wide, ...): what a GPU evaluates.
  pixels,
  /// At arbitrary NDC positions (the kept region's points as they project): positions no target
  /// has, a stiff mode.
  arbitrary,
};
inline constexpr EnumName<Sampling> sampling_names[] = {
    {Sampling::pixels, "pixels"},
    {Sampling::arbitrary, "arbitrary"},
};
constexpr std::string_view sampling_name(Sampling s) noexcept {
  return name_in(sampling_names, s);
}
constexpr std::optional<Sampling> parse_sampling(std::string_view name) noexcept {
  return value_in(sampling_names, name);
}

/// How the depth functions are handed the pixel (Consumers::pixel_input).
enum class PixelInput {
  /// Its NDC x and y, as the sample holds them: judged against that ray exactly.
  ndc,
  /// As a GPU hands it (a texture coordinate, a fragment coordinate, a texel and the target's
  /// size), from which the function derives NDC in its own arithmetic: judged against the ray of
  /// the position handed, within the rounding of handing it and of that derivation
  /// (tolerance.h, kPixelToNdcRoundings).
  gpu,
};

/// What a depth consumer reads at one pixel.
template <class T>
struct DepthSample {
  Matrix4<T> projection;  ///< M', the matrix the depth was rendered with
  Matrix4<T> original;    ///< M, the camera's projection before the oblique modification
  Convention convention = Convention::gl;
  DepthBuffer buffer = DepthBuffer::fixed24;
  T ndc_x = 0, ndc_y = 0;  ///< the pixel's NDC (its centre's, rounded to T, for a target's pixel)
  /// The target's pixel the sample is read at (its centre is at NDC x, y), or none (width 0).
  Pixel pixel;
  /// How far in NDC x and in NDC y the position the consumer reads may be from (ndc_x, ndc_y):
  /// 0 where it is handed NDC; for a position handed as a GPU hands it, the rounding of handing
  /// it and of the consumer's derivation of NDC from it (PixelInput::gpu). The judges widen the
  /// ray by it.
  T ndc_error = 0;
  /// The pass camera's view (world -> its camera space, affine: last row (0, 0, 0, 1)), for a
  /// consumer that reconstructs the world position; the identity otherwise.
  Matrix4<T> view = Matrix4<T>::Identity();
  /// The window depth as a shader reads it: fixed24, k / (2^24 - 1) rounded to T; float32, the
  /// stored float.
  T depth = 0;
  std::uint32_t stored = 0;  ///< fixed24: k; float32: the float's bits
};

/// The sample a camera-space point leaves in the buffer under `projection`: its NDC x and y
/// rounded to T, its window depth stored in `buffer`. Empty when the point is not in front of
/// the camera or its depth is outside [0, 1].
template <class T>
std::optional<DepthSample<T>> depth_sample(const Matrix4<T>& projection, const Matrix4<T>& original,
                                           Convention convention, DepthBuffer buffer,
                                           const Vector4<T>& point);

/// `sample` read at a pixel of `target` (its width and height): Sampling::pixels moves it to the
/// centre of the pixel that holds its NDC (the nearest pixel where it is outside), its NDC that
/// centre's rounded to T; Sampling::arbitrary keeps its NDC and notes the pixel that holds it.
/// The depth is kept (a depth of that pixel's ray within the volume).
template <class T>
DepthSample<T> at_pixel(const DepthSample<T>& sample, Pixel target, Sampling sampling);

/// How a judge computes what it compares: certified floating-point bounds first and exact
/// rational arithmetic where they cannot decide (filtered, the verdict the same), or exact
/// arithmetic throughout (the reference the filtered judge is tested against).
enum class Arithmetic { filtered, exact };

/// The arithmetic a consumer computes in, which its bounds are derived from: T's IEEE arithmetic
/// (every operation correctly rounded), or a GPU's in T (a shader: the shading language's stated
/// precision per operation, tolerance.h kGpuLostBits; the depth judges only).
enum class ConsumerArithmetic { ieee, gpu };

/// DepthSample::ndc_error for a consumer that reads the pixel as `input` in `arithmetic`: 0 for
/// NDC; for a position as a GPU hands it, kPixelToNdcRoundings units of the arithmetic
/// (tolerance.h).
template <class T>
T ndc_error_of(PixelInput input, ConsumerArithmetic arithmetic);

/// `answer`, the view position the consumer reconstructed from `sample`, against the segment of
/// the pixel ray whose window depths the stored value stands for (fixed24: k +- 1/2 over 2^24 - 1;
/// float32: the half-ulps around it; clamped to [0, 1]), widened by the solve's rounding in
/// `arithmetic`. Not judged where that segment reaches infinity.
template <class T>
ConsumerFinding judge_view_position(const DepthSample<T>& sample, const Vector3<T>& answer,
                                    ConsumerArithmetic arithmetic = ConsumerArithmetic::ieee,
                                    Arithmetic method = Arithmetic::filtered);

/// `answer`, the linear depth (view_axis_sign(original) z) the consumer reconstructed from
/// `sample`, as judge_view_position() judges the point's z.
template <class T>
ConsumerFinding judge_linear_depth(const DepthSample<T>& sample, T answer,
                                   ConsumerArithmetic arithmetic = ConsumerArithmetic::ieee,
                                   Arithmetic method = Arithmetic::filtered);

/// `answer`, the world position the consumer reconstructed from `sample` (through the pass
/// camera's sample.view), judged as judge_view_position() judges its image under the view
/// (sample.view times it, exactly), the segment widened by what reaching world space may add:
/// the larger of a route through the view position and the inverse view, and one through the
/// inverse of the view-projection M' view (tolerance.h, world position), each in `arithmetic`.
/// Filtered as judge_view_position() is: an answer shown to hold in certified bounds (the box from
/// below) is settled there, every other in exact arithmetic.
template <class T>
ConsumerFinding judge_world_position(const DepthSample<T>& sample, const Vector3<T>& answer,
                                     ConsumerArithmetic arithmetic = ConsumerArithmetic::ieee,
                                     Arithmetic method = Arithmetic::filtered);

/// The culling planes the consumer extracted from `oblique` (the answer for m, c, convention in T),
/// each keeping P . x >= 0: culling_keeps_visible (every vertex of the kept region of m and c,
/// directions at infinity included, on each plane's kept side within its rounding and row 3's
/// error bound) and culling_near_is_c (near_plane = s C, s > 0, within those bounds). Filtered:
/// a vertex certainly on a plane's kept side is settled in certified intervals, every other
/// exactly (Arithmetic::exact: all exactly).
template <class T>
std::vector<ConsumerFinding> judge_culling_planes(const Matrix4<T>& m, const Vector4<T>& c,
                                                  Convention convention, const Matrix4<T>& oblique,
                                                  const FrustumPlanes<T>& answer,
                                                  Arithmetic arithmetic = Arithmetic::filtered);

/// The plane the consumer gives in the pass camera's space (pass_view: world -> pass camera) for
/// the world plane whose front the pass keeps: plane_on_surface (points of the world plane,
/// `surface_points`, land on it) and plane_kept_side (`front_point`, in front of the world plane,
/// lands on its positive side).
template <class T>
std::vector<ConsumerFinding> judge_camera_plane(const Matrix4<T>& pass_view,
                                                const Vector4<T>& world_plane,
                                                const std::vector<Vector4<T>>& surface_points,
                                                const Vector4<T>& front_point,
                                                const Vector4<T>& answer);

/// How a mirror pass's camera is built; both are designs engines ship.
enum class MirrorDesign {
  /// view R, R the reflection in the mirror's plane: an improper camera (det < 0) whose images
  /// come out mirrored by themselves (the winding flips).
  reflected_view,
  /// diag(-1, 1, 1, 1) view R: a proper camera (det > 0) looking at the reflected scene, the
  /// horizontal flip done elsewhere (in the projection, M11 < 0, or in the texture lookup).
  proper_camera,
};
inline constexpr EnumName<MirrorDesign> mirror_design_names[] = {
    {MirrorDesign::reflected_view, "reflected_view"},
    {MirrorDesign::proper_camera, "proper_camera"},
};
constexpr std::string_view mirror_design_name(MirrorDesign d) noexcept {
  return name_in(mirror_design_names, d);
}
/// Inverse of mirror_design_name(); none for an unknown name.
constexpr std::optional<MirrorDesign> parse_mirror_design(std::string_view name) noexcept {
  return value_in(mirror_design_names, name);
}

/// The mirror pass's view the consumer built from the main `view` and the mirror's world plane:
/// the `design`'s matrix (view R, or diag(-1, 1, 1, 1) view R) within gamma(kPassViewRoundings)
/// |view| |R|. An answer of the other design is violated, the finding naming that design and
/// how to declare it.
template <class T>
ConsumerFinding judge_mirror_view(const Matrix4<T>& view, const Vector4<T>& world_plane,
                                  const Matrix4<T>& answer,
                                  MirrorDesign design = MirrorDesign::reflected_view);

/// The portal pass's view from the main `view` and the two portals' frames: view frame turn
/// linked^-1 within gamma(kPassViewRoundings) |view| |frame| |linked^-1| |linked| |linked^-1|.
template <class T>
ConsumerFinding judge_portal_view(const Matrix4<T>& view, const Matrix4<T>& frame,
                                  const Matrix4<T>& linked, const Matrix4<T>& answer);

/// The most distinct points judge_corners() takes.
inline constexpr std::size_t kMaxCorners = 32;

/// The points the consumer gives as the corners of the view volume of `oblique` (the answer for
/// m, c, convention in T): their convex hull must contain every vertex of the kept region, within
/// the distance their computation from `oblique` in T and row 3's error allow. Not judged for an
/// infinite m (the kept region is unbounded), or for more than kMaxCorners distinct points.
/// Reports the depth waste.
template <class T>
ConsumerFinding judge_corners(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                              const Matrix4<T>& oblique, const std::vector<Vector3<T>>& answer,
                              Arithmetic arithmetic = Arithmetic::filtered);

/// A vector or matrix as the consumer reports print it: "[a, b; c, d]" (rows separated by "; "),
/// each number the shortest decimal that reads back as it (protocol::format_number()); a
/// vector prints as one row.
template <class T, int R, int C>
std::string numbers_text(const Eigen::Matrix<T, R, C>& m) {
  const bool row = C == 1;  // a column vector prints as one row
  std::string out = "[";
  for (int i = 0; i < (row ? 1 : R); ++i) {
    out += i ? "; " : "";
    for (int j = 0; j < (row ? R : C); ++j)
      out += (j ? ", " : "") + protocol::format_number(row ? m(j, 0) : m(i, j));
  }
  return out + "]";
}

/// A readable line of a finding: "culling_near_is_c: ... (ratio 3.2)".
std::string describe(const ConsumerFinding& finding);

}  // namespace oblique::oracle

namespace oblique {

/// The code around the oblique matrix, yours: each function given is checked against its
/// properties (oblique/oracle/consumers.h; docs/consumers.md), the others are not asked.
/// Camera space and planes as for adapt(): column vectors, a plane keeps P . x >= 0.
template <class T>
struct Consumers {
  std::string name = "consumers";
  /// The camera-space point of the pixel at NDC (x, y) whose depth buffer holds sample.depth
  /// (the depth was rendered with sample.projection, the oblique M').
  std::function<Vector3<T>(const oracle::DepthSample<T>& sample)> view_position;
  /// Its linear depth: the distance in front of the camera along the view axis (-z for a camera
  /// looking down -z).
  std::function<T(const oracle::DepthSample<T>& sample)> linear_depth;
  /// The world point of the pixel: the camera-space point carried back through the pass camera's
  /// view (sample.view, world -> camera), as engines do with an inverse view-projection.
  std::function<Vector3<T>(const oracle::DepthSample<T>& sample)> world_position;
  /// The six culling planes of an oblique projection (camera space, kept side positive).
  std::function<FrustumPlanes<T>(const Matrix4<T>& oblique, Convention convention)> culling_planes;
  /// The plane in a pass camera's space (pass_view: world -> that camera) whose positive side is
  /// the world plane's front, which the pass keeps.
  std::function<Vector4<T>(const Matrix4<T>& pass_view, const Vector4<T>& world_plane)>
      camera_plane;
  /// A mirror pass's view from the main view and the mirror's world plane.
  std::function<Matrix4<T>(const Matrix4<T>& view, const Vector4<T>& mirror_plane)> mirror_view;
  /// Which design mirror_view builds (judge_mirror_view() above): the reflected view, or a proper
  /// camera whose horizontal flip is done in the projection or the texture lookup.
  oracle::MirrorDesign mirror_design = oracle::MirrorDesign::reflected_view;
  /// A portal pass's view from the main view, this portal's frame and the linked portal's frame
  /// (columns right, up, normal, centre).
  std::function<Matrix4<T>(const Matrix4<T>& view, const Matrix4<T>& frame,
                           const Matrix4<T>& linked)>
      portal_view;
  /// Points whose convex hull bounds what an oblique pass draws (cascade fitting, light lists),
  /// from its oblique projection and the camera's unmodified one.
  std::function<std::vector<Vector3<T>>(const Matrix4<T>& oblique, const Matrix4<T>& original,
                                        Convention convention)>
      corners;
  /// The cameras the functions that take a projection (view_position, linear_depth,
  /// culling_planes, corners) are meant for, by the camera's own projection M and its convention,
  /// as adapt()'s accepts (the presets of adapter.h serve). Empty: every camera. A refused
  /// camera's round asks none of them; runs count it refused by accepts, never judged, and a
  /// family the contract claims with every case refused fails the run, saying so.
  std::function<bool(Convention convention, const Matrix4<T>& projection)> accepts;
  /// The arithmetic view_position and linear_depth compute in (their bounds): T's IEEE one, or a
  /// GPU's (a shader run by oblique/shader).
  oracle::ConsumerArithmetic arithmetic = oracle::ConsumerArithmetic::ieee;
  /// How view_position and linear_depth read the pixel: the sample's NDC, or as a GPU hands it
  /// (a shader's texture coordinate, fragment coordinate or texel: sample.pixel).
  oracle::PixelInput pixel_input = oracle::PixelInput::ndc;
  /// Where view_position and linear_depth are asked: pixel centres of real targets, or arbitrary
  /// positions (stiff).
  oracle::Sampling sampling = oracle::Sampling::pixels;
};

/// A Consumers with the settings of `c` (its name, accepts, arithmetic, designs, pixel input and
/// sampling) and none of its functions: a run asks one function of it at a time.
template <class T>
Consumers<T> settings_of(const Consumers<T>& c) {
  Consumers<T> out;
  out.name = c.name;
  out.accepts = c.accepts;
  out.arithmetic = c.arithmetic;
  out.mirror_design = c.mirror_design;
  out.pixel_input = c.pixel_input;
  out.sampling = c.sampling;
  return out;
}

}  // namespace oblique

namespace oblique::oracle {

/// The core's references as a Consumers (depth_reconstruction.h, frustum_planes.h, pass_camera.h,
/// kept_region.h), named "core_references": what `oblique check` judges when no program is
/// given, and what fuzz_consumers fuzzes.
template <class T>
Consumers<T> reference_consumers();

/// Where a consumer round's choices come from: an integer in [lo, hi) (RapidCheck's choices, a
/// fuzz input's bytes, verify's seeded draws or a report's recorded picks).
using Pick = std::function<int(int lo, int hi)>;

/// A consumer property's verdict on one answer, with the inputs as text (a Markdown list, every
/// number round-trip) and whether the case is an oblique matrix's (M, C and the core's M'), which
/// a report draws.
using Settle = std::function<void(const ConsumerFinding& finding, const std::string& inputs,
                                  bool about_oblique_case)>;

/// One request of a consumer round as data, so that a round is planned apart from being answered
/// and a program can be sent many requests at once: the function it asks, the protocol's request
/// line for it (consumer_wire.h), how an in-process Consumers answers it (as the numbers of the
/// protocol's answer), and how those numbers are judged (each finding to `settle`).
template <class T>
struct ConsumerAsk {
  protocol::ConsumerKind kind = protocol::ConsumerKind::view_position;
  std::function<protocol::ConsumerRequest()> request;
  std::function<std::vector<T>(const Consumers<T>&)> call;
  std::function<void(const std::vector<T>& answer, const Settle& settle)> judge;
};

/// Explains a violated finding of `answer` to `ask` (sets its likely_cause): given by a tool that
/// knows the catalogue of consumer mistakes (mistakes::explain_consumer), empty otherwise.
template <class T>
using Explain = std::function<void(const ConsumerAsk<T>& ask, const std::vector<T>& answer,
                                   ConsumerFinding& finding)>;

/// judge() of `ask` on `answer`, each violated finding explained (when `explain` is given) before
/// it goes to `settle`.
template <class T>
void judge_explained(const ConsumerAsk<T>& ask, const std::vector<T>& answer, const Settle& settle,
                     const Explain<T>& explain);

/// consumer_round()'s requests, planned and not yet asked: its picks drawn in the same order, the
/// findings left out before any asking (refused by accepts, no oblique matrix for M and C, no
/// depth sample) given to `settle` now, and the requests returned in the order the round asks
/// them. Only which functions `consumers` gives, its accepts, mirror design, arithmetic and name
/// are read.
template <class T>
std::vector<ConsumerAsk<T>> consumer_asks(const Matrix4<T>& m, const Vector4<T>& c,
                                          Convention convention, const Consumers<T>& consumers,
                                          const Pick& pick, const Settle& settle);

/// One round of the code around the matrix, the one way every tool asks and judges it: for each
/// function `consumers` gives, its case is built from `pick` (consumer_cases.h; depth, culling
/// and corners on m, c and the core's M' for them), the function is asked, and each finding of its
/// properties goes to `settle` as soon as it is judged. m and c are used only by the functions
/// that take an oblique matrix; where the core has no answer for them, `settle` gets one finding
/// not judged ("no oblique matrix for M and C (STATUS)"). A violated finding is first given to
/// `explain` where given.
template <class T>
void consumer_round(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                    const Consumers<T>& consumers, const Pick& pick, const Settle& settle,
                    const Explain<T>& explain = {});

}  // namespace oblique::oracle
