// The implementation behind lengyel.h: the formulas, the solver and the JSON Lines adapter,
// compiled once for every example program.
#include "lengyel.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <string>

namespace lengyel {

inline bool has_sign_by_division(Mistake m) {
  return m == Mistake::sign_by_division || m == Mistake::two_bugs;
}
/// M12 = M14 = M21 = M24 = M31 = M32 = M41 = M42 = M44 = 0, M43 != 0 (row-major): the matrices
/// glFrustum and its [0, 1] and reversed-Z variants make, flipped or not. There C' = M^-T C has
/// C'_x = C_x / M11 and C'_y = C_y / M22.
template <class T>
bool perspective_shape(const T (&m)[16]) {
  for (int i : {1, 3, 4, 7, 8, 9, 12, 13, 15}) {
    if (m[i] != T(0)) return false;
  }
  return m[14] != T(0);
}

inline bool has_no_camera_guard(Mistake m) {
  return m == Mistake::no_camera_guard || m == Mistake::two_bugs || m == Mistake::no_statuses;
}

template <class T>
T sgn(T x, Mistake mistake) {
  if (has_sign_by_division(mistake)) return x / std::abs(x);
  return x > 0 ? T(1) : (x < 0 ? T(-1) : T(0));
}

/// Solves A x = b (4 x 4, row-major) by Gaussian elimination with partial pivoting; false when
/// a pivot is zero. `transpose` solves A^T x = b.
template <class T>
bool eliminate(const T (&a)[16], bool transpose, const T (&b)[4], T (&x)[4]) {
  T m[4][5];
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) m[i][j] = transpose ? a[4 * j + i] : a[4 * i + j];
    m[i][4] = b[i];
  }
  for (int k = 0; k < 4; ++k) {
    int p = k;
    for (int i = k + 1; i < 4; ++i) {
      if (std::abs(m[i][k]) > std::abs(m[p][k])) p = i;
    }
    if (m[p][k] == T(0)) return false;
    for (int j = 0; j < 5; ++j) std::swap(m[k][j], m[p][j]);
    for (int i = k + 1; i < 4; ++i) {
      const T f = m[i][k] / m[k][k];
      for (int j = k; j < 5; ++j) m[i][j] -= f * m[k][j];
    }
  }
  for (int i = 3; i >= 0; --i) {
    T s = m[i][4];
    for (int j = i + 1; j < 4; ++j) s -= m[i][j] * x[j];
    x[i] = s / m[i][i];
  }
  return true;
}

/// eliminate() and one step of iterative refinement in T: x += A^-1 (b - A x). Elimination alone
/// is backward stable only relative to |L| |U|, which pivoting can fill in where A has zeros: a
/// perspective matrix with a tiny M33 (reversed Z, far plane 2e7 away) and a plane far out gave
/// C'_y = 0.3 a relative error of 7 in float (the far corner on the wrong side, near' = -C). One
/// refinement step makes the solve componentwise backward stable (Skeel, 1980; Higham, Accuracy
/// and Stability of Numerical Algorithms, section 12.2), the error the checker's bounds allow.
template <class T>
bool solve(const T (&a)[16], bool transpose, const T (&b)[4], T (&x)[4]) {
  if (!eliminate(a, transpose, b, x)) return false;
  T r[4], d[4];
  for (int i = 0; i < 4; ++i) {
    T ax = 0;
    for (int j = 0; j < 4; ++j) ax += (transpose ? a[4 * j + i] : a[4 * i + j]) * x[j];
    r[i] = b[i] - ax;
  }
  if (!eliminate(a, transpose, r, d)) return false;
  for (int i = 0; i < 4; ++i) x[i] += d[i];
  return true;
}

/// Skeel's condition number || |A^-1| |A| ||_inf from the computed inverse; +inf when singular.
template <class T>
T skeel_condition(const T (&a)[16]) {
  T inverse[16];
  for (int j = 0; j < 4; ++j) {
    T e[4] = {0, 0, 0, 0}, column[4];
    e[j] = 1;
    if (!solve(a, false, e, column)) return std::numeric_limits<T>::infinity();
    for (int i = 0; i < 4; ++i) inverse[4 * i + j] = column[i];
  }
  T worst = 0;
  for (int i = 0; i < 4; ++i) {
    T row = 0;
    for (int k = 0; k < 4; ++k) {
      T abs_a_row_sum = 0;
      for (int j = 0; j < 4; ++j) abs_a_row_sum += std::abs(a[4 * k + j]);
      row += std::abs(inverse[4 * i + k]) * abs_a_row_sum;
    }
    worst = std::max(worst, row);
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<T>::infinity();
}

/// The oblique modification (Lengyel's method for any invertible M and any depth convention):
///   C' = M^-T C,  Q' = the corner of the clip volume that maximises C' . Q',  Q = M^-1 Q',
///   a = (z_far - z_near range) / (C . Q),  near(M') = a C,  rows 1, 2, 4 unchanged.
/// Returns the status code; on "ok", `out` is M'.
template <class T>
std::string oblique(const T (&m)[16], const T (&c_in)[4], const std::string& convention,
                    Mistake mistake, T (&out)[16]) {
  const bool guards = mistake != Mistake::no_statuses;
  for (int i = 0; i < 16; ++i) out[i] = m[i];  // what an engine without statuses keeps
  for (T v : m) {
    if (guards && !std::isfinite(v)) return "invalid_input";
  }
  for (T v : c_in) {
    if (guards && !std::isfinite(v)) return "invalid_input";
  }
  // A matrix this close to singular has no trustworthy inverse in T.
  if (guards && skeel_condition(m) >= T(1) / (128 * std::numeric_limits<T>::epsilon()))
    return "singular_projection";
  if (!has_no_camera_guard(mistake) && !(c_in[3] < 0)) return "camera_not_behind_plane";
  // The numerical route reversed_z_through_zero_one: one routine for [0, 1] depth, reversed Z
  // turned into it (row 3 M_4 - M_3) and back (M'_3 = M_4 - the [0, 1] answer's row 3).
  if (mistake == Mistake::reversed_z_through_zero_one && convention == "reversed_z") {
    T zero_one[16], answer[16];
    for (int i = 0; i < 16; ++i) zero_one[i] = m[i];
    for (int j = 0; j < 4; ++j) zero_one[8 + j] = m[12 + j] - m[8 + j];
    const std::string status = oblique(zero_one, c_in, "zero_one", Mistake::none, answer);
    if (status != "ok") return status;
    for (int j = 0; j < 4; ++j) out[8 + j] = m[12 + j] - answer[8 + j];
    return "ok";
  }
  // a C does not change when C is scaled, so bring a very tiny or very huge C to magnitude about
  // 1 by a power of two first (C . Q would underflow or overflow). Only then: scaling down an
  // ordinary C would push a subnormal component further down and lose its bits.
  T largest = 0;
  for (T v : c_in) largest = std::max(largest, std::abs(v));
  if (largest == 0) return "camera_not_behind_plane";
  const int e = std::ilogb(largest);
  const int shift = std::abs(e) > std::numeric_limits<T>::max_exponent / 4 ? -e : 0;
  T c[4];
  for (int i = 0; i < 4; ++i) c[i] = std::ldexp(c_in[i], shift);
  T c_clip[4], q[4];
  // The mistake ignores_shift: portal math written for a centred camera, M14 = M24 = 0.
  T solved[16];
  for (int i = 0; i < 16; ++i) solved[i] = m[i];
  if (mistake == Mistake::ignores_shift) solved[3] = solved[7] = 0;
  if (!solve(solved, true, c, c_clip)) return guards ? "singular_projection" : "ok";
  // The mistake zero_one_factor_on_gl: the [0, 1] formulas (z in [0, 1], M'_3 = a C) on gl.
  const bool as_zero_one =
      convention == "zero_one" || (convention == "gl" && mistake == Mistake::zero_one_factor_on_gl);
  const T z_low = convention == "gl" && !as_zero_one ? T(-1) : T(0), z_high = 1;
  const T sz = sgn(c_clip[2], mistake);
  // The mistake ignores_m11_sign: the engine's fast path for its perspective matrices writes
  // sgn(C'_x) as sgn(C_x), true while M11 > 0 (it knew of Vulkan's y flip, so y is right).
  const bool x_from_c = mistake == Mistake::camera_space_signs ||
                        (mistake == Mistake::ignores_m11_sign && perspective_shape(m));
  const T sx = sgn(x_from_c ? c[0] : c_clip[0], mistake);
  const T sy = sgn(mistake == Mistake::camera_space_signs ? c[1] : c_clip[1], mistake);
  const T corner[4] = {sx, sy, sz > 0 ? z_high : (sz < 0 ? z_low : (z_low + z_high) / 2), 1};
  if (!solve(solved, false, corner, q)) return guards ? "singular_projection" : "ok";
  const T d = c[0] * q[0] + c[1] * q[1] + c[2] * q[2] + c[3] * q[3];
  // Written as engines write it: a NaN d (from a NaN sign) passes this test.
  if (guards && d <= 0) return "plane_misses_view_volume";
  T a = (z_high - z_low) / d;
  // The numerical route far_corner_as_point: the corner unprojected to a point, Q / Q_w.
  if (mistake == Mistake::far_corner_as_point) {
    T point[4], m4q = 0, cq = 0;
    for (int i = 0; i < 4; ++i) point[i] = q[i] / q[3];
    for (int i = 0; i < 4; ++i) {
      m4q += m[12 + i] * point[i];
      cq += c[i] * point[i];
    }
    a = (z_high - z_low) * m4q / cq;
  }
  for (int i = 0; i < 16; ++i) out[i] = m[i];
  // Near plane: gl M_4 + M_3 = a C; zero_one M_3 = a C; reversed_z M_4 - M_3 = a C.
  for (int j = 0; j < 4; ++j) {
    const T ac = a * c[j], m4 = m[12 + j];
    out[8 + j] = convention == "reversed_z" ? m4 - ac : (as_zero_one ? ac : ac - m4);
  }
  if (guards && !has_sign_by_division(mistake)) {
    for (T v : out) {
      if (!std::isfinite(v)) return "out_of_range";
    }
    // The near plane the rasterizer will extract from M' (gl M'_4 + M'_3, zero_one M'_3,
    // reversed_z M'_4 - M'_3) must still keep C's side: where a C is lost against M_4 in the
    // subtraction (it is below M_4's rounding) it vanishes, and nothing would be clipped.
    T kept = 0;
    for (int j = 0; j < 4; ++j) {
      const T m3 = out[8 + j], m4 = out[12 + j];
      const T n = convention == "reversed_z" ? m4 - m3 : (as_zero_one ? m3 : m4 + m3);
      kept += n * c[j];
    }
    if (!(kept > 0)) return "out_of_range";
  }
  return "ok";
}

/// A request number: a JSON number, or "nan", "inf", "-inf".
inline double number(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>();
  const std::string s = v.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  return std::numeric_limits<double>::quiet_NaN();
}

/// Round-trip text of a value; the protocol's strings for non-finite values.
template <class T>
std::string text(T v) {
  if (std::isnan(v)) return "\"nan\"";
  if (std::isinf(v)) return v > 0 ? "\"inf\"" : "\"-inf\"";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", static_cast<double>(v));
  return buffer;
}

template <class T>
std::string answer(const std::string& line, Mistake mistake) {
  const nlohmann::json request = nlohmann::json::parse(line, nullptr, false);
  if (request.is_discarded() || !request.contains("projection") || !request.contains("plane"))
    return "{\"status\": \"invalid_input\"}";
  T m[16], c[4], out[16];
  for (int i = 0; i < 16; ++i) m[i] = static_cast<T>(number(request["projection"][i]));
  for (int i = 0; i < 4; ++i) c[i] = static_cast<T>(number(request["plane"][i]));
  const std::string convention = request.value("convention", "gl");
  const std::string status = oblique(m, c, convention, mistake, out);
  if (status != "ok") return "{\"status\": \"" + status + "\"}";
  std::string s = "{\"status\": \"ok\", \"projection\": [";
  for (int i = 0; i < 16; ++i) s += (i ? ", " : "") + text(out[i]);
  return s + "]}";
}

int serve(int argc, char** argv, Mistake mistake) {
  const bool in_float = argc > 1 && std::strcmp(argv[1], "--float") == 0;
  std::string line;
  while (std::getline(std::cin, line)) {
    std::cout << (in_float ? answer<float>(line, mistake) : answer<double>(line, mistake))
              << std::endl;
  }
  return 0;
}

}  // namespace lengyel
