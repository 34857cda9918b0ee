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

namespace oblique::scene {

std::vector<Segment> volume_edges(const Matrix4<double>& view, const Matrix4<double>& projection,
                                  Convention convention, double reach,
                                  const std::array<double, 4>& rect) {
  const Matrix4<double> to_clip = projection * view;
  const Matrix4<double> inverse = to_clip.inverse();
  const DepthRange range = clip_depth_range(convention);
  // The planes, as coefficients on clip coordinates: the rectangle's four sides, then depth.
  const std::array<Vector4<double>, 6> clip = {
      Vector4<double>(1, 0, 0, -rect[0]),
      Vector4<double>(-1, 0, 0, rect[2]),
      Vector4<double>(0, 1, 0, -rect[1]),
      Vector4<double>(0, -1, 0, rect[3]),
      Vector4<double>(0, 0, -1, 1),
      convention == Convention::gl ? Vector4<double>(0, 0, 1, 1) : Vector4<double>(0, 0, 1, 0)};
  std::vector<Vector4<double>> world_planes;  // q . (p, 1) >= 0
  for (const Vector4<double>& c : clip) world_planes.push_back(to_clip.transpose() * c);
  std::vector<Vector3> low, high;
  for (const auto& [sx, sy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    const double ex = sx < 0 ? rect[0] : rect[2], ey = sy < 0 ? rect[1] : rect[3];
    // Two points of the edge line x = ex w, y = ey w (the same line for every depth row): on the
    // near face (reversed Z: z = 1) and on the far face (a direction when the far face is at
    // infinity). The line is walked from its near point, so `reach` counts from there.
    const double near_z = convention == Convention::reversed_z ? 1 : range.z_low;
    const double far_z = convention == Convention::reversed_z ? 0 : 1;
    const Vector4<double> a = inverse * Vector4<double>(ex, ey, near_z, 1);
    const Vector4<double> b = inverse * Vector4<double>(ex, ey, far_z, 1);
    if (!(std::abs(a.w()) > 0)) return {};
    const Vector3 p = a.head<3>() / a.w();
    const Vector3 d = std::abs(b.w()) > 1e-12 * std::abs(a.w()) ? Vector3(b.head<3>() / b.w() - p)
                                                                : Vector3(b.head<3>());
    if (!(d.norm() > 0) || !p.allFinite() || !d.allFinite()) return {};
    // Every plane and w > 0: q . (p + t d, 1) = q . (p, 1) + t q . (d, 0), linear in t.
    const double limit = reach / d.norm();
    double t0 = -limit, t1 = limit;
    // The edge lies in two side planes (x = sx w, y = sy w): left out, since rounding puts it a
    // hair outside them.
    std::vector<Vector4<double>> constraints;
    for (std::size_t k = 0; k < world_planes.size(); ++k) {
      if (k == (sx < 0 ? 0u : 1u) || k == (sy < 0 ? 2u : 3u)) continue;
      constraints.push_back(world_planes[k]);
    }
    constraints.push_back(to_clip.row(3).transpose());
    for (const Vector4<double>& q : constraints) {
      const double c = q.head<3>().dot(p) + q.w(), k = q.head<3>().dot(d);
      if (k > 0) {
        t0 = std::max(t0, -c / k);
      } else if (k < 0) {
        t1 = std::min(t1, -c / k);
      } else if (c < 0) {
        t1 = t0 - 1;
      }
    }
    if (!(t0 <= t1)) continue;  // this edge is cut away entirely
    low.push_back(p + t0 * d);
    high.push_back(p + t1 * d);
  }
  std::vector<Segment> out;
  for (std::size_t i = 0; i < low.size(); ++i) {
    out.push_back({low[i], high[i]});
    out.push_back({low[i], low[(i + 1) % low.size()]});
    out.push_back({high[i], high[(i + 1) % high.size()]});
  }
  return out;
}

namespace {

/// A name as a single-quoted gnuplot string: ' doubled, control characters dropped.
std::string gnuplot_string(const std::string& name) {
  std::string out = "'";
  for (const char ch : name) {
    if (ch == '\'') {
      out += "''";
    } else if (static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f) {
      out += ch;
    }
  }
  return out + "'";
}

struct Dataset {
  std::string title, style;
  std::vector<Segment> segments;
};

}  // namespace

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
  sets.push_back(
      {"main view volume", "lc rgb 'black' lw 2",
       volume_edges(scene.camera.view, scene.camera.projection, scene.convention, reach)});
  for (const Surface& s : scene.surfaces) {
    Dataset d{s.name, "lc rgb 'blue' lw 3", {}};
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
                    "lc rgb '" + std::string(colors[color++ % 8]) + "' dt 2 lw 1.5",
                    volume_edges(s.view, *s.projection, scene.convention, reach, rect)});
  }
  try {
    report::ReportFiles files(dir);
    {
      std::ostream& data = files.open("scene.dat");
      for (const Dataset& d : sets) {
        data << "# " << gnuplot_string(d.title) << "\n";
        for (const Segment& seg : d.segments) {
          for (const Vector3& p : {seg.a, seg.b}) {
            data << protocol::format_number(p.x()) << " " << protocol::format_number(p.y()) << " "
                 << protocol::format_number(p.z()) << "\n";
          }
          data << "\n";
        }
        if (d.segments.empty()) data << "nan nan nan\n\n";
        data << "\n";
      }
    }
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
    for (const auto& [view, columns, xlabel, ylabel, axes] :
         {std::tuple{"top", "1:3", "world x", "world z", std::array<int, 2>{0, 2}},
          std::tuple{"side", "3:2", "world z", "world y", std::array<int, 2>{2, 1}}}) {
      const std::string script = std::string(view) + ".gp", png = std::string(view) + ".png";
      std::ostream& gp = files.open(script);
      gp << "set terminal pngcairo size 1000,800 noenhanced\n"
         << "set output " << gnuplot_string((dir / png).string()) << "\n"
         << "set title " << gnuplot_string(check.scene + ": " + view + " view") << "\n"
         << "set xlabel '" << xlabel << "'\nset ylabel '" << ylabel << "'\n"
         << "set size ratio -1\nset key below\nset grid\n"
         << "set xrange [" << protocol::format_number(lo[axes[0]]) << ":"
         << protocol::format_number(hi[axes[0]]) << "]\n"
         << "set yrange [" << protocol::format_number(lo[axes[1]]) << ":"
         << protocol::format_number(hi[axes[1]]) << "]\n"
         << "plot \\\n";
      for (std::size_t i = 0; i < sets.size(); ++i) {
        gp << "  " << gnuplot_string((dir / "scene.dat").string()) << " index " << i << " using "
           << columns << " with lines " << sets[i].style << " title "
           << gnuplot_string(sets[i].title) << (i + 1 < sets.size() ? ", \\\n" : "\n");
      }
    }
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
