#include "oblique/scene/plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "oblique/protocol/numbers.h"
#include "oblique/report/html_page.h"
#include "oblique/report/report_files.h"
#include "oblique/report/views.h"

namespace oblique::scene {

using report::Dataset;
using report::Segment;
using report::volume_edges;

namespace {

/// Where the eye of a camera with this view matrix (world -> camera) is.
Vector3 eye_of(const Matrix4<double>& view) {
  const Vector4<double> e = view.inverse() * Vector4<double>(0, 0, 0, 1);
  return e.head<3>() / e.w();
}

/// The box the pictures show: the eyes, the surfaces and where the main camera's view axis meets
/// them, with a margin, every side at least a third of the longest (so neither view is a strip).
std::pair<Vector3, Vector3> frame(const std::vector<Vector3>& points) {
  Vector3 lo = points.front(), hi = points.front();
  for (const Vector3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double longest = std::max((hi - lo).maxCoeff(), 1.0);
  for (int i = 0; i < 3; ++i) {
    const double grow = std::max(0.0, longest / 3 - (hi(i) - lo(i))) / 2 + 0.1 * longest;
    lo(i) -= grow;
    hi(i) += grow;
  }
  return {lo, hi};
}

}  // namespace

SceneViews scene_views(const Scene& scene, const SceneCheck& check) {
  SceneViews out;
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
  std::vector<report::Label> labels = {{eye, "camera"}};
  sets.push_back({"camera", "points pt 7 ps 1.5 lc rgb 'black'", {}, {eye}});
  // What the pictures frame: the eyes, the surfaces, and where the view axis meets a surface.
  std::vector<Vector3> framed = {eye};
  const Vector3 axis = (scene.camera.target - eye).normalized();
  for (const Surface& s : scene.surfaces) {
    // A bounded surface's point is its polygon's centroid (the reader's polygon_plane()).
    labels.push_back({s.point, s.name});
    framed.push_back(s.point);
    for (const Vector3& v : s.polygon) framed.push_back(v);
    const double facing = s.normal.dot(axis);
    if (facing != 0) {
      const double t = s.normal.dot(s.point - eye) / facing;
      if (t > 0 && t < reach) framed.push_back(eye + t * axis);
    }
  }
  std::size_t color = 0;
  const SurfaceCheck*& first_virtual = out.first_virtual;
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render || !s.projection) continue;
    // The virtual volume in the pass's world (the pass camera's view), within its scissor, from
    // its oblique near plane (the surface) to its tilted far plane; and the pass's camera.
    std::array<double, 4> rect = {-1, -1, 1, 1};
    if (s.scissor) rect = {s.scissor->x0, s.scissor->y0, s.scissor->x1, s.scissor->y1};
    const std::string rgb = colors[color++ % 8];
    sets.push_back({s.name + (s.scissor ? " (pass, scissored)" : " (pass)"),
                    "lines lc rgb '" + rgb + "' dt 2 lw 1.5",
                    volume_edges(s.view, *s.projection, scene.convention, reach, rect),
                    {}});
    // The virtual camera of a pass seen from the main camera (deeper ones would crowd it).
    const Vector3 pass_eye = eye_of(s.view);
    if (s.level != 1 || !pass_eye.allFinite() || (pass_eye - eye).norm() < 1e-9 * (1 + eye.norm()))
      continue;
    // What the virtual camera would draw without the oblique near plane: everything behind the
    // surface too.
    sets.push_back({s.name + ": without the oblique near plane",
                    "lines lc rgb '#999999' dt 3 lw 1",
                    volume_edges(s.view, s.camera_projection, scene.convention, reach, rect),
                    {}});
    sets.push_back(
        {s.name + ": virtual camera", "points pt 7 ps 1.5 lc rgb '" + rgb + "'", {}, {pass_eye}});
    if (color <= 4) labels.push_back({pass_eye, "virtual camera (" + s.name + ")"});
    if (!first_virtual) first_virtual = &s;
    framed.push_back(pass_eye);
  }
  // The picture frames what matters (volumes are cut at its edge).
  const auto [lo, hi] = frame(framed);
  report::Views& views = out.views;
  views.title = check.scene;
  views.space = "world";
  views.data = "scene.dat";
  views.top = "top";
  views.side = "side";
  views.lo = lo;
  views.hi = hi;
  views.sets = std::move(sets);
  views.labels = std::move(labels);
  return out;
}

PlotResult write_plot(const Scene& scene, const SceneCheck& check, const std::filesystem::path& dir,
                      const std::string& page_markdown) {
  PlotResult result;
  const SceneViews shown = scene_views(scene, check);
  const report::Views& views = shown.views;
  const SurfaceCheck* first_virtual = shown.first_virtual;
  try {
    report::ReportFiles files(dir);
    files.open("scene.html") << report::views_html(views, page_markdown, {});
    report::stage_views(files, views);
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
    if (first_virtual) {
      // Top (x, z) or side (z, y): the one whose axes hold more of the surface's normal.
      const Vector3& n = scene.surfaces[first_virtual->path.back()].normal;
      const bool side = std::abs(n.y()) > std::abs(n.x());  // a wall facing z: the floor plan
      const std::filesystem::path png = dir / (side ? "side.png" : "top.png");
      if (std::find(result.written.begin(), result.written.end(), png) != result.written.end()) {
        result.across = png;
        result.across_surface = first_virtual->name;
      }
    }
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  return result;
}

}  // namespace oblique::scene
