// Reading a depth buffer back under any projection, the oblique one included (the reference of
// `oblique::testing`'s depth-reconstruction properties: what SSAO, fog, SSR and decals need).
//
//   window depth  d = (z_ndc + 1) / 2 (gl), d = z_ndc (zero_one, reversed_z), for the default
//                 depth range [0, 1];
//   view position p = v / v_w with v = M^-1 (x_ndc, y_ndc, z_ndc, 1): the camera-space point the
//                 pixel ray at NDC (x, y) meets where M gives window depth d.
//
// The oblique matrix M' has the same rows 1, 2 and 4 as M but its own third row, so a depth
// written through M' means a different point than the same depth under M: the textbook
// linearisation n f / (f - d (f - n)) (zero_one) or 2 n f / (f + n - z (f - n)) (gl), which
// reads n and f off M, is wrong for every pixel but those on the view axis at C's own depth.
// Reconstruct through M'^-1 (this header) instead.
#pragma once

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/util/enum_names.h"

namespace oblique {

template <class T>
using Vector3 = Eigen::Matrix<T, 3, 1>;

/// How a depth buffer stores window depth d in [0, 1]: fixed24 keeps the integer k = round(d (2^24
/// - 1)) and reads back k / (2^24 - 1); float32 keeps d rounded to float.
enum class DepthBuffer { fixed24, float32 };

/// "fixed24" or "float32", as scenes, reports and the protocol name them.
inline constexpr EnumName<DepthBuffer> depth_buffer_names[] = {{DepthBuffer::fixed24, "fixed24"},
                                                               {DepthBuffer::float32, "float32"}};

constexpr std::string_view depth_buffer_name(DepthBuffer buffer) noexcept {
  return name_in(depth_buffer_names, buffer);
}
/// Inverse of depth_buffer_name(); none for an unknown name.
constexpr std::optional<DepthBuffer> parse_depth_buffer(std::string_view name) noexcept {
  return value_in(depth_buffer_names, name);
}

/// The largest value of a fixed24 depth buffer.
inline constexpr unsigned kFixed24Max = (1u << 24) - 1;

/// How many values `buffer` holds between window depths a and b (clamped to [0, 1]), both ends
/// counted: fixed24, the integers between round(a (2^24 - 1)) and round(b (2^24 - 1)); float32,
/// the floats between a and b rounded to float (their bit patterns order like the numbers for
/// non-negative floats). log2 of it is the bits the stretch uses.
template <class T>
double depth_buffer_values(T a, T b, DepthBuffer buffer) {
  const T lo = std::max(T(0), std::min(T(1), std::min(a, b)));
  const T hi = std::max(T(0), std::min(T(1), std::max(a, b)));
  if (buffer == DepthBuffer::fixed24) {
    const T scale = T(kFixed24Max);
    return static_cast<double>(std::nearbyint(hi * scale) - std::nearbyint(lo * scale)) + 1;
  }
  auto pattern = [](T x) {
    const float f = static_cast<float>(x);
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    return u;
  };
  return static_cast<double>(pattern(hi) - pattern(lo)) + 1;
}

/// The window depth (depth range [0, 1]) of NDC depth z.
template <class T>
T window_depth(T ndc_z, Convention convention) {
  return convention == Convention::gl ? (ndc_z + T(1)) / T(2) : ndc_z;
}

/// The NDC depth of window depth d (the inverse of window_depth()).
template <class T>
T ndc_depth(T window, Convention convention) {
  return convention == Convention::gl ? T(2) * window - T(1) : window;
}

/// M^-1 (x, y, z_ndc, 1) for window depth `depth`: the homogeneous camera-space point, w not
/// divided out (w = 0: the ray's point at infinity; w < 0: behind the eye of a perspective M).
template <class T>
Vector4<T> unproject(const Matrix4<T>& m, T ndc_x, T ndc_y, T depth, Convention convention) {
  return m.partialPivLu().solve(Vector4<T>(ndc_x, ndc_y, ndc_depth(depth, convention), T(1)));
}

/// The camera-space point the pixel at NDC (x, y) with stored window depth `depth` stands for,
/// under the projection `m` the depth was rendered with: unproject() divided by its w.
template <class T>
Vector3<T> view_position(const Matrix4<T>& m, T ndc_x, T ndc_y, T depth, Convention convention) {
  const Vector4<T> v = unproject(m, ndc_x, ndc_y, depth, convention);
  return v.template head<3>() / v.w();
}

/// The world point the pixel stands for, through the pass camera's `view` (world -> camera,
/// affine): view_position() carried by view^-1. (Not through the inverse of m view computed in
/// T: the condition of m view grows with the square of the camera's distance from the origin,
/// and in float, a few thousand units out, that inverse has no correct digit.)
template <class T>
Vector3<T> world_position(const Matrix4<T>& m, const Matrix4<T>& view, T ndc_x, T ndc_y, T depth,
                          Convention convention) {
  const Vector3<T> v = view_position(m, ndc_x, ndc_y, depth, convention);
  return (view.inverse() * Vector4<T>(v.x(), v.y(), v.z(), T(1))).template head<3>();
}

/// +1 when the camera looks along +z (left-handed camera space), -1 along -z (OpenGL's
/// right-handed one): the sign of the camera-space z of the centre of `original`'s view volume
/// (the unmodified projection, perspective or orthographic, looking along z: its fourth row is
/// (0, 0, a, b); for any other, linear depth is not defined).
template <class T>
int view_axis_sign(const Matrix4<T>& original, Convention convention) {
  const DepthRange range = clip_depth_range(convention);
  const T middle = T(range.z_low + range.z_high) / T(2);
  const Vector4<T> v = original.partialPivLu().solve(Vector4<T>(0, 0, middle, 1));
  return (v.z() > 0) == (v.w() > 0) ? 1 : -1;
}

/// Linear (view) depth: the distance of view_position() in front of the camera along its axis,
/// axis_sign * z, axis_sign = view_axis_sign(original).
template <class T>
T linear_depth(const Matrix4<T>& m, T ndc_x, T ndc_y, T depth, Convention convention,
               int axis_sign) {
  return T(axis_sign) * view_position(m, ndc_x, ndc_y, depth, convention).z();
}

}  // namespace oblique
