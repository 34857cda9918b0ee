#include "oblique/raster/raster_report.h"

#include <cstdio>
#include <ostream>
#include <sstream>

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
  // Where they are: one block per kind, in pixels; each block starts with a point off the frame,
  // so that no block is empty (gnuplot refuses an empty index).
  struct Shown {
    Flag::Kind kind;
    const char* colour;
    const char* title;
  };
  const Shown shown[] = {{Flag::Kind::drawn_behind_c, "#d62728", "drawn behind C"},
                         {Flag::Kind::clipped_kept, "#1f77b4", "kept region clipped"},
                         {Flag::Kind::wrong_pixel, "#2ca02c", "drawn into a wrong pixel"}};
  std::ostream& dat = files.open(stem + ".pixels.dat");
  for (const Shown& s : shown) {
    dat << "# " << flag_name(s.kind) << "\n0 -1e9\n";
    for (const auto& [sample, kind] : result.flagged)
      if (kind == s.kind) dat << sample % size << " " << sample / size << "\n";
    dat << "\n\n";
  }
  std::ostream& gp = files.open(stem + ".pixels.gp");
  gp << "set terminal pngcairo size 800,800 noenhanced\nset output '" << stem
     << ".pixels.png'\nset title 'samples flagged on the rasterizer (" << size << " x " << size
     << " pixels)'\nset size ratio -1\nset xrange [0:" << size << "]\nset yrange [0:" << size
     << "]\nset xlabel 'pixel x'\nset ylabel 'pixel y'\nset key outside below\nplot ";
  for (int i = 0; i < 3; ++i) {
    gp << (i == 0 ? "'" + stem + ".pixels.dat'" : std::string(", ''")) << " index " << i
       << " with points pt 5 ps 0.3 lc rgb '" << shown[i].colour << "' title '" << shown[i].title
       << "'";
  }
  gp << "\n";
  std::ostringstream plot_log;
  if (files.plot_staged(stem + ".pixels.gp", stem + ".pixels.png", plot_log))
    md += "\n![where the flagged samples are](" + stem + ".pixels.png)\n";
  return md + "\n";
}

}  // namespace oblique::raster
