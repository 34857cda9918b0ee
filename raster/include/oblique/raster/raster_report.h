// What a raster finding's report shows of its frame: the first flagged samples of each kind and
// a picture of where they all are. Shared by `oblique verify --rasterize`'s reports and the
// property suite's (oblique/testing/raster.h).
#pragma once

#include <string>

#include "oblique/raster/raster.h"
#include "oblique/report/report_files.h"

namespace oblique::raster {

/// Stages in `files` the picture of the `size` x `size` frame as drawn with the flagged samples of
/// `result` over it (STEM.pixels.png) and returns the Markdown section "The samples flagged": a
/// table of the first flags of each kind (pixel, camera-space point, C . v, band) and the
/// picture's link.
std::string stage_flagged_section(report::ReportFiles& files, const std::string& stem,
                                  const Result& result, int size);

/// A raster finding's pictures: what an engine would draw through the answer M' to (M, C) beside
/// the core's answer, with the difference (case_scene.h's stage_case_renders()), then
/// stage_flagged_section().
std::string stage_raster_finding(report::ReportFiles& files, const std::string& stem,
                                 const Result& result, int size, const Eigen::Matrix4d& m,
                                 const Eigen::Vector4d& c, const Eigen::Matrix4d& answer,
                                 Convention convention);

}  // namespace oblique::raster
