// `oblique report depth`: what the oblique near plane costs in depth precision.
//  - Figure 5 of the paper: the maximum attainable NDC z along the view axis (Eq. 19), as a
//    function of the plane's angle to the -z axis and its distance from the camera, computed from
//    the formula and, independently, from the matrix the core returns, in every convention;
//  - the bits of a 24-bit fixed-point and a 32-bit float depth buffer the oblique frustum still
//    uses along view directions, against the unmodified frustum.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace oblique::report {

struct DepthOptions {
  std::filesystem::path out_dir = "report-out";
  double fovy_degrees = 90, aspect = 1, near_distance = 1, far_distance = 100;
};

/// One point of Figure 5 (a plane at `angle_degrees` from the -z axis, `distance` from the eye).
struct Figure5Point {
  double angle_degrees = 0, distance = 0;
  bool answered = false;    ///< the core gave an oblique matrix (the plane meets the view volume)
  double z_max_eq19 = 0;    ///< -(a (C . V) + V_z) / V_z with V = (0, 0, -1, 0), not clamped
  double z_max_matrix = 0;  ///< (M'_3 . V) / (M'_4 . V) from the core's gl matrix
  /// The fraction of the depth range reachable along the axis, min(1, ...), per convention
  /// (gl, zero_one, reversed_z), each from that convention's matrix.
  double reachable[3] = {0, 0, 0};
  /// With a rasterizer (add_measured()): the NDC z it stored for the axis's point at infinity,
  /// V = (0, 0, -1, 0), with the core's gl matrix, clamped to 1 (a point it clipped: 1); NaN
  /// where not measured.
  double z_max_measured = std::numeric_limits<double>::quiet_NaN();
  /// The gl matrix the point was measured with (the core's answer).
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Zero();
};

/// Distinct depth values along one direction (as bits, log2 of the count): the original
/// frustum's whole range (near plane to far plane) against the oblique frustum's (C to the
/// original far plane).
struct DepthBitsRow {
  double angle_degrees = 0, distance = 0;
  std::string convention, direction;
  double fixed24_bits_original = 0, fixed24_bits_oblique = 0;
  double float32_bits_original = 0, float32_bits_oblique = 0;
};

struct DepthReport {
  std::vector<Figure5Point> figure5;
  std::vector<DepthBitsRow> bits;
  double eq19_vs_matrix_max_gap = 0;  ///< largest |z_max_eq19 - z_max_matrix| over the grid
  double convention_max_gap = 0;      ///< largest spread of `reachable` across conventions
  /// With add_measured(): who measured, and the largest |z_max_measured - min(1, Eq. 19)|.
  std::string measured_on;
  long measured_points = 0;
  double measured_max_gap = 0;
};

/// A rasterizer's answer for a batch of gl matrices: the window depth ([0, 1]) each stores for
/// V = (0, 0, -1, 0), nullopt where it clipped V; or why it could not.
using AxisLimitMeasure = std::function<std::optional<std::vector<std::optional<double>>>(
    const std::vector<Eigen::Matrix4d>&, std::string& error)>;

/// Figure 5 measured: every answered grid point's V drawn with its matrix (`measure`), named
/// `renderer`. False, with the reason in `error`, when the measure fails.
bool add_measured(DepthReport& report, const AxisLimitMeasure& measure, const std::string& renderer,
                  std::string& error);

DepthReport measure_depth(const DepthOptions& options);

/// Writes figure5.csv, depth_bits.csv, depth.md, figure5.gp (and figure5.png with gnuplot).
/// Returns the paths written; all or nothing: empty (the reason on `log`, the folder's earlier
/// files kept) when a file cannot be written.
std::optional<std::vector<std::filesystem::path>> write_depth_report(const DepthReport& report,
                                                                     const DepthOptions& options,
                                                                     std::ostream& log);

}  // namespace oblique::report
