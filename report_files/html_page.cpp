#include "oblique/report/html_page.h"

#include <array>
#include <cstdlib>
#include <string_view>
#include <utility>
#include <vector>

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

/// `template_text` with each mark replaced by its text, the marks found in the template alone (a
/// value that holds a mark, a surface named "/*OBLIQUE_DATA*/", stays as it is).
std::string filled(const std::string& template_text,
                   const std::vector<std::pair<std::string, std::string>>& marks) {
  std::string out;
  std::size_t from = 0;
  for (;;) {
    std::size_t first = std::string::npos;
    const std::pair<std::string, std::string>* which = nullptr;
    for (const auto& m : marks) {
      const std::size_t at = template_text.find(m.first, from);
      if (at < first) {
        first = at;
        which = &m;
      }
    }
    if (!which) break;
    out.append(template_text, from, first - from);
    out += which->second;
    from = first + which->first.size();
  }
  out.append(template_text, from, std::string::npos);
  return out;
}

}  // namespace

std::string html_escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string script_safe(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    // '<', '>' and '&' occur in JSON only inside strings, where \u escapes mean the same.
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (c == '\xE2' && i + 2 < json.size() && json[i + 1] == '\x80' &&
               (json[i + 2] == '\xA8' || json[i + 2] == '\xA9')) {
      out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";  // line ends to older parsers
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

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
  return filled(kView3dPageTemplate, {{"<!--OBLIQUE_TITLE-->", html_escaped(views.title)},
                                      {"/*OBLIQUE_DATA*/", script_safe(data)},
                                      {"<!--OBLIQUE_REPORT-->", text}});
}

}  // namespace oblique::report
