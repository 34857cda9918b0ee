// `oblique check --plot DIR`: a top view (world x, z) and a side view (world z, y) of a scene as
// gnuplot PNGs: the main camera's view volume, each surface, and each rendered pass's virtual view
// volume, cut by its oblique near plane and its tilted far plane.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "oblique/report/views.h"
#include "oblique/scene/check.h"
#include "oblique/scene/scene.h"

namespace oblique::scene {

// (The volumes' edges are traced by report::volume_edges, oblique/report/views.h, which the
// counterexample reports' pictures share.)

struct PlotResult {
  std::vector<std::filesystem::path> written;  ///< the data, scripts and PNGs
  std::string error;                           ///< empty when both PNGs were written
  /// The view that shows the first rendered mirror or portal pass across its surface (the one
  /// whose axes hold most of the surface's normal), and that surface's name; empty without one.
  std::filesystem::path across;
  std::string across_surface;
};

/// What the pictures of a scene show: the camera and each rendered pass's virtual camera
/// (labelled), the surfaces, the main view volume, each pass's oblique volume (dashed) and what
/// its camera would draw without the oblique near plane (dotted), framed to the eyes, the
/// surfaces and where the view axis meets them; and the first mirror or portal pass, if any.
struct SceneViews {
  report::Views views;
  const SurfaceCheck* first_virtual = nullptr;
};
SceneViews scene_views(const Scene& scene, const SceneCheck& check);

/// Writes DIR/scene.dat, DIR/top.gp, DIR/side.gp, DIR/scene.html (scene_views() in 3D to turn,
/// beside `page_markdown`: the check's table) and (with gnuplot) DIR/top.png, DIR/side.png.
PlotResult write_plot(const Scene& scene, const SceneCheck& check, const std::filesystem::path& dir,
                      const std::string& page_markdown = "");

}  // namespace oblique::scene
