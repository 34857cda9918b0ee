#include "oblique/report/depth_report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ostream>
#include <sstream>

#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/report/report_files.h"

namespace oblique::report {
namespace {

constexpr double kPi = 3.14159265358979323846;

Matrix4<double> base_projection(const DepthOptions& o, Convention c) {
  return perspective<double>(o.fovy_degrees * kPi / 180, o.aspect, o.near_distance, o.far_distance,
                             c);
}

/// The plane at `angle` from the -z axis (normal tilted toward +x), `distance` from the eye,
/// keeping the side away from the eye: C = (sin t, 0, -cos t, -distance).
Vector4<double> tilted_plane(double angle_degrees, double distance) {
  const double t = angle_degrees * kPi / 180;
  return Vector4<double>(std::sin(t), 0, -std::cos(t), -distance);
}

/// NDC z of the camera-space point s V (w = 1), in long double.
long double ndc_depth(const Matrix4<double>& m, const Eigen::Vector3d& v, long double s) {
  long double z = 0, w = 0;
  for (int j = 0; j < 3; ++j) {
    z += static_cast<long double>(m(2, j)) * s * static_cast<long double>(v(j));
    w += static_cast<long double>(m(3, j)) * s * static_cast<long double>(v(j));
  }
  z += static_cast<long double>(m(2, 3));
  w += static_cast<long double>(m(3, 3));
  return z / w;
}

/// Window depth in [0, 1] as stored: glDepthRange(0, 1) maps gl's [-1, 1]; the others are as is.
long double window_depth(long double ndc, Convention c) {
  return c == Convention::gl ? (ndc + 1) / 2 : ndc;
}

/// Distinct depth values between two window depths (both in [0, 1]), as bits
/// (depth_buffer_values()).
double fixed24_bits(long double a, long double b) {
  return std::log2(depth_buffer_values(a, b, DepthBuffer::fixed24));
}
double float32_bits(long double a, long double b) {
  return std::log2(depth_buffer_values(a, b, DepthBuffer::float32));
}

std::string fixed(double x, int digits = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

}  // namespace

DepthReport measure_depth(const DepthOptions& options) {
  DepthReport report;
  const Eigen::Vector3d axis(0, 0, -1);
  for (int i = 0; i <= 36; ++i) {
    const double angle = 2.5 * i;  // 0 .. 90 degrees
    for (int j = 1; j < 40; ++j) {
      // f / 40 .. 39 f / 40: at d = f the plane is within rounding of the far corner for the
      // axis-aligned planes, and the conventions disagree on whether an answer exists.
      const double distance = options.far_distance * j / 40;
      Figure5Point p;
      p.angle_degrees = angle;
      p.distance = distance;
      const Vector4<double> c = tilted_plane(angle, distance);
      for (int k = 0; k < 3; ++k) {
        const Convention convention = all_conventions[k];
        const ObliqueResult<double> r =
            apply<double>(base_projection(options, convention), c, convention, Method::accurate);
        if (!r.ok()) break;
        const Matrix4<double>& m = r.projection;
        // Eq. 17's limit for s -> infinity along V = (0, 0, -1, 0): (M'_3 . V) / (M'_4 . V).
        const long double limit = static_cast<long double>(m(2, 2)) / m(3, 2);
        const DepthRange range = clip_depth_range(convention);
        const double near_value = near_rows(convention).m3 > 0 ? range.z_low : range.z_high;
        p.reachable[k] = std::min(
            1.0, static_cast<double>(std::abs(limit - near_value) / (range.z_high - range.z_low)));
        if (convention == Convention::gl) {
          p.answered = true;
          p.z_max_matrix = static_cast<double>(limit);
          p.matrix = m;
          // Eq. 19 with a = 2 / (C . Q) read off the matrix: a C = M'_3 + M_4.
          const double a = (m(2, 2) + m(3, 2)) / c.z();
          p.z_max_eq19 =
              -(a * c.dot(Vector4<double>(axis.x(), axis.y(), axis.z(), 0)) + axis.z()) / axis.z();
        }
      }
      if (p.answered) {
        report.eq19_vs_matrix_max_gap =
            std::max(report.eq19_vs_matrix_max_gap, std::abs(p.z_max_eq19 - p.z_max_matrix));
        const auto [lo, hi] = std::minmax({p.reachable[0], p.reachable[1], p.reachable[2]});
        report.convention_max_gap = std::max(report.convention_max_gap, hi - lo);
      }
      report.figure5.push_back(p);
    }
  }

  // Depth values used along directions: the axis and the four corner directions of the frustum.
  const double top = std::tan(options.fovy_degrees * kPi / 360), right = top * options.aspect;
  const std::pair<const char*, Eigen::Vector3d> directions[] = {
      {"axis", axis},
      {"toward +x corner", Eigen::Vector3d(0.95 * right, 0.95 * top, -1)},
      {"toward -x corner", Eigen::Vector3d(-0.95 * right, 0.95 * top, -1)}};
  const double angles[] = {0, 15, 30, 45, 60, 75};
  const double distances[] = {options.near_distance, options.far_distance / 10,
                              options.far_distance / 2};
  for (double angle : angles) {
    for (double distance : distances) {
      const Vector4<double> c = tilted_plane(angle, distance);
      for (Convention convention : all_conventions) {
        const Matrix4<double> m = base_projection(options, convention);
        const ObliqueResult<double> r = apply<double>(m, c, convention, Method::accurate);
        if (!r.ok()) continue;
        for (const auto& [name, v] : directions) {
          // The original frustum along V: from the near plane to the far plane (z = -n, -f).
          const long double s_far = options.far_distance / -v.z();
          // The oblique one: from where V crosses C (or the eye) to the original far plane.
          const double cv = c.head<3>().dot(v);
          if (!(cv > 0)) continue;  // V never reaches C's kept side
          const long double s_plane = std::max(0.0L, static_cast<long double>(-c.w()) / cv);
          if (!(s_plane < s_far)) continue;
          DepthBitsRow row;
          row.angle_degrees = angle;
          row.distance = distance;
          row.convention = std::string(convention_name(convention));
          row.direction = name;
          // The original frustum uses the whole depth range along V, from its near plane to its
          // far plane; the oblique one from C to where V leaves the original view volume (the
          // original far plane: the oblique frustum clips none of it). Ends on a clip plane take
          // its depth exactly (a rounded 1e-17 instead of 0 would count the 2^29 floats below
          // it); the oblique far end, inside the range, is computed.
          const DepthRange range = clip_depth_range(convention);
          const bool reversed = convention == Convention::reversed_z;
          const long double near_face =
                                window_depth(reversed ? range.z_high : range.z_low, convention),
                            far_face =
                                window_depth(reversed ? range.z_low : range.z_high, convention);
          const long double o0 = near_face, o1 = far_face;
          const long double q0 = near_face,
                            q1 = window_depth(ndc_depth(r.projection, v, s_far), convention);
          row.fixed24_bits_original = fixed24_bits(o0, o1);
          row.fixed24_bits_oblique = fixed24_bits(q0, q1);
          row.float32_bits_original = float32_bits(o0, o1);
          row.float32_bits_oblique = float32_bits(q0, q1);
          report.bits.push_back(row);
        }
      }
    }
  }
  return report;
}

bool add_measured(DepthReport& report, const AxisLimitMeasure& measure, const std::string& renderer,
                  std::string& error) {
  std::vector<Eigen::Matrix4d> matrices;
  std::vector<Figure5Point*> points;
  for (Figure5Point& p : report.figure5) {
    if (!p.answered) continue;
    matrices.push_back(p.matrix);
    points.push_back(&p);
  }
  const auto depths = measure(matrices, error);
  if (!depths || depths->size() != matrices.size()) {
    if (error.empty()) error = "the rasterizer measured no depth";
    return false;
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    Figure5Point& p = *points[k];
    // gl: NDC z = 2 d - 1; a clipped V lies beyond the far plane: the whole range is reachable.
    p.z_max_measured = (*depths)[k] ? std::min(1.0, 2 * *(*depths)[k] - 1) : 1.0;
    report.measured_max_gap =
        std::max(report.measured_max_gap, std::abs(p.z_max_measured - std::min(1.0, p.z_max_eq19)));
  }
  report.measured_on = renderer;
  report.measured_points = static_cast<long>(points.size());
  return true;
}

std::optional<std::vector<std::filesystem::path>> write_depth_report(const DepthReport& report,
                                                                     const DepthOptions& options,
                                                                     std::ostream& log) {
  ReportFiles files(options.out_dir);
  {
    std::ostream& csv = files.open("figure5.csv");
    csv << "angle_degrees,distance,answered,z_max_eq19,z_max_matrix,reachable_gl,"
           "reachable_zero_one,reachable_reversed_z,z_max_measured\n";
    csv.precision(17);
    for (const Figure5Point& p : report.figure5) {
      csv << p.angle_degrees << ',' << p.distance << ',' << (p.answered ? 1 : 0) << ','
          << p.z_max_eq19 << ',' << p.z_max_matrix << ',' << p.reachable[0] << ',' << p.reachable[1]
          << ',' << p.reachable[2] << ',' << p.z_max_measured << '\n';
    }
  }
  {
    // gnuplot grid: blocks by angle, NaN where the plane misses the view volume.
    std::ostream& dat = files.open("figure5.dat");
    double angle = -1;
    for (const Figure5Point& p : report.figure5) {
      if (p.angle_degrees != angle && angle >= 0) dat << '\n';
      angle = p.angle_degrees;
      dat << p.angle_degrees << ' ' << p.distance << ' ';
      if (p.answered) {
        dat << std::min(1.0, p.z_max_eq19) << '\n';
      } else {
        dat << "NaN\n";
      }
    }
  }
  {
    std::ostream& csv = files.open("depth_bits.csv");
    csv << "angle_degrees,distance,convention,direction,fixed24_bits_original,"
           "fixed24_bits_oblique,fixed24_bits_lost,float32_bits_original,float32_bits_oblique,"
           "float32_bits_lost\n";
    csv.precision(6);
    for (const DepthBitsRow& r : report.bits) {
      csv << r.angle_degrees << ',' << r.distance << ',' << r.convention << ',' << r.direction
          << ',' << r.fixed24_bits_original << ',' << r.fixed24_bits_oblique << ','
          << r.fixed24_bits_original - r.fixed24_bits_oblique << ',' << r.float32_bits_original
          << ',' << r.float32_bits_oblique << ','
          << r.float32_bits_original - r.float32_bits_oblique << '\n';
    }
  }
  {
    std::ostream& md = files.open("depth.md");
    md << "Frustum: gluPerspective " << options.fovy_degrees << " degrees, aspect "
       << options.aspect << ", n = " << options.near_distance << ", f = " << options.far_distance
       << "; plane C = (sin t, 0, -cos t, -d). Eq. 19 against the core's matrix: largest gap "
       << report.eq19_vs_matrix_max_gap
       << "; reachable fraction, largest spread across the three conventions: "
       << report.convention_max_gap << ".\n\n";
    md << "Distinct depth values along the view axis on the stretch the oblique frustum keeps "
          "(from "
          "the plane to the original far plane), as bits: original matrix / oblique matrix, and "
          "the bits lost (negative: gained), 24-bit fixed point and 32-bit float:\n\n| angle | d | "
          "convention | fixed 24 | float 32 "
          "|\n|---:|---:|---|---|---|\n";
    for (const DepthBitsRow& r : report.bits) {
      if (r.direction != "axis") continue;
      md << "| " << r.angle_degrees << " | " << r.distance << " | " << r.convention << " | "
         << fixed(r.fixed24_bits_original) << " / " << fixed(r.fixed24_bits_oblique) << ", "
         << fixed(r.fixed24_bits_original - r.fixed24_bits_oblique) << " lost | "
         << fixed(r.float32_bits_original) << " / " << fixed(r.float32_bits_oblique) << ", "
         << fixed(r.float32_bits_original - r.float32_bits_oblique) << " lost |\n";
    }
    md << "\ndepth_bits.csv has the same for two directions toward far corners of the frustum.\n";
    if (report.measured_points > 0)
      md << "\nFigure 5 measured on " << report.measured_on << ": the axis's point at infinity "
         << "drawn with each of the " << report.measured_points
         << " gl matrices into a 32-bit float depth buffer and read back (clipped: 1); largest "
            "gap to Eq. 19 clamped to 1: "
         << report.measured_max_gap << " (figure5_measured.png).\n";
  }
  if (report.measured_points > 0) {
    // A few angles: Eq. 19 (clamped) as lines, the rasterizer's values as points.
    std::ostream& dat = files.open("figure5_measured.dat");
    const double angles[] = {0, 30, 60, 75};
    for (const double angle : angles) {
      dat << "# angle " << angle << "\n";
      for (const Figure5Point& p : report.figure5) {
        if (p.angle_degrees != angle || !p.answered) continue;
        dat << p.distance << ' ' << std::min(1.0, p.z_max_eq19) << ' ' << p.z_max_measured << '\n';
      }
      dat << "\n\n";
    }
    std::ostream& gp = files.open("figure5_measured.gp");
    gp << "set terminal pngcairo size 900,650 noenhanced\nset output '"
       << (options.out_dir / "figure5_measured.png").string()
       << "'\nset title 'Figure 5 measured on "
       << report.measured_on.substr(0, report.measured_on.find(" ("))
       << ": max NDC z along the view axis (gl)'\nset xlabel 'distance from the camera to the "
          "plane'\nset ylabel 'max NDC z (clamped to 1)'\nset key outside below\nset grid\n"
          "plot ";
    const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728"};
    for (int i = 0; i < 4; ++i) {
      const std::string data = "'" + (options.out_dir / "figure5_measured.dat").string() + "'";
      gp << (i ? ", " : "") << data << " index " << i << " using 1:2 with lines lw 2 lc rgb '"
         << colours[i] << "' title 'Eq. 19, " << angles[i] << " degrees', " << data << " index "
         << i << " using 1:3 with points pt 7 ps 0.8 lc rgb '" << colours[i]
         << "' title 'measured, " << angles[i] << " degrees'";
    }
    gp << "\n";
  }
  {
    std::ostream& gp = files.open("figure5.gp");
    gp << "set terminal pngcairo size 900,650 noenhanced\nset output '"
       << (options.out_dir / "figure5.png").string()
       << "'\nset title 'Figure 5 reproduced: max NDC z along the view axis (Eq. 19, gl), clamped "
          "to 1'\nset xlabel 'angle between the plane normal and -z (degrees)'\n"
          "set ylabel 'distance from the camera to the plane'\nset view map\nset pm3d at b\n"
          "set palette rgbformulae 33,13,10\nset cbrange [-1:1]\nset cblabel 'max NDC z'\n"
          "set contour base\nset cntrparam levels discrete -0.5,0,0.5,0.9,0.99\n"
          "unset surface\nset key off\nsplot '"
       << (options.out_dir / "figure5.dat").string() << "' using 1:2:3 with pm3d\n";
  }
  if (!files.commit(log)) return std::nullopt;
  files.plot("figure5.gp", "figure5.png", log);
  if (report.measured_points > 0) files.plot("figure5_measured.gp", "figure5_measured.png", log);
  return files.written();
}

}  // namespace oblique::report
