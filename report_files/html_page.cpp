#include "oblique/report/html_page.h"

#include <array>
#include <cstdlib>
#include <string_view>

#include "oblique/protocol/json.h"
#include "oblique/protocol/numbers.h"

namespace oblique::report {

/// html/view3d.html, compiled in (CMake writes it into view3d_html.cpp).
extern const char* const kView3dPageTemplate;

namespace {

/// A gnuplot style's colour (`lc rgb '#rrggbb'` or a few names), black when it names none.
std::array<int, 3> style_colour(const std::string& style) {
  const std::size_t at = style.find("rgb '");
  if (at == std::string::npos) return {0, 0, 0};
  const std::size_t end = style.find('\'', at + 5);
  const std::string name = style.substr(at + 5, end == std::string::npos ? 0 : end - at - 5);
  if (name.size() == 7 && name[0] == '#') {
    const long v = std::strtol(name.c_str() + 1, nullptr, 16);
    return {static_cast<int>((v >> 16) & 255), static_cast<int>((v >> 8) & 255),
            static_cast<int>(v & 255)};
  }
  struct Named {
    std::string_view name;
    std::array<int, 3> rgb;
  };
  static constexpr Named kNamed[] = {{"red", {214, 39, 40}},      {"blue", {31, 119, 180}},
                                     {"green", {44, 160, 44}},    {"orange", {255, 127, 14}},
                                     {"grey", {127, 127, 127}},   {"gray", {127, 127, 127}},
                                     {"magenta", {227, 119, 194}}};
  for (const Named& n : kNamed)
    if (n.name == name) return n.rgb;
  return {0, 0, 0};
}

/// The number after `key` in a style ("lw 2"), or `otherwise`.
double style_number(const std::string& style, const std::string& key, double otherwise) {
  const std::size_t at = style.find(" " + key + " ");
  if (at == std::string::npos) return otherwise;
  return std::strtod(style.c_str() + at + key.size() + 2, nullptr);
}

std::string number(double x) {
  return std::isfinite(x) ? protocol::format_number(x) : "0";
}

std::string point(const Eigen::Vector3d& p) {
  return number(p.x()) + "," + number(p.y()) + "," + number(p.z());
}

/// JSON text safe inside a <script> element.
std::string script_safe(std::string text) {
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3)
    text.replace(at, 2, "<\\/");
  return text;
}

std::string html_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void replace_once(std::string& text, const std::string& mark, const std::string& with) {
  const std::size_t at = text.find(mark);
  if (at != std::string::npos) text.replace(at, mark.size(), with);
}

}  // namespace

std::string views_html(const Views& views, const std::string& markdown,
                       const std::vector<StagedPicture>& pictures) {
  std::string data =
      "{\"lo\":[" + point(views.lo) + "],\"hi\":[" + point(views.hi) + "],\"layers\":[";
  for (std::size_t i = 0; i < views.sets.size(); ++i) {
    const Dataset& d = views.sets[i];
    const std::array<int, 3> rgb = style_colour(d.style);
    data += (i ? "," : "") + std::string("{\"name\":") + protocol::json_string(d.title) +
            ",\"color\":[" + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) + "," +
            std::to_string(rgb[2]) + "],\"width\":" + number(style_number(d.style, "lw", 1)) +
            ",\"dashed\":" + (d.style.find(" dt ") != std::string::npos ? "true" : "false") +
            ",\"segments\":[";
    bool first = true;
    for (const Segment& s : d.segments) {
      if (!s.a.allFinite() || !s.b.allFinite()) continue;
      data += (first ? "[" : ",[") + point(s.a) + "," + point(s.b) + "]";
      first = false;
    }
    data += "],\"points\":[";
    first = true;
    for (const Eigen::Vector3d& p : d.points) {
      if (!p.allFinite()) continue;
      data += (first ? "[" : ",[") + point(p) + "]";
      first = false;
    }
    data += "]}";
  }
  data += "]}";
  std::string text = "<h1>" + html_escaped(views.title) + "</h1>\n";
  for (const StagedPicture& p : pictures) {
    text += "<figure><img alt=\"" + html_escaped(p.file) + "\" src=\"data:image/png;base64," +
            base64(p.png) + "\"><figcaption>" + html_escaped(p.caption) +
            "</figcaption></figure>\n";
  }
  // The report's text as it is, less its picture links (the pictures are above, inline).
  std::string kept;
  std::size_t from = 0;
  while (from < markdown.size()) {
    std::size_t end = markdown.find('\n', from);
    if (end == std::string::npos) end = markdown.size();
    const std::string line = markdown.substr(from, end - from);
    if (line.rfind("![", 0) != 0) kept += line + "\n";
    from = end + 1;
  }
  text += "<pre>" + html_escaped(kept) + "</pre>\n";
  std::string page = kView3dPageTemplate;
  replace_once(page, "<!--OBLIQUE_TITLE-->", html_escaped(views.title));
  replace_once(page, "/*OBLIQUE_DATA*/", script_safe(data));
  replace_once(page, "<!--OBLIQUE_REPORT-->", text);
  return page;
}

}  // namespace oblique::report
