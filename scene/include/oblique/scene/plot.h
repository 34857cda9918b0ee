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

// (The volumes' edges are traced by report::volume_edges, oblique/report/views.h, which the
// counterexample reports' pictures share.)

struct PlotResult {
  std::vector<std::filesystem::path> written;  ///< the data, scripts and PNGs
  std::string error;                           ///< empty when both PNGs were written
};

/// Writes DIR/scene.dat, DIR/top.gp, DIR/side.gp and (with gnuplot) DIR/top.png, DIR/side.png.
PlotResult write_plot(const Scene& scene, const SceneCheck& check,
                      const std::filesystem::path& dir);

}  // namespace oblique::scene
