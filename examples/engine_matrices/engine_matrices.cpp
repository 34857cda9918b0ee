// The idioms of engine_matrices.h. Each is written as an engine writes it: float, its own storage
// read by index, a closed form where the engine has one. M(r, c) below is the column-vector
// matrix's entry (1-based in the comments, as the papers print it); in the 16 numbers of either
// storage it is m[4 (c - 1) + (r - 1)] (column-major stores M by columns; a row-vector engine
// stores R = M^T by rows: the same numbers). A row-vector engine's code reads R[i][j] = M(j+1,
// i+1).
#include "engine_matrices.h"

#include <cmath>
#include <utility>

namespace engine_matrices {
namespace {

float sgn(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}

float dot4(const float a[4], const float b[4]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/// A row-vector engine's view of its 16 numbers: R[i][j], R = M^T.
using Rows = float (*)[4];
Rows rows(float m[16]) {
  return reinterpret_cast<Rows>(m);
}

// --- OpenGL, column-major, right-handed: the printed listing ------------------------------------
// On the perspective shape C' = (C_x / M11, C_y / M22, ...), so the far corner's clip signs are
// sgn(C_x) sgn(M11) and sgn(C_y) sgn(M22); Q = M^-1 (s_x, s_y, 1, 1) = ((s_x + M13) / M11,
// (s_y + M23) / M22, -1, (1 + M33) / M34); row 3 = a C - M_4 = a C + (0, 0, 1, 0), a = 2 / (C . Q).
// `clip_signs` false: the signs read from C itself, as the listing prints them (right only while
// M11 > 0 and M22 > 0).
void gl_listing_with(float m[16], const float c[4], bool clip_signs) {
  const float sx = clip_signs ? sgn(c[0]) * sgn(m[0]) : sgn(c[0]);
  const float sy = clip_signs ? sgn(c[1]) * sgn(m[5]) : sgn(c[1]);
  const float q[4] = {(sx + m[8]) / m[0], (sy + m[9]) / m[5], -1.0f, (1.0f + m[10]) / m[14]};
  const float a = 2.0f / dot4(c, q);
  m[2] = a * c[0];
  m[6] = a * c[1];
  m[10] = a * c[2] + 1.0f;
  m[14] = a * c[3];
}

void gl_listing(float m[16], const float c[4]) {
  gl_listing_with(m, c, true);
}
void gl_listing_wrong(float m[16], const float c[4]) {
  gl_listing_with(m, c, false);
}

// --- OpenGL, column-major: perspective and orthographic cameras ---------------------------------
// An engine with orthographic cameras too (shadow maps, top-down maps, editor views). The right
// one branches: the listing for the perspective shape, and for M_4 = (0, 0, 0, 1) C' = (C_x / M11,
// C_y / M22, C_z / M33), Q = M^-1 (s_x, s_y, s_z, 1) = ((s_x - M14) / M11, (s_y - M24) / M22,
// (s_z - M34) / M33, 1) on the face C'_z points to, row 3 = a C - M_4. The wrong one runs the
// listing on every camera.
bool orthographic(const float m[16]) {
  return m[3] == 0.0f && m[7] == 0.0f && m[11] == 0.0f && m[15] == 1.0f;
}

void gl_every_camera(float m[16], const float c[4]) {
  if (!orthographic(m)) {
    gl_listing_with(m, c, true);
    return;
  }
  const float sx = sgn(c[0]) * sgn(m[0]), sy = sgn(c[1]) * sgn(m[5]);
  const float sz = sgn(c[2]) * sgn(m[10]);
  const float q[4] = {(sx - m[12]) / m[0], (sy - m[13]) / m[5], (sz - m[14]) / m[10], 1.0f};
  const float a = 2.0f / dot4(c, q);
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = a * c[j] - m[4 * j + 3];
}
void gl_every_camera_wrong(float m[16], const float c[4]) {
  gl_listing_with(m, c, true);
}

// --- Direct3D style: row vectors, [0, 1], left-handed -------------------------------------------
// R = M^T by rows: R[0][0] = M11, R[2][0] = M13, R[1][1] = M22, R[2][1] = M23, R[2][2] = M33,
// R[3][2] = M34, R[2][3] = M43 = 1. Q = M^-1 (s_x, s_y, 1, 1) = ((s_x - M13) / M11,
// (s_y - M23) / M22, 1, (1 - M33) / M34); M's row 3 (R's column 2) = C / (C . Q).
// `off_axis` false: M13 and M23 left out (a symmetric frustum assumed), wrong on a leaning one.
void d3d_left_handed_with(float m[16], const float c[4], bool off_axis) {
  const Rows r = rows(m);
  const float sx = sgn(c[0]) * sgn(r[0][0]), sy = sgn(c[1]) * sgn(r[1][1]);
  const float m13 = off_axis ? r[2][0] : 0.0f, m23 = off_axis ? r[2][1] : 0.0f;
  const float q[4] = {(sx - m13) / r[0][0], (sy - m23) / r[1][1], 1.0f, (1.0f - r[2][2]) / r[3][2]};
  const float a = 1.0f / dot4(c, q);
  for (int i = 0; i < 4; ++i) r[i][2] = a * c[i];
}

void d3d_left_handed(float m[16], const float c[4]) {
  d3d_left_handed_with(m, c, true);
}
void d3d_left_handed_wrong(float m[16], const float c[4]) {
  d3d_left_handed_with(m, c, false);
}

// --- Direct3D style, the mirror pass: M11 negated ----------------------------------------------
// The engine's mirror pass negates M11 (R's column 0: M's row 1). Its oblique function undoes the
// flip, clips, and flips back: the view volume is the same, so is its far corner, and row 3 does
// not move. The wrong one scales C by 2 / (C . Q) on the mirror path only (OpenGL's factor, left
// from a port): a bug no camera but a mirror's shows.
void d3d_mirror_pass_with(float m[16], const float c[4], float mirror_factor) {
  const Rows r = rows(m);
  const bool mirrored = r[0][0] < 0.0f;
  if (mirrored) {
    for (int i = 0; i < 4; ++i) r[i][0] = -r[i][0];
  }
  const float sx = sgn(c[0]), sy = sgn(c[1]) * sgn(r[1][1]);
  const float q[4] = {(sx - r[2][0]) / r[0][0], (sy - r[2][1]) / r[1][1], 1.0f,
                      (1.0f - r[2][2]) / r[3][2]};
  const float a = (mirrored ? mirror_factor : 1.0f) / dot4(c, q);
  for (int i = 0; i < 4; ++i) r[i][2] = a * c[i];
  if (mirrored) {
    for (int i = 0; i < 4; ++i) r[i][0] = -r[i][0];
  }
}

void d3d_mirror_pass(float m[16], const float c[4]) {
  d3d_mirror_pass_with(m, c, 1.0f);
}
void d3d_mirror_pass_wrong(float m[16], const float c[4]) {
  d3d_mirror_pass_with(m, c, 2.0f);
}

// --- Vulkan style: column-major, [0, 1], right-handed, clip y flipped ---------------------------
// Q = M^-1 (s_x, s_y, 1, 1) = ((s_x + M13) / M11, (s_y + M23) / M22, -1, (1 + M33) / M34); row 3 =
// C / (C . Q). The projection's y flip (M22 < 0) flips C'_y: the wrong one reads s_y from C.
void vulkan_with(float m[16], const float c[4], bool clip_y) {
  const float sx = sgn(c[0]) * sgn(m[0]);
  const float sy = clip_y ? sgn(c[1]) * sgn(m[5]) : sgn(c[1]);
  const float q[4] = {(sx + m[8]) / m[0], (sy + m[9]) / m[5], -1.0f, (1.0f + m[10]) / m[14]};
  const float a = 1.0f / dot4(c, q);
  m[2] = a * c[0];
  m[6] = a * c[1];
  m[10] = a * c[2];
  m[14] = a * c[3];
}

void vulkan_y_flipped(float m[16], const float c[4]) {
  vulkan_with(m, c, true);
}
void vulkan_y_flipped_wrong(float m[16], const float c[4]) {
  vulkan_with(m, c, false);
}

// --- Direct3D style, reversed Z --------------------------------------------------------------
// Reversed Z keeps depth 1 at the near plane and 0 at the far one: M_4 - M_3 is the forward
// [0, 1] row 3, and the far face is z = 0. The right one modifies the matrix as it is:
// Q = M^-1 (s_x, s_y, 0, 1) = ((s_x - M13) / M11, (s_y - M23) / M22, 1, -M33 / M34), row 3 =
// M_4 - C / (C . Q). The wrong one takes its matrix forward (row 3 M_4 - M_3), runs its [0, 1]
// function and reverses again: a route through another convention, right in exact arithmetic,
// which in float adds M33's n / (f - n) to 1 and keeps only the bits 1 leaves it.
void d3d_reversed_z(float m[16], const float c[4]) {
  const Rows r = rows(m);
  const float sx = sgn(c[0]) * sgn(r[0][0]), sy = sgn(c[1]) * sgn(r[1][1]);
  const float q[4] = {(sx - r[2][0]) / r[0][0], (sy - r[2][1]) / r[1][1], 1.0f, -r[2][2] / r[3][2]};
  const float a = 1.0f / dot4(c, q);
  for (int i = 0; i < 4; ++i) r[i][2] = r[i][3] - a * c[i];
}
void d3d_reversed_z_wrong(float m[16], const float c[4]) {
  const Rows r = rows(m);
  for (int i = 0; i < 4; ++i) r[i][2] = r[i][3] - r[i][2];
  d3d_left_handed_with(m, c, true);
  for (int i = 0; i < 4; ++i) r[i][2] = r[i][3] - r[i][2];
}

// --- Vulkan style through the OpenGL code path --------------------------------------------------
// A [0, 1] engine (column-major, right-handed) that keeps one OpenGL code path: its matrix taken to
// OpenGL's range (row 3 2 M_3 - M_4), the OpenGL listing run there, row 3 brought back ((M'_3 +
// M_4) / 2). Right in exact arithmetic. The wrong one's OpenGL path has three slips of a port:
// the corner's signs from C, the frustum assumed symmetric, and [0, 1]'s factor 1 / (C . Q).
void through_gl_with(float m[16], const float c[4], bool slips) {
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = 2.0f * m[4 * j + 2] - m[4 * j + 3];
  const float sx = slips ? sgn(c[0]) : sgn(c[0]) * sgn(m[0]);
  const float sy = slips ? sgn(c[1]) : sgn(c[1]) * sgn(m[5]);
  const float m13 = slips ? 0.0f : m[8], m23 = slips ? 0.0f : m[9];
  const float q[4] = {(sx + m13) / m[0], (sy + m23) / m[5], -1.0f, (1.0f + m[10]) / m[14]};
  const float a = (slips ? 1.0f : 2.0f) / dot4(c, q);
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = a * c[j] - m[4 * j + 3];
  for (int j = 0; j < 4; ++j) m[4 * j + 2] = 0.5f * (m[4 * j + 2] + m[4 * j + 3]);
}

void vulkan_through_gl(float m[16], const float c[4]) {
  through_gl_with(m, c, false);
}
void vulkan_through_gl_wrong(float m[16], const float c[4]) {
  through_gl_with(m, c, true);
}

// --- OpenGL, column-major, every camera an engine builds: the inverse ---------------------------
// The general method as an engine with a matrix library writes it: C' = M^-T C, Q = M^-1 (s_x,
// s_y, s_z, 1) on the face C'_z points to, row 3 = a C - M_4, a = 2 / (C . Q) (solved in double,
// as the engine's math library does for an inverse). The wrong one reads the corner's x and y
// signs from C in camera space (right while C' keeps C's signs). It claims the cameras engines
// build (idioms.txt: not the family `general`): on a raw matrix whose rows differ by 10^14 this
// solve, refined once in double, still lost three digits of row 3 (the fuzz driver's finding),
// and such a matrix needs the core's solver (equilibrated, residuals in twice the precision).
/// A x = b (A^T x = b) by Gaussian elimination with partial pivoting; false at a zero pivot.
bool eliminate(const double a[4][4], bool transpose, const double b[4], double x[4]) {
  double s[4][5];
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) s[i][j] = transpose ? a[j][i] : a[i][j];
    s[i][4] = b[i];
  }
  for (int k = 0; k < 4; ++k) {
    int p = k;
    for (int i = k + 1; i < 4; ++i) {
      if (std::fabs(s[i][k]) > std::fabs(s[p][k])) p = i;
    }
    if (s[p][k] == 0.0) return false;
    for (int j = 0; j < 5; ++j) std::swap(s[k][j], s[p][j]);
    for (int i = k + 1; i < 4; ++i) {
      const double f = s[i][k] / s[k][k];
      for (int j = k; j < 5; ++j) s[i][j] -= f * s[k][j];
    }
  }
  for (int i = 3; i >= 0; --i) {
    double v = s[i][4];
    for (int j = i + 1; j < 4; ++j) v -= s[i][j] * x[j];
    x[i] = v / s[i][i];
  }
  return true;
}

/// eliminate() and one step of iterative refinement: partial pivoting alone is backward stable
/// only against the matrix's norm, and a projection whose rows differ in scale by 10^13 (a raw
/// matrix) then loses 13 digits; the refined solve is componentwise stable (Skeel 1980).
bool solve(const double a[4][4], bool transpose, const double b[4], double x[4]) {
  if (!eliminate(a, transpose, b, x)) return false;
  double r[4], dx[4];
  for (int i = 0; i < 4; ++i) {
    double ax = 0;
    for (int j = 0; j < 4; ++j) ax += (transpose ? a[j][i] : a[i][j]) * x[j];
    r[i] = b[i] - ax;
  }
  if (!eliminate(a, transpose, r, dx)) return false;
  for (int i = 0; i < 4; ++i) x[i] += dx[i];
  return true;
}

void gl_inverse_with(float m[16], const float c[4], bool clip_signs) {
  double a[4][4];
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) a[r][k] = m[4 * k + r];
  }
  const double plane[4] = {c[0], c[1], c[2], c[3]};
  double c_clip[4], q[4];
  if (!solve(a, true, plane, c_clip)) return;  // singular: left as it was
  auto sign = [](double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); };
  const double corner[4] = {clip_signs ? sign(c_clip[0]) : sign(plane[0]),
                            clip_signs ? sign(c_clip[1]) : sign(plane[1]), sign(c_clip[2]), 1.0};
  if (!solve(a, false, corner, q)) return;
  const double d = plane[0] * q[0] + plane[1] * q[1] + plane[2] * q[2] + plane[3] * q[3];
  const double scale = 2.0 / d;
  for (int k = 0; k < 4; ++k) m[4 * k + 2] = static_cast<float>(scale * plane[k] - a[3][k]);
}

void gl_inverse(float m[16], const float c[4]) {
  gl_inverse_with(m, c, true);
}
void gl_inverse_wrong(float m[16], const float c[4]) {
  gl_inverse_with(m, c, false);
}

}  // namespace

const std::vector<Idiom>& idioms() {
  static const std::vector<Idiom> all = {
      {"gl_listing", Storage::column_major, gl_listing, gl_listing_wrong},
      {"gl_every_camera", Storage::column_major, gl_every_camera, gl_every_camera_wrong},
      {"d3d_left_handed", Storage::row_vectors, d3d_left_handed, d3d_left_handed_wrong},
      {"d3d_mirror_pass", Storage::row_vectors, d3d_mirror_pass, d3d_mirror_pass_wrong},
      {"vulkan_y_flipped", Storage::column_major, vulkan_y_flipped, vulkan_y_flipped_wrong},
      {"d3d_reversed_z", Storage::row_vectors, d3d_reversed_z, d3d_reversed_z_wrong},
      {"vulkan_through_gl", Storage::column_major, vulkan_through_gl, vulkan_through_gl_wrong},
      {"gl_inverse", Storage::column_major, gl_inverse, gl_inverse_wrong},
  };
  return all;
}

const Idiom* find(const std::string& name, bool* wrong) {
  const std::string suffix = "_wrong";
  const bool twin = name.size() > suffix.size() &&
                    name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  const std::string stem = twin ? name.substr(0, name.size() - suffix.size()) : name;
  for (const Idiom& idiom : idioms()) {
    if (idiom.name == stem) {
      if (wrong) *wrong = twin;
      return &idiom;
    }
  }
  return nullptr;
}

}  // namespace engine_matrices
