// What a raster finding's report shows of its frame: the first flagged samples of each kind and
// a picture of where they all are. Shared by `oblique verify --rasterize`'s reports and the
// property suite's (oblique/testing/raster.h).
#pragma once

#include <string>

#include "oblique/raster/raster.h"
#include "oblique/report/report_files.h"

namespace oblique::raster {

/// Stages in `files` the picture of where the flagged samples of `result` are in its `size` x
/// `size` frame (STEM.pixels.dat, .gp and, with gnuplot, .png) and returns the Markdown section
/// "The samples flagged": a table of the first flags of each kind (pixel, camera-space point,
/// C . v, band) and the picture's link when it was drawn.
std::string stage_flagged_section(report::ReportFiles& files, const std::string& stem,
                                  const Result& result, int size);

}  // namespace oblique::raster
