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

/// Pictures one above the other, the narrower ones centred.
Picture stacked(const std::vector<const Picture*>& pictures,
                std::uint32_t background = 0xffffffffu);

}  // namespace oblique::report
