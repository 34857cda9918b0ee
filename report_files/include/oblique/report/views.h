// Pictures of view volumes, shared by `oblique check --plot` (a scene in world space) and the
// counterexample reports of verify and the property suite (one case in eye space): the edges of a
// projection's view volume, and a top view (x, z) and a side view (z, y) as gnuplot data and
// scripts staged in a ReportFiles folder.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/report/report_files.h"

namespace oblique::report {

/// A line segment of a picture.
struct Segment {
  Eigen::Vector3d a, b;
};

/// The edges of the view volume of `projection` x `view` (a pass's oblique matrix, or the main
/// camera's; view = identity for eye space) within the NDC rectangle `rect` (x0, y0, x1, y1: a
/// scissor): each side edge, the line x = x0|x1 w, y = y0|y1 w, cut by the other planes of the
/// volume (w > 0); an unbounded volume (infinite far) is cut `reach` from the edge's near end.
/// Empty when the matrix has no finite volume to draw.
std::vector<Segment> volume_edges(const Matrix4<double>& view, const Matrix4<double>& projection,
                                  Convention convention, double reach,
                                  const std::array<double, 4>& rect = {-1, -1, 1, 1});

/// A name as a single-quoted gnuplot string: ' doubled, control characters dropped.
std::string gnuplot_string(const std::string& name);

/// One entry of the pictures' legend: segments drawn as lines, or points drawn as marks.
struct Dataset {
  std::string title;
  std::string style;  ///< gnuplot's "with ..." style, e.g. "lines lc rgb 'black' lw 2"
  std::vector<Segment> segments;
  std::vector<Eigen::Vector3d> points;
};

/// A text placed at a point of the pictures (beside it, in front of every line).
struct Label {
  Eigen::Vector3d at;
  std::string text;
};

/// What the two views show.
struct Views {
  std::string title;       ///< the pictures' title ("top view" / "side view" is appended)
  std::string space;       ///< the axes' space: "world" or "eye"
  std::string data;        ///< the data file's name, e.g. "scene.dat"
  std::string top, side;   ///< the scripts' and pictures' stems, e.g. "top" (top.gp, top.png)
  Eigen::Vector3d lo, hi;  ///< the box the pictures show
  std::vector<Dataset> sets;
  std::vector<Label> labels;
  /// gnuplot's `set key` options: outside the plot, at its right, compact.
  std::string key = "outside right top vertical Left reverse samplen 1.5 spacing 0.9 font ',9'";
};

/// Stages views.data, views.top + ".gp" and views.side + ".gp" in `files`. The scripts name the
/// data and the PNGs by their names alone: they are rendered in the folder itself
/// (ReportFiles::plot() runs gnuplot there; by hand, `cd` into it first).
void stage_views(ReportFiles& files, const Views& views);

}  // namespace oblique::report
