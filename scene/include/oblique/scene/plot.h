// `oblique check --plot DIR`: a top view (world x, z) and a side view (world z, y) of a scene as
// gnuplot PNGs: the main camera's view volume, each surface, and each rendered pass's virtual view
// volume, cut by its oblique near plane and its tilted far plane.
#pragma once

#include <array>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "oblique/scene/check.h"
#include "oblique/scene/scene.h"

namespace oblique::scene {

/// A line segment of the picture, world space.
struct Segment {
  Vector3 a, b;
};

/// The edges of the view volume of `projection` x `view` (a pass's oblique matrix, or the main
/// camera's) within the NDC rectangle `rect` (x0, y0, x1, y1: a scissor): each side edge, the
/// line x = x0|x1 w, y = y0|y1 w, cut by the other planes of the volume (w > 0); an unbounded
/// volume (infinite far) is cut `reach` from the edge's near end.
std::vector<Segment> volume_edges(const Matrix4<double>& view, const Matrix4<double>& projection,
                                  Convention convention, double reach,
                                  const std::array<double, 4>& rect = {-1, -1, 1, 1});

struct PlotResult {
  std::vector<std::filesystem::path> written;  ///< the data, scripts and PNGs
  std::string error;                           ///< empty when both PNGs were written
};

/// Writes DIR/scene.dat, DIR/top.gp, DIR/side.gp and (with gnuplot) DIR/top.png, DIR/side.png.
PlotResult write_plot(const Scene& scene, const SceneCheck& check,
                      const std::filesystem::path& dir);

}  // namespace oblique::scene
