// A matrix finding's renders as its report shows them (case_scene.h's stage_case_renders()).
#include <sstream>
#include <string>

#include "oblique/raster/case_scene.h"

namespace oblique::raster {

std::string stage_case_renders(report::ReportFiles& files, const std::string& stem,
                               const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                               const Eigen::Matrix4d& expected, const Eigen::Matrix4d& answer,
                               Convention convention, const std::vector<Eigen::Vector4d>& hints,
                               std::vector<report::StagedPicture>& staged,
                               report::RenderSummary& summary) {
  std::ostringstream md;
  md << "## What your engine would draw\n\n";
  const Expected<CaseRenders> renders = render_case(m, c, expected, answer, convention, hints);
  if (!renders) {
    summary.why = renders.error();
    md << "Not drawn: " << renders.error() << ".\n\n";
    return md.str();
  }
  // Each panel named above it: which is the right answer, which is yours, which the difference.
  auto three = [](const report::Picture& right, const report::Picture& yours,
                  const report::Picture& difference, const std::string& suffix) {
    const report::Picture a = report::labelled(right, "right answer" + suffix),
                          b = report::labelled(yours, "yours" + suffix),
                          d = report::labelled(difference, "difference" + suffix);
    return report::side_by_side({&a, &b, &d}, 8);
  };
  report::Picture row =
      three(renders->expected.colour, renders->answered.colour, renders->difference, "");
  // A zoom below its full view: the same three, around the mark whose difference is thin.
  for (const CaseRenders::Zoom& zoom : renders->zooms) {
    const report::Picture zoomed = three(
        zoom.expected, zoom.answered, zoom.difference,
        " (mark " + std::to_string(zoom.mark + 1) + ", x" + std::to_string(zoom.factor) + ")");
    const report::Picture gap(row.width, 8);
    row = report::stacked({&row, &gap, &zoomed});
  }
  const report::Picture right_depth = report::labelled(renders->expected_depth, "right answer"),
                        your_depth = report::labelled(renders->answered_depth, "yours");
  const report::Picture depths = report::side_by_side({&right_depth, &your_depth}, 8);
  const std::string render_png = report::png_bytes(row), depth_png = report::png_bytes(depths);
  if (render_png.empty() || depth_png.empty()) {
    summary.why = "the pictures could not be encoded as PNG";
    md << "Not drawn: " << summary.why << ".\n\n";
    return md.str();
  }
  summary.drawn = true;
  summary.differing_pixels = renders->differing;
  summary.marks = static_cast<int>(renders->mark_pixels.size());
  summary.marks_with_difference = renders->marks_with_difference();
  const std::string render_file = stem + ".render.png", depth_file = stem + ".depth.png";
  files.open(render_file) << render_png;
  files.open(depth_file) << depth_png;
  const std::string render_caption =
      "A reference scene in the case's eye space (a floor, pillars on both sides of C, a magenta "
      "marker at each place the answer and the correct M' disagree, ringed) drawn on llvmpipe: "
      "left through the correct M', middle through the answer, right the difference (" +
      std::to_string(renders->differing) + " pixels in red).";
  const std::string depth_caption =
      "The depth buffers (left: the correct M', right: the answer), near bright, on one scale.";
  staged.push_back({render_file, render_caption, render_png});
  staged.push_back({depth_file, depth_caption, depth_png});
  md << render_caption << " C is where the correct picture is cut: what is behind it is clipped.";
  for (const CaseRenders::Zoom& zoom : renders->zooms)
    md << " Below: zoomed x" << zoom.factor << " around mark " << zoom.mark + 1 << " ("
       << zoom.differing << " pixels differ there).";
  if (renders->unseen_marks > 0)
    md << " " << renders->unseen_marks
       << (renders->unseen_marks == 1 ? " further place disagrees" : " further places disagree")
       << " by less than a pixel even zoomed x64 (not marked).";
  if (renders->differing == 0)
    md << " **The two pictures are the same**: the answer clips what the correct M' clips to "
          "within a pixel here; the fault is in the numbers above (a far plane or a depth off by "
          "less than the picture resolves).";
  if (renders->marks.empty() && renders->differing > 0)
    md << " No point is clipped by one and kept by the other: what differs is where things land "
          "on the screen, or which is in front (the depths).";
  md << "\n\n![what the engine would draw](" << render_file << ")\n\n"
     << depth_caption << "\n\n![the depth buffers](" << depth_file << ")\n\n";
  return md.str();
}

}  // namespace oblique::raster
