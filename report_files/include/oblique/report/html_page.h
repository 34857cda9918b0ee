// A report's interactive page: one self-contained HTML file (no network: script, data and
// pictures inline) with the report's views in 3D to turn and zoom (WebGL2; a plain canvas where
// there is none), a toggle per layer, and the report's text and pictures beside them. A page
// opened with #selftest checks itself (each layer is seen in its colour, a toggle changes the
// picture) and writes the result into its #selftest element, for a headless browser to read.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "oblique/report/picture.h"
#include "oblique/report/views.h"

namespace oblique::report {

/// The page of `views` (each dataset a layer: its segments, its points as small crosses, in the
/// colour, width and dashes of its gnuplot style), beside `markdown` (shown as text) and
/// `pictures` (inline, with their captions).
std::string views_html(const Views& views, const std::string& markdown,
                       const std::vector<StagedPicture>& pictures);

/// The two ways a user's string (a surface's name, a path, a report's text) enters a page, each
/// the only one of its kind: as HTML text or an attribute's value (& < > " ' as entities), and as
/// JSON inside a <script> element (< > & as \u escapes, so no "</script>", "<!--" or "<script"
/// can end or change the element; U+2028 and U+2029 escaped too).
std::string html_escaped(std::string_view text);
std::string script_safe(std::string_view json);

}  // namespace oblique::report
