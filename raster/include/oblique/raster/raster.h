// oblique::raster: an oblique projection rendered on a real rasterizer (OpenGL 4.5 through EGL,
// headless), and what it clipped and stored judged against the plane C and the original view
// volume. The software device is Mesa's llvmpipe, on any machine without a GPU.
//
// One frame is one sample per pixel: a point of camera space on the pixel's ray through M, at a
// distance bunched near C, the original near and far planes and the answer's far plane. The
// rasterizer draws them as 1-pixel points with M' in float32, each writing its id and its depth;
// the judge reads both back. Its bands (what float32 shading cannot decide) are in
// oblique/oracle/tolerance.h, derived there.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/expected.h"
#include "oblique/raster/gl_context.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/util/enum_names.h"

namespace oblique::raster {

/// A verdict about the answer, or none: a self-check of the renderer tripped.
enum class Outcome { pass, fail, inconclusive };

inline constexpr EnumName<Outcome> outcome_names[] = {
    {Outcome::pass, "pass"},
    {Outcome::fail, "fail"},
    {Outcome::inconclusive, "inconclusive"},
};
constexpr std::string_view outcome_name(Outcome value) noexcept {
  return name_in(outcome_names, value);
}

/// The samples of one frame, one per pixel (pixel (i, j), i from the left, j from the bottom, is
/// sample j * size + i): a point of camera space with w = 1, in float32 as the vertex shader
/// gets it. A sample whose pixel float32 shading cannot decide is not drawn (`placed` 0).
struct Frame {
  int size = 0;
  std::vector<Eigen::Vector4f> points;
  std::vector<unsigned char> placed;
};

/// Builds the frame for M, C and the correct answer `reference` (its far plane is one the
/// distances bunch at) in `convention`, `size` x `size` pixels, from `seed`.
Frame make_frame(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                 const Eigen::Matrix4d& reference, Convention convention, int size,
                 std::uint64_t seed);

/// What the renderer gave back for a frame: per pixel, the id of the sample drawn there (its
/// index + 1; 0 for none) and the depth stored, as read back.
struct Readback {
  std::vector<std::uint32_t> ids;
  std::vector<float> depths;
};

/// One sample that a judgement flagged, with its numbers.
struct Flag {
  enum class Kind {
    drawn_behind_c,      ///< drawn, on C's clipped side beyond the band
    clipped_kept,        ///< in the original volume on C's kept side beyond the bands, not drawn
    wrong_pixel,         ///< drawn into a pixel not its own: the answer moved it
    renderer_disagrees,  ///< the renderer clipped against its own float32 arithmetic (self-check)
    depth_off,           ///< the stored depth beyond its bound (self-check)
  };
  Kind kind = Kind::drawn_behind_c;
  long sample = 0;        ///< its index (pixel j * size + i)
  long pixel = 0;         ///< where it was drawn (its own pixel unless wrong_pixel)
  Eigen::Vector4f point;  ///< in camera space
  double c_dot = 0;       ///< C . point, C scaled by a power of two to a largest |C_i| in [0.5, 1)
  double band = 0;        ///< the band C . point was judged against
  double depth_read = 0, depth_exact = 0, depth_bound = 0;
};

inline constexpr EnumName<Flag::Kind> flag_names[] = {
    {Flag::Kind::drawn_behind_c, "drawn_behind_c"},
    {Flag::Kind::clipped_kept, "clipped_kept"},
    {Flag::Kind::wrong_pixel, "wrong_pixel"},
    {Flag::Kind::renderer_disagrees, "renderer_disagrees"},
    {Flag::Kind::depth_off, "depth_off"},
};
constexpr std::string_view flag_name(Flag::Kind kind) noexcept {
  return name_in(flag_names, kind);
}

/// The depth buffer's precision measured across the kept region: the depths stored there span
/// [low, high], which the buffer resolves into `values` distinct values (log2: `bits`);
/// `observed` distinct values were read back from the frame's samples.
struct DepthMeasure {
  double low = 0, high = 0;
  double values = 0;
  double bits = 0;
  long observed = 0;
};

struct [[nodiscard]] Result {
  Outcome outcome = Outcome::inconclusive;
  std::string why;  ///< one line: what failed, or which self-check tripped
  long samples = 0;
  long placed = 0;       ///< samples drawn into the frame (the others' pixel is not decidable)
  long drawn = 0;        ///< samples the renderer kept
  long undecidable = 0;  ///< placed, but within a band of a plane that decides them
  long drawn_behind_c = 0, clipped_kept = 0, wrong_pixel = 0;
  long renderer_disagrees = 0, depth_off = 0, ids_inconsistent = 0;
  double worst_depth_ratio = 0;  ///< the largest |stored - exact| / bound
  DepthMeasure depth;
  std::vector<Flag> examples;  ///< the first few flags of each kind
  /// Every flagged sample (index, kind), for a picture of where they are (at most 2^18).
  std::vector<std::pair<long, Flag::Kind>> flagged;
  /// The frame as drawn: per pixel (j * size + i), 1 where the renderer kept a sample.
  std::vector<std::uint8_t> drawn_pixels;
  bool rendered = false;  ///< the frame was drawn and read back (else `why` says why not)
  double render_seconds = 0, judge_seconds = 0;
};

/// What the properties accept of an answer's third row when it is computed in a type of
/// `precision_bits` (24: float, 53: double, 64: long double) from M and C (exactly representable
/// there): per entry, the bound on |M'_3i - exact M'_3i| (properties' Problem::row3_bounds(): the
/// entries' rounding and the error of the scale a, kappa-dependent), widened by property 1's
/// allowance (u a max|C_j|) and the reference's own 2 ulps, in doubles rounded up. nullopt where
/// no bound exists: C lies within rounding of the far corner.
std::optional<Eigen::Vector4d> accepted_row3(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                                             Convention convention, int precision_bits);

/// Judges a frame's read-back for the answer M' (`answer`), against C, the original M and the
/// correct answer `reference`, in `convention` and `buffer`. The bands are what float32 shading
/// of any answer the properties accept cannot decide: the reference's rows, widened by
/// `accepted` (accepted_row3()); where that is nullopt, nothing is decided against C or the
/// volume (every placed sample counts as within a band), and only the self-checks and the pixels
/// are judged.
Result judge_frame(const Frame& frame, const Readback& readback, const Eigen::Matrix4d& m,
                   const Eigen::Vector4d& c, const Eigen::Matrix4d& answer,
                   const Eigen::Matrix4d& reference, const std::optional<Eigen::Vector4d>& accepted,
                   Convention convention, DepthBuffer buffer);

/// The depth buffer's precision along the view axis, measured: the axis of M (M^-1 (0, 0, z, 1))
/// where it is on C's kept side, one sample a pixel spread evenly over it, each drawn with its
/// own depth (placed in its pixel by id). The depths stored span [low, high]: `values` buffer
/// values, and `bits_lost` = log2(the buffer's values in [0, 1] / values), as `oblique check`'s
/// analytic figure; `observed` distinct depths were read back from `drawn` samples.
struct AxisDepth {
  long drawn = 0;
  long observed = 0;
  double low = 0, high = 0;
  double values = 0;
  double bits_lost = 0;
};

/// AxisDepth from the read-back of an axis frame.
AxisDepth measure_axis(const Readback& readback, Convention convention, DepthBuffer buffer);

/// The half of a check that needs no renderer (prepare_check(); safe on any thread, so a frame
/// is built while the renderer draws the one before): the core's answer to judge against, the
/// frame and the envelope of accepted answers.
struct PreparedCheck {
  Eigen::Matrix4d m, answer, reference;
  Eigen::Vector4d c;
  Convention convention = Convention::gl;
  DepthBuffer buffer = DepthBuffer::fixed24;
  Frame frame;
  std::optional<Eigen::Vector4d> accepted;  ///< accepted_row3()
  std::string why;     ///< not empty: nothing to draw (the core has no answer), and why
  double seconds = 0;  ///< spent preparing
};

/// The core's answer for (M, C), make_frame() (`size` x `size`, from `seed`) and accepted_row3()
/// for an answer computed in a type of `precision_bits`.
PreparedCheck prepare_check(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                            const Eigen::Matrix4d& answer, Convention convention,
                            DepthBuffer buffer, int size, std::uint64_t seed,
                            int precision_bits = 53);

/// judge_frame() for a prepared check's read-back, with the time spent: `render_seconds` (the
/// preparation and the drawing) and the judging's own.
Result judge_prepared(const PreparedCheck& prepared, const Readback& readback,
                      double render_seconds);

struct Options {
  Device device = Device::software;
  int size = 1000;  ///< the frame is size x size pixels, one sample each
};

/// A headless OpenGL 4.5 context with the frame's buffers, opened once and used for every check.
class Rasterizer {
 public:
  /// Opens the device and runs the self-checks (the renderer is the one asked for; the core's
  /// answer on a fixed case passes in every convention and buffer). Fails with one line that says
  /// what is missing (beginning "no EGL": nothing to render with; install what it names) or which
  /// self-check tripped.
  static Expected<std::shared_ptr<Rasterizer>> open(const Options& options);
  ~Rasterizer();
  Rasterizer(const Rasterizer&) = delete;
  Rasterizer& operator=(const Rasterizer&) = delete;

  /// GL_RENDERER and GL_VERSION, as the driver says them.
  const std::string& renderer() const;
  const Options& options() const;

  /// Renders `frame` with the answer M' in `convention` into a `buffer` depth buffer and reads
  /// back ids and depths; the error is one line.
  Expected<Readback> render(const Frame& frame, const Eigen::Matrix4d& answer,
                            Convention convention, DepthBuffer buffer);

  /// The depth buffer's precision along M's view axis, measured with the answer M' (AxisDepth).
  Expected<AxisDepth> axis_depth(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                                 const Eigen::Matrix4d& answer, Convention convention,
                                 DepthBuffer buffer);

  /// The window depth M' stores for each of `points` (camera space, homogeneous: a direction,
  /// w = 0, is a point at infinity), each drawn alone in a pixel of its own; nullopt for a point
  /// the rasterizer clipped. At most size x size points.
  Expected<std::vector<std::optional<double>>> stored_depths(
      const Eigen::Matrix4d& answer, const std::vector<Eigen::Vector4d>& points,
      Convention convention, DepthBuffer buffer);

  /// make_frame(), render() and judge_frame() for the answer M' to (M, C), computed in a type
  /// of `precision_bits` (accepted_row3()), against the core's answer for (M, C). Where the core
  /// has none, or the render fails, the result is inconclusive and not rendered, saying why.
  Result check(const Eigen::Matrix4d& m, const Eigen::Vector4d& c, const Eigen::Matrix4d& answer,
               Convention convention, DepthBuffer buffer, std::uint64_t seed = 1,
               int precision_bits = 53);

  /// render() and judge_prepared() for a prepared check (its frame the size of this
  /// rasterizer's); inconclusive and not rendered where it holds nothing to draw.
  Result check(const PreparedCheck& prepared);

  /// A prepared check's frame rendered and read back; the error says why not (nothing to draw,
  /// a frame of another size, the renderer's failure). `render_seconds`: the preparation's time
  /// and the drawing's.
  Expected<Readback> render(const PreparedCheck& prepared, double* render_seconds = nullptr);

 private:
  struct State;
  explicit Rasterizer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace oblique::raster
