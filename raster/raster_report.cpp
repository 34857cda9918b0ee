#include "oblique/raster/raster_report.h"

#include <cstdio>
#include <ostream>
#include <sstream>

#include "oblique/oblique.h"
#include "oblique/raster/case_scene.h"
#include "oblique/report/picture.h"

namespace oblique::raster {

std::string stage_flagged_section(report::ReportFiles& files, const std::string& stem,
                                  const Result& result, int size) {
  std::string md =
      "## The samples flagged\n\nThe first of each kind (sample j * size + i is pixel (i, j) "
      "from the bottom left; the band is what float32 shading of a correct answer cannot "
      "decide, docs/raster.md):\n\n| kind | pixel | point (camera space) | C . v | band "
      "|\n|---|---|---|---|---|\n";
  for (const Flag& f : result.examples) {
    char row[320];
    std::snprintf(row, sizeof row, "| %s | (%ld, %ld) | (%.9g, %.9g, %.9g) | %.17g | %.3g |\n",
                  std::string(flag_name(f.kind)).c_str(), f.sample % size, f.sample / size,
                  f.point.x(), f.point.y(), f.point.z(), f.c_dot, f.band);
    md += row;
  }
  // Where they are, over the frame as drawn: the pixels the renderer kept grey, the others
  // white, each flagged sample in its kind's colour (the frame's top row first). A sample is a
  // point at its own depth, so the flagged ones are spread like the samples; the picture of what
  // an engine would draw (stage_raster_finding()) shows the surfaces.
  struct Shown {
    Flag::Kind kind;
    std::uint32_t rgb;
    const char* title;
  };
  const Shown shown[] = {{Flag::Kind::drawn_behind_c, 0xd62728, "drawn behind C (red)"},
                         {Flag::Kind::clipped_kept, 0x1f77b4, "kept region clipped (blue)"},
                         {Flag::Kind::wrong_pixel, 0x2ca02c, "drawn into a wrong pixel (green)"}};
  const std::size_t pixels = static_cast<std::size_t>(size) * size;
  if (size > 0 && result.drawn_pixels.size() == pixels) {
    report::Picture frame(size, size, 0xffffffffu);
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        if (!result.drawn_pixels[static_cast<std::size_t>(size - 1 - y) * size + x]) continue;
        std::uint8_t* p = frame.at(x, y);
        p[0] = p[1] = p[2] = 190;
      }
    }
    std::string legend;
    for (const Shown& s : shown) {
      long n = 0;
      for (const auto& [sample, kind] : result.flagged) {
        if (kind != s.kind) continue;
        ++n;
        std::uint8_t* p =
            frame.at(static_cast<int>(sample % size), static_cast<int>(size - 1 - sample / size));
        p[0] = static_cast<std::uint8_t>(s.rgb >> 16);
        p[1] = static_cast<std::uint8_t>(s.rgb >> 8);
        p[2] = static_cast<std::uint8_t>(s.rgb);
      }
      if (n > 0)
        legend += std::string(legend.empty() ? "" : ", ") + s.title + ": " + std::to_string(n);
    }
    const std::string png = report::png_bytes(frame);
    if (!png.empty()) {
      files.open(stem + ".pixels.png") << png;
      md += "\nThe frame as drawn (" + std::to_string(size) + " x " + std::to_string(size) +
            " pixels, one sample each: grey where the renderer kept it) with the flagged samples "
            "over it: " +
            legend + ".\n\n![the frame and the flagged samples](" + stem + ".pixels.png)\n";
    }
  }
  return md + "\n";
}

std::string stage_raster_finding(report::ReportFiles& files, const std::string& stem,
                                 const Result& result, int size, const Eigen::Matrix4d& m,
                                 const Eigen::Vector4d& c, const Eigen::Matrix4d& answer,
                                 Convention convention) {
  std::string md;
  const ObliqueResult<double> core = apply<double>(m, c, convention);
  if (core.status == Status::ok) {
    std::vector<report::StagedPicture> staged;
    report::RenderSummary summary;
    md += stage_case_renders(files, stem, m, c, core.projection, answer, convention, {}, staged,
                             summary);
  }
  return md + stage_flagged_section(files, stem, result, size);
}

}  // namespace oblique::raster
