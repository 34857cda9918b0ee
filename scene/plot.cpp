#include "oblique/scene/plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "oblique/protocol/numbers.h"
#include "oblique/report/report_files.h"
#include "oblique/report/views.h"

namespace oblique::scene {

using report::Dataset;
using report::Segment;
using report::volume_edges;

PlotResult write_plot(const Scene& scene, const SceneCheck& check,
                      const std::filesystem::path& dir) {
  PlotResult result;
  // How far an unbounded volume is drawn: three times the scene's extent around the eye.
  const Vector3 eye = scene.camera.eye;
  double extent = 1;
  for (const Surface& s : scene.surfaces) {
    extent = std::max(extent, (s.point - eye).norm());
    for (const Vector3& v : s.polygon) extent = std::max(extent, (v - eye).norm());
  }
  const double reach = 3 * extent;
  std::vector<Dataset> sets;
  sets.push_back({"main view volume",
                  "lines lc rgb 'black' lw 2",
                  volume_edges(scene.camera.view, scene.camera.projection, scene.convention, reach),
                  {}});
  for (const Surface& s : scene.surfaces) {
    Dataset d{s.name, "lines lc rgb 'blue' lw 3", {}, {}};
    std::vector<Vector3> outline = s.polygon;
    if (outline.empty()) {  // an infinite plane: a square of the scene's size around its point
      const Vector3 n = s.normal.normalized();
      const Vector3 a =
          (std::abs(n.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY()).cross(n).normalized();
      const Vector3 b = n.cross(a);
      for (const auto& [u, v] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
        outline.push_back(s.point + extent * (u * a + v * b));
    }
    for (std::size_t i = 0; i < outline.size(); ++i)
      d.segments.push_back({outline[i], outline[(i + 1) % outline.size()]});
    sets.push_back(std::move(d));
  }
  const char* colors[] = {"#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                          "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
  std::size_t color = 0;
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render || !s.projection) continue;
    // The virtual volume in the pass's world (the pass camera's view), within its scissor.
    std::array<double, 4> rect = {-1, -1, 1, 1};
    if (s.scissor) rect = {s.scissor->x0, s.scissor->y0, s.scissor->x1, s.scissor->y1};
    sets.push_back({s.name + (s.scissor ? " (pass, scissored)" : " (pass)"),
                    "lines lc rgb '" + std::string(colors[color++ % 8]) + "' dt 2 lw 1.5",
                    volume_edges(s.view, *s.projection, scene.convention, reach, rect),
                    {}});
  }
  try {
    report::ReportFiles files(dir);
    // The picture shows the eye and the surfaces with a margin (volumes are cut at its edge).
    Vector3 lo = eye, hi = eye;
    for (const Surface& s : scene.surfaces) {
      lo = lo.cwiseMin(s.point);
      hi = hi.cwiseMax(s.point);
      for (const Vector3& v : s.polygon) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    }
    const double margin = 0.5 * std::max((hi - lo).maxCoeff(), 1.0);
    lo.array() -= margin;
    hi.array() += margin;
    report::Views views;
    views.title = check.scene;
    views.space = "world";
    views.data = "scene.dat";
    views.top = "top";
    views.side = "side";
    views.lo = lo;
    views.hi = hi;
    views.sets = std::move(sets);
    report::stage_views(files, views, dir);
    // Every file whole in place (or none), then the pictures.
    std::ostringstream commit_log;
    if (!files.commit(commit_log)) {
      std::string why = commit_log.str();
      while (!why.empty() && why.back() == '\n') why.pop_back();
      throw std::runtime_error(why);
    }
    for (const char* view : {"top", "side"}) {
      const std::string script = std::string(view) + ".gp", png = std::string(view) + ".png";
      std::ostringstream log;
      files.plot(script, png, log);
      if (std::find(files.written().begin(), files.written().end(), dir / png) ==
          files.written().end()) {
        result.error = log.str().empty() ? "gnuplot did not write " + png : log.str();
        while (!result.error.empty() && result.error.back() == '\n') result.error.pop_back();
      }
    }
    result.written = files.written();
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  return result;
}

}  // namespace oblique::scene
