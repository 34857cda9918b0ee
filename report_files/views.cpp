#include "oblique/report/views.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <tuple>
#include <utility>

#include "oblique/protocol/numbers.h"

namespace oblique::report {

std::vector<Segment> volume_edges(const Matrix4<double>& view, const Matrix4<double>& projection,
                                  Convention convention, double reach,
                                  const std::array<double, 4>& rect) {
  using Vector3 = Eigen::Vector3d;
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

void stage_views(ReportFiles& files, const Views& views) {
  {
    std::ostream& data = files.open(views.data);
    auto write_point = [&data](const Eigen::Vector3d& p) {
      data << protocol::format_number(p.x()) << " " << protocol::format_number(p.y()) << " "
           << protocol::format_number(p.z()) << "\n";
    };
    for (const Dataset& d : views.sets) {
      data << "# " << gnuplot_string(d.title) << "\n";
      // Each segment is a block (a blank line ends it); two blank lines end the dataset.
      bool blank = false;
      for (const Segment& seg : d.segments) {
        write_point(seg.a);
        write_point(seg.b);
        data << "\n";
        blank = true;
      }
      for (const Eigen::Vector3d& p : d.points) {
        write_point(p);
        blank = false;
      }
      if (d.segments.empty() && d.points.empty()) {
        data << "nan nan nan\n";
        blank = false;
      }
      data << (blank ? "\n" : "\n\n");
    }
  }
  const std::string data_path = views.data;
  for (const auto& [stem, view, columns, axes] :
       {std::tuple{views.top, "top", "1:3", std::array<int, 2>{0, 2}},
        std::tuple{views.side, "side", "3:2", std::array<int, 2>{2, 1}}}) {
    const char* names = "xyz";
    std::ostream& gp = files.open(stem + ".gp");
    // The canvas is shaped to the view (equal scales on both axes), the legend beside it: the
    // plot fills its height, whatever the box's proportions.
    const double aspect = (views.hi[axes[0]] - views.lo[axes[0]]) /
                          std::max(1e-300, views.hi[axes[1]] - views.lo[axes[1]]);
    const int plot_width = static_cast<int>(std::clamp(560 * aspect, 420.0, 1100.0));
    gp << "set terminal pngcairo size " << plot_width + 520 << ",720 noenhanced font ',11'\n"
       << "set output " << gnuplot_string(stem + ".png")
       << "\n"
       // The title from the canvas's left edge (a long one over the plot would be cut).
       << "set label " << gnuplot_string(std::string(view) + " view: " + views.title)
       << " at screen 0.01, 0.97 left front font ',12'\nset tmargin 3\n"
       << "set xlabel '" << views.space << " " << names[axes[0]] << "'\nset ylabel '" << views.space
       << " " << names[axes[1]] << "'\n"
       << "set size ratio -1\nset key " << views.key << "\nset grid\n"
       << "set xrange [" << protocol::format_number(views.lo[axes[0]]) << ":"
       << protocol::format_number(views.hi[axes[0]]) << "]\n"
       << "set yrange [" << protocol::format_number(views.lo[axes[1]]) << ":"
       << protocol::format_number(views.hi[axes[1]]) << "]\n";
    // Labels that fall on one spot of this view share one text; a label in the right half is
    // written to the left of its point, so it stays inside the picture.
    const double width = views.hi[axes[0]] - views.lo[axes[0]];
    const double height = views.hi[axes[1]] - views.lo[axes[1]];
    std::vector<std::pair<Eigen::Vector2d, std::string>> spots;
    for (const Label& label : views.labels) {
      const Eigen::Vector2d at(label.at[axes[0]], label.at[axes[1]]);
      auto same = std::find_if(spots.begin(), spots.end(), [&](const auto& spot) {
        return std::abs(spot.first.x() - at.x()) <= 0.02 * width &&
               std::abs(spot.first.y() - at.y()) <= 0.02 * height;
      });
      if (same == spots.end())
        spots.emplace_back(at, label.text);
      else
        same->second += ", " + label.text;
    }
    // A label near one placed before (within a line's height and its text's width) goes a line
    // lower each time, so none is written over another.
    std::vector<std::pair<Eigen::Vector2d, int>> placed;  // where, and its line offset
    for (const auto& [at, text] : spots) {
      const bool right_half = at.x() > views.lo[axes[0]] + width / 2;
      int line = 1;
      for (bool moved = true; moved;) {
        moved = false;
        for (const auto& [other, other_line] : placed) {
          if (other_line == line && std::abs(other.y() - at.y()) < 0.06 * height &&
              std::abs(other.x() - at.x()) < 0.35 * width) {
            --line;
            moved = true;
          }
        }
      }
      placed.emplace_back(at, line);
      gp << "set label " << gnuplot_string(text) << " at " << protocol::format_number(at.x()) << ","
         << protocol::format_number(at.y())
         << (right_half ? " right offset -1," : " left offset 1,") << line << " front\n";
    }
    gp << "plot \\\n";
    for (std::size_t i = 0; i < views.sets.size(); ++i) {
      gp << "  " << gnuplot_string(data_path) << " index " << i << " using " << columns << " with "
         << views.sets[i].style << " title " << gnuplot_string(views.sets[i].title)
         << (i + 1 < views.sets.size() ? ", \\\n" : "\n");
    }
  }
}

}  // namespace oblique::report
