// Polygons clipped as a GPU clips them: homogeneous clipping against each plane of the view
// volume (Sutherland-Hodgman), then the NDC rectangle a pass's scissor covers.
#include <algorithm>
#include <cmath>
#include <vector>

#include "oblique/scene/check.h"

namespace oblique::scene {

namespace {

/// Clips a convex or concave polygon (homogeneous clip coordinates) by a x + b y + c z + d w >= 0
/// (Sutherland-Hodgman).
std::vector<Vector4<double>> clip_by(const std::vector<Vector4<double>>& in,
                                     const Vector4<double>& plane) {
  std::vector<Vector4<double>> out;
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector4<double>& a = in[i];
    const Vector4<double>& b = in[(i + 1) % n];
    const double da = plane.dot(a), db = plane.dot(b);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out;
}

}  // namespace

std::optional<Scissor> clip_polygon(const std::vector<Vector3>& polygon,
                                    const Matrix4<double>& view, const Matrix4<double>& projection,
                                    Convention convention, const std::optional<Scissor>& within,
                                    const std::optional<std::array<int, 2>>& viewport) {
  const Matrix4<double> to_clip = projection * view;
  std::vector<Vector4<double>> points;
  for (const Vector3& v : polygon)
    points.push_back(to_clip * Vector4<double>(v.x(), v.y(), v.z(), 1));
  // The six planes of the view volume (depth: gl -w <= z <= w; zero_one and reversed_z
  // 0 <= z <= w), then the parent's rectangle.
  std::vector<Vector4<double>> planes = {
      {1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, -1, 1}};
  planes.push_back(convention == Convention::gl ? Vector4<double>(0, 0, 1, 1)
                                                : Vector4<double>(0, 0, 1, 0));
  if (within) {
    planes.push_back({1, 0, 0, -within->x0});
    planes.push_back({-1, 0, 0, within->x1});
    planes.push_back({0, 1, 0, -within->y0});
    planes.push_back({0, -1, 0, within->y1});
  }
  for (const Vector4<double>& plane : planes) {
    points = clip_by(points, plane);
    if (points.size() < 3) return std::nullopt;
  }
  std::vector<Eigen::Vector2d> ndc;
  for (const Vector4<double>& p : points) {
    if (!(p.w() > 0) || !p.allFinite()) continue;  // on the eye plane: no screen position
    ndc.emplace_back(p.x() / p.w(), p.y() / p.w());
  }
  if (ndc.size() < 3) return std::nullopt;
  Scissor s;
  s.x0 = s.y0 = INFINITY;
  s.x1 = s.y1 = -INFINITY;
  double twice_area = 0;
  for (std::size_t i = 0; i < ndc.size(); ++i) {
    const Eigen::Vector2d& a = ndc[i];
    const Eigen::Vector2d& b = ndc[(i + 1) % ndc.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
    s.x0 = std::min(s.x0, std::clamp(a.x(), -1.0, 1.0));
    s.x1 = std::max(s.x1, std::clamp(a.x(), -1.0, 1.0));
    s.y0 = std::min(s.y0, std::clamp(a.y(), -1.0, 1.0));
    s.y1 = std::max(s.y1, std::clamp(a.y(), -1.0, 1.0));
  }
  s.ndc_area = std::abs(twice_area) / 2;
  if (!(s.ndc_area > 0) || !std::isfinite(s.ndc_area)) return std::nullopt;  // edge-on
  if (viewport) {
    const double w = (*viewport)[0], h = (*viewport)[1];
    auto px = [](double ndc, double size, bool up) {
      const double x = (ndc + 1) / 2 * size;
      return static_cast<int>(std::clamp(up ? std::ceil(x) : std::floor(x), 0.0, size));
    };
    const int x0 = px(s.x0, w, false), x1 = px(s.x1, w, true);
    const int y0 = px(s.y0, h, false), y1 = px(s.y1, h, true);
    s.pixels = std::array<int, 4>{x0, y0, x1 - x0, y1 - y0};
    s.covered_pixels = std::min(s.ndc_area, 4.0) / 4 * w * h;
  }
  return s;
}

}  // namespace oblique::scene
