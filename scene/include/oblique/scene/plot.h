// `oblique check --plot DIR`: a top view (world x, z) and a side view (world z, y) of a scene as
// gnuplot PNGs: the main camera's view volume, each surface, and each rendered pass's virtual view
// volume, cut by its oblique near plane and its tilted far plane.
#pragma once

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
/// camera's), each side edge the line x = +-w, y = +-w of `original` x `view` cut by every plane
/// of the volume; an unbounded volume (infinite far) is cut `reach` from the line's near end.
std::vector<Segment> volume_edges(const Matrix4<double>& view, const Matrix4<double>& projection,
                                  Convention convention, double reach);

struct PlotResult {
  std::vector<std::filesystem::path> written;  ///< the data, scripts and PNGs
  std::string error;                           ///< empty when both PNGs were written
};

/// Writes DIR/scene.dat, DIR/top.gp, DIR/side.gp and (with gnuplot) DIR/top.png, DIR/side.png.
PlotResult write_plot(const Scene& scene, const SceneCheck& check,
                      const std::filesystem::path& dir);

}  // namespace oblique::scene
