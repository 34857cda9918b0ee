// The panels' names on a report's pictures (report_files/lettering.cpp): a label is drawn, in
// the strip above its picture, with the font's ink where the font has it; the picture itself is
// left as it was.
#include <gtest/gtest.h>

#include <string_view>

#include "oblique/report/picture.h"

namespace {

using oblique::report::Picture;

/// Pixels of `p` in rows [top, bottom) that are not white.
long inked(const Picture& p, int top, int bottom) {
  long n = 0;
  for (int y = top; y < bottom; ++y) {
    for (int x = 0; x < p.width; ++x) {
      const std::uint8_t* c = p.at(x, y);
      if (c[0] != 0xff || c[1] != 0xff || c[2] != 0xff) ++n;
    }
  }
  return n;
}

TEST(Lettering, aLabelSitsAboveItsPictureAndLeavesThePictureAsItWas) {
  const Picture panel(40, 30, 0x3366ccffu);
  const Picture out = oblique::report::labelled(panel, "yours", 2);
  const int strip = 22;  // 7 rows of 2 pixels and 4 of padding above and below
  ASSERT_EQ(out.height, panel.height + strip);
  EXPECT_GT(inked(out, 0, strip), 0);
  for (int y = 0; y < panel.height; ++y) {
    for (int x = 0; x < panel.width; ++x) {
      const int left = (out.width - panel.width) / 2;
      for (int k = 0; k < 4; ++k) ASSERT_EQ(out.at(left + x, strip + y)[k], panel.at(x, y)[k]);
    }
  }
}

TEST(Lettering, theInkIsTheFontsAtItsScale) {
  // "I" has 11 pixels of ink in the 5 x 7 font; at scale 3 each is 9.
  Picture canvas(40, 40);
  oblique::report::letter(canvas, "I", 2, 2, 3);
  EXPECT_EQ(inked(canvas, 0, canvas.height), 11 * 9);
  // Lowercase is drawn as its capital.
  Picture lower(40, 40);
  oblique::report::letter(lower, "i", 2, 2, 3);
  EXPECT_EQ(lower.rgba, canvas.rgba);
}

TEST(Lettering, differentNamesLookDifferentAndAnUnknownCharacterIsABox) {
  const Picture panel(200, 10);
  const Picture right = oblique::report::labelled(panel, "right answer"),
                yours = oblique::report::labelled(panel, "yours         ");
  EXPECT_NE(right.rgba, yours.rgba);
  Picture box(20, 20);
  oblique::report::letter(box, "~", 0, 0, 1);
  EXPECT_EQ(inked(box, 0, box.height), 20);  // the box's outline: 5 + 5 + 2 x 5
}

TEST(Lettering, aLabelWiderThanItsPictureWidensTheStrip) {
  const Picture narrow(4, 4, 0x000000ffu);
  const Picture out = oblique::report::labelled(narrow, "difference", 1);
  EXPECT_EQ(out.width, oblique::report::lettering_width("difference", 1) + 4);
  EXPECT_EQ(oblique::report::lettering_width("difference", 1), 10 * 6 - 1);
}

}  // namespace
