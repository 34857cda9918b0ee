// `oblique report depth`: what the oblique near plane costs in depth precision.
//  - Figure 5 of the paper: the maximum attainable NDC z along the view axis (Eq. 19), as a
//    function of the plane's angle to the -z axis and its distance from the camera, computed from
//    the formula and, independently, from the matrix the core returns, in every convention;
//  - the bits of a 24-bit fixed-point and a 32-bit float depth buffer the oblique frustum still
//    uses along view directions, against the unmodified frustum.
#pragma once

#include <filesystem>
#include <iosfwd>
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
};

DepthReport measure_depth(const DepthOptions& options);

/// Writes figure5.csv, depth_bits.csv, depth.md, figure5.gp (and figure5.png with gnuplot).
/// Returns the paths written; all or nothing: empty (the reason on `log`, the folder's earlier
/// files kept) when a file cannot be written.
std::optional<std::vector<std::filesystem::path>> write_depth_report(const DepthReport& report,
                                                                     const DepthOptions& options,
                                                                     std::ostream& log);

}  // namespace oblique::report
