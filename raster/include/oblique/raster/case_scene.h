// What an engine would draw through a finding's matrix: a small reference scene in the case's eye
// space (a floor, pillars across M's view volume on both sides of C, and a marker at each place
// where the answer and the correct M' disagree about what is drawn), rendered on the rasterizer
// through the correct M' and through the answer, side by side with the difference marked and the
// depth buffers as pictures.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/expected.h"
#include "oblique/raster/gl_context.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/report/picture.h"
#include "oblique/report/report_files.h"

namespace oblique::raster {

/// Triangles in eye space, three vertices each (w = 1), each vertex with its RGBA colour; those
/// of `overlay` are drawn after the rest without the depth test (markers: seen wherever they are
/// not clipped).
struct Mesh {
  std::vector<Eigen::Vector4f> points, colors;
  std::vector<Eigen::Vector4f> overlay_points, overlay_colors;
};

/// Whether a matrix keeps the eye-space point p (homogeneous) in `convention`: its clip
/// coordinates within the clip volume (-w <= x, y <= w; z within [-w, w] for gl, [0, w] else).
bool keeps(const Eigen::Matrix4d& projection, const Eigen::Vector4d& p, Convention convention);

/// Points of M's view volume that `expected` and `answer` treat differently (one keeps, the other
/// clips): drawn from M's volume (NDC of M sampled, mapped back; more densely around each of
/// `hints`, the finding's points: the far corner, a vertex the answer clips), at most `count`,
/// spread apart, those the correct M' keeps first. Deterministic.
std::vector<Eigen::Vector4d> disagreements(const Eigen::Matrix4d& m,
                                           const Eigen::Matrix4d& expected,
                                           const Eigen::Matrix4d& answer, Convention convention,
                                           const std::vector<Eigen::Vector4d>& hints = {},
                                           int count = 4);

/// The reference scene for M (the original projection), C and `marks` (disagreements()): a
/// checkered floor along M's view axis, pillars from near to far spread across it (some straddle
/// C), and a small marker cube at each mark (in `overlay`).
Mesh reference_scene(const Eigen::Matrix4d& m, const Eigen::Vector4d& c, Convention convention,
                     const std::vector<Eigen::Vector4d>& marks);

/// One matrix's render: the colours (the background where nothing was drawn) and the depth
/// buffer read back (window depth; the cleared value where nothing was drawn).
struct Render {
  report::Picture colour;
  std::vector<float> depth;  ///< rows from the top, as `colour`
  float cleared = 1;         ///< the depth buffer's clear value (0 for reversed Z)
};

/// Draws `mesh` through `projection` in `convention` into a `size` x `size` frame with a
/// `buffer` depth buffer, as an engine would (glClipControl for [0, 1], reversed Z cleared to 0
/// with GL_GEQUAL); the error is one line (no EGL: what to install).
Expected<Render> draw_mesh(GlContext& gl, const Mesh& mesh, const Eigen::Matrix4d& projection,
                           Convention convention, DepthBuffer buffer, int size);

/// The side by side of a case: the correct M''s render, the answer's, and the difference (the
/// correct render dimmed, every pixel whose colour differs in red); the two depth buffers as grey
/// pictures on one scale (ranks of the depths drawn in either). Where a mark's difference is too
/// thin to see at full view, the same three zoomed in around it (`zooms`: x8, then x64).
struct CaseRenders {
  Render expected, answered;
  report::Picture difference, expected_depth, answered_depth;
  long differing = 0;                           ///< pixels whose colour differs
  std::vector<Eigen::Vector4d> marks;           ///< the disagreements marked in the scene
  std::vector<std::array<int, 2>> mark_pixels;  ///< where each mark is on screen (x, y from top)
  std::vector<bool> mark_shown;  ///< a differing pixel within 3 pixels of the mark, or its zoom's
  struct Zoom {
    int factor = 1;
    int mark = 0;  ///< the mark it is centred on
    report::Picture expected, answered, difference;
    long differing = 0;
  };
  std::vector<Zoom> zooms;
  /// Places where the two disagree by less than a pixel even zoomed x64: not marked.
  int unseen_marks = 0;
  int marks_with_difference() const {
    return static_cast<int>(std::count(mark_shown.begin(), mark_shown.end(), true));
  }
};

/// Renders the reference scene of (M, C) through `expected` and `answer` on the software
/// rasterizer (llvmpipe).
Expected<CaseRenders> render_case(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                                  const Eigen::Matrix4d& expected, const Eigen::Matrix4d& answer,
                                  Convention convention,
                                  const std::vector<Eigen::Vector4d>& hints = {}, int size = 320);

/// For a matrix finding's report: render_case() of (M, C) through the correct M' and the answer,
/// staged in `files` as STEM.render.png (the two renders and the difference, side by side) and
/// STEM.depth.png (the two depth buffers), added to `staged`; returns the report's Markdown
/// section "What your engine would draw", which says why there is no picture where none could be
/// drawn (no EGL, a matrix beyond float).
std::string stage_case_renders(report::ReportFiles& files, const std::string& stem,
                               const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                               const Eigen::Matrix4d& expected, const Eigen::Matrix4d& answer,
                               Convention convention, const std::vector<Eigen::Vector4d>& hints,
                               std::vector<report::StagedPicture>& staged,
                               report::RenderSummary& summary);

}  // namespace oblique::raster
