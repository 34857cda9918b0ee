// Pictures the reports render themselves (the rasterizer's frames of a case, the difference of
// two): RGBA pixels, written as PNG (libpng) into a report's files or inline into its HTML page.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace oblique::report {

/// RGBA, 8 bits a channel, rows from the top.
struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4

  Picture() = default;
  Picture(int w, int h, std::uint32_t fill = 0xffffffffu);
  std::uint8_t* at(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const std::uint8_t* at(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
};

/// A picture a report staged itself (STEM.render.png, ...): its file name in the report's folder,
/// what it shows, and its PNG bytes (for an HTML page to carry inline).
struct StagedPicture {
  std::string file, caption, png;
};

/// What a render of a finding shows, for its report's JSON ("render"): the pixels that differ
/// between the correct M''s picture and the answer's, and how many of the places where the two
/// disagree (each marked in the scene) have a differing pixel within 3 pixels of it.
struct RenderSummary {
  bool drawn = false;
  long differing_pixels = 0;
  int marks = 0, marks_with_difference = 0;
  std::string why;  ///< not drawn: why
};

/// The picture as PNG bytes; empty when libpng fails (or the picture is empty).
std::string png_bytes(const Picture& picture);

/// RFC 4648 base64 (for data: URLs).
std::string base64(std::string_view bytes);

/// Pictures side by side, `gap` pixels of `background` (0xRRGGBBAA) between them, the shorter
/// ones centred vertically.
Picture side_by_side(const std::vector<const Picture*>& pictures, int gap,
                     std::uint32_t background = 0xffffffffu);

/// The width in pixels of `text` lettered at `scale` (each character 6 scale wide, the last
/// without its space).
int lettering_width(std::string_view text, int scale);

/// `text` lettered into `picture` in `ink` (0xRRGGBBAA), its top left corner at (left, top): a 5 x
/// 7 capital font, each of its pixels drawn `scale` x `scale` (lowercase letters as capitals, a
/// character the font lacks as a box); what falls outside the picture is left out.
void letter(Picture& picture, std::string_view text, int left, int top, int scale,
            std::uint32_t ink = 0x202020ffu);

/// `picture` under a white strip with `label` lettered in it, centred: a panel's name in a row
/// of pictures ("right answer", "yours", "difference"). The strip is 11 `scale` pixels high; the
/// result is as wide as the picture, or as the label where that is wider.
Picture labelled(const Picture& picture, std::string_view label, int scale = 2);

/// Pictures one above the other, the narrower ones centred.
Picture stacked(const std::vector<const Picture*>& pictures,
                std::uint32_t background = 0xffffffffu);

}  // namespace oblique::report
